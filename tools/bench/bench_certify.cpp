// bench_certify: the cost of certified answers (issue 3, items 1 and 7).
//
//   1. time to certify the sticking question at eps = 0.96, a = 28.82 from the release
//      state (the answer: never sticks, period-103 attractor, trapping-box proof);
//   2. bits needed and cost per certified step as the orbit grows, at eps = 0.96, a = 31
//      (a long chaotic transient): escalation 64, 128, ... until N steps are certified;
//   3. certified horizon per bit, naive interval boxes vs Lohner's QR mean-value form,
//      on both orbits;
//   4. certified periodic orbits (Krawczyk): an isolated orbit, a parameter range, a family
//      and the period-103 attractor of claim 9;
//   5. the certified step per precision: the interval step (ImpactMap<S>) and the Lohner
//      step of the eps = 0.96, a = 28.82 orbit in interval:double and in MPFI at several
//      precisions, each as a ratio to the double step of the same orbit timed in the same
//      run (thread CPU time).
// Wall-clock timings on a shared machine: indicative only; nothing is asserted.
//
// Usage: bench_certify [--quick] [--json FILE] | --columns   (bench_record.hpp)

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench_record.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "bouncer/verify/periodic_certify.hpp"
#include "bouncer/verify/sticking.hpp"

using namespace bouncer;

namespace {

ModelSpec model(const char* a) {
  ModelSpec m;
  m.law = Law::constant;
  m.a = *Decimal::parse(a);
  m.eps = *Decimal::parse("0.96");
  m.wall = parse_wall("wall", "triangle");
  return m;
}

InitialCondition release() { return {*Decimal::parse("0.5"), Decimal::from_int(4)}; }

// Nanoseconds per step of `n` steps of the point or interval step from the release state
// (the orbit never sticks and never becomes undecided in this range; restarted if it does).
template <class T>
double step_ns(const ModelSpec& spec, long bits, long n) {
  const ImpactMap<T> map(make_model<T>(spec, bits));
  const State<T> start = make_state<T>(release(), bits);
  State<T> s = start;
  const double t0 = bench::thread_cpu_seconds();
  for (long i = 0; i < n; ++i) {
    try {
      s = map.step(s).next;
    } catch (const Undecided&) {
      s = start;
    }
  }
  return 1e9 * (bench::thread_cpu_seconds() - t0) / static_cast<double>(n);
}

template <class S>
double lohner_ns(const ModelSpec& spec, long bits, long n) {
  OrbitEnclosureOf<S> orbit(interval_model_of<S>(spec, bits), make_state<S>(release(), bits), EnclosureMethod::lohner);
  const double t0 = bench::thread_cpu_seconds();
  for (long i = 0; i < n; ++i) orbit.step();
  return 1e9 * (bench::thread_cpu_seconds() - t0) / static_cast<double>(n);
}

// The five tables: their columns (and text widths) in one place, for the text and the JSON.
struct Tables {
  bench::Table sticking{"sticking", "certify the sticking question at eps = 0.96, a = 28.82 (from (1/2, 4))",
                        {"max_steps", "outcome", "bits", "seconds", "statement"}, {-10, -14, -8, -10, -1}, {}, {}};
  bench::Table growth{"growth",
                      "bits needed and cost per certified step as the orbit grows (eps = 0.96, a = 31, Lohner)",
                      {"steps", "bits", "seconds", "us/step", "escalation (bits:steps certified)"},
                      {-8, -8, -12, -14, -1}, {}, {}};
  bench::Table horizon{"horizon", "certified horizon per bit: naive boxes vs Lohner (from (1/2, 4), eps = 0.96)",
                       {"a", "bits", "naive steps", "lohner steps", "ratio", "lohner s", "steps/bit"},
                       {-7, -6, -14, -14, -10, -14, -10}, {}, {}};
  bench::Table periodic{"periodic", "certified periodic orbits (Krawczyk, escalation from 64 bits)",
                        {"case", "outcome", "certified", "bits", "pieces", "seconds"}, {-44, -10, -9, -6, -8, -1}, {}, {}};
  bench::Table step{"step",
                    "the certified step per precision (eps = 0.96, a = 28.82 from (1/2, 4); thread CPU time)",
                    {"scalar", "interval step ns", "/double", "Lohner step ns", "/double"}, {-18, -16, -10, -16, -1}, {}, {}};
  std::vector<const bench::Table*> all() const { return {&sticking, &growth, &horizon, &periodic, &step}; }
};

void section(const char* number, const bench::Table& t) {
  std::printf("%s== %s. %s ==\n", *number == '1' ? "" : "\n", number, t.title.c_str());
  t.print_header();
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Run run = bench::Run::start("bench_certify", argc, argv);
  Tables t;
  if (run.columns_only) return run.print_columns(t.all());
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  if (argc > 2 || (argc > 1 && !quick)) {
    std::printf("usage: bench_certify [--quick] [--json FILE]\n       bench_certify --columns\n");
    return argc > 1 && std::strcmp(argv[1], "--help") == 0 ? 0 : 2;
  }
  run.print_provenance();

  section("1", t.sticking);
  for (long long n : quick ? std::vector<long long>{20000} : std::vector<long long>{20000, 100000}) {
    StickingQuestion q;
    q.model = model("28.82");
    q.max_steps = n;
    const StickingCertificate c = certify_sticking(q);
    t.sticking.add_and_print({std::to_string(n), name(c.outcome), std::to_string(c.bits), bench::fmt("%.3f", c.seconds),
                              describe(c, n)});
  }

  section("2", t.growth);
  const std::vector<long long> lengths =
      quick ? std::vector<long long>{1000, 4000} : std::vector<long long>{1000, 2000, 4000, 8000, 16000, 25000};
  for (long long n : lengths) {
    StickingQuestion q;
    q.model = model("31");
    q.max_steps = n;
    q.prove_attractor = false;
    q.schedule = EscalationSchedule{64, 4096};
    const StickingCertificate c = certify_sticking(q);
    std::string esc;
    double last = 0;
    for (const Attempt& a : c.attempts) {
      esc += std::string(esc.empty() ? "" : " ") + std::to_string(a.bits) + ":" + std::to_string(a.steps);
      last = a.seconds;
    }
    t.growth.add_and_print({std::to_string(n), std::to_string(c.bits), bench::fmt("%.3f", c.seconds),
                            bench::fmt("%.2f", 1e6 * last / static_cast<double>(n)), esc});
  }

  section("3", t.horizon);
  const long long cap = quick ? 20000 : 100000;
  for (const char* a : {"28.82", "31"}) {
    for (long bits : quick ? std::vector<long>{64, 256, 1024} : std::vector<long>{64, 128, 256, 512, 1024, 2048}) {
      const Horizon h0 = certified_horizon(model(a), release(), bits, EnclosureMethod::naive, cap);
      const Horizon h1 = certified_horizon(model(a), release(), bits, EnclosureMethod::lohner, cap);
      t.horizon.add_and_print({a, std::to_string(bits), std::to_string(h0.steps),
                               std::to_string(h1.steps) + (h1.reached_max ? "+" : ""),
                               bench::fmt("%.1f", static_cast<double>(h1.steps) / static_cast<double>(std::max(1LL, h0.steps))),
                               bench::fmt("%.3f", h1.seconds),
                               bench::fmt("%.2f", static_cast<double>(h1.steps) / static_cast<double>(bits))});
    }
  }
  t.horizon.notes.push_back("'+': the cap of " + std::to_string(cap) + " steps was reached, the horizon is longer.");
  std::printf("%s\n", t.horizon.notes.back().c_str());

  section("4", t.periodic);
  struct Case {
    const char* label;
    const char* eps;
    const char* a;
    long period;
    const char* theta;
    const char* v;
    const char* range_lo;
    const char* range_hi;
  };
  const Case cases[] = {
      {"eps 0.8, a 19, period 2 (unstable)", "0.8", "19", 2, "0.944", "-0.345", nullptr, nullptr},
      {"eps 0.8, a in [18.9, 19.1], period 2", "0.8", "19", 2, "0.944", "-0.345", "18.9", "19.1"},
      {"eps 0.5, a 24, eq. 5 family", "0.5", "24", 1, "0.3", "12", nullptr, nullptr},
      {"eps 0.96, a 28.82, period-103 attractor", "0.96", "28.82", 103, "0.30576639227782704", "43.55500361255162", nullptr,
       nullptr},
  };
  for (const Case& k : cases) {
    PeriodicQuestion q;
    ModelSpec m = model(k.a);
    m.eps = *Decimal::parse(k.eps);
    q.model = m;
    q.period = k.period;
    q.guess = InitialCondition{*Decimal::parse(k.theta), *Decimal::parse(k.v)};
    if (k.range_lo) {
      q.range = std::make_pair(Decimal::parse(k.range_lo)->value(), Decimal::parse(k.range_hi)->value());
      const PeriodicRangeReport r = certify_periodic_range(q);
      long bits = 0;
      for (const PeriodicPiece& p : r.pieces) bits = std::max(bits, p.cert.bits);
      t.periodic.add_and_print({k.label, "isolated", r.uncertified_length == 0 ? "yes" : "no", std::to_string(bits),
                                std::to_string(r.pieces.size()), bench::fmt("%.3f", r.seconds)});
    } else {
      const PeriodicCertificate c = certify_periodic(q);
      t.periodic.add_and_print({k.label, name(c.outcome), c.certified ? "yes" : "no", std::to_string(c.bits), "1",
                                bench::fmt("%.3f", c.seconds)});
    }
  }

  section("5", t.step);
  const long n = quick ? 2000 : 20000;
  const ModelSpec m = model("28.82");
  const double dbl = step_ns<double>(m, 53, n * 20);
  t.step.add_and_print({"double (point)", bench::fmt("%.1f", dbl), "1.00x", "-", "-"});
  auto row = [&](const char* label, double iv, double lo) {
    t.step.add_and_print({label, bench::fmt("%.1f", iv), bench::fmt("%.2fx", iv / dbl), bench::fmt("%.1f", lo),
                          bench::fmt("%.1fx", lo / dbl)});
  };
  row("interval:double", step_ns<DoubleInterval>(m, 53, n * 5), lohner_ns<DoubleInterval>(m, 53, n));
  for (long bits : quick ? std::vector<long>{64, 256} : std::vector<long>{53, 64, 128, 256, 1024})
    row(("interval:" + std::to_string(bits)).c_str(), step_ns<Mpfi>(m, bits, n), lohner_ns<Mpfi>(m, bits, n / 2));
  return run.finish(t.all()) ? 0 : 1;
}
