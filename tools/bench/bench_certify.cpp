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
// Usage: bench_certify [--quick]
#include <time.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

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

double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Nanoseconds per step of `n` steps of the point or interval step from the release state
// (the orbit never sticks and never becomes undecided in this range; restarted if it does).
template <class T>
double step_ns(const ModelSpec& spec, long bits, long n) {
  const ImpactMap<T> map(make_model<T>(spec, bits));
  const State<T> start = make_state<T>(release(), bits);
  State<T> s = start;
  const double t0 = thread_seconds();
  for (long i = 0; i < n; ++i) {
    try {
      s = map.step(s).next;
    } catch (const Undecided&) {
      s = start;
    }
  }
  return 1e9 * (thread_seconds() - t0) / static_cast<double>(n);
}

template <class S>
double lohner_ns(const ModelSpec& spec, long bits, long n) {
  OrbitEnclosureOf<S> orbit(interval_model_of<S>(spec, bits), make_state<S>(release(), bits), EnclosureMethod::lohner);
  const double t0 = thread_seconds();
  for (long i = 0; i < n; ++i) orbit.step();
  return 1e9 * (thread_seconds() - t0) / static_cast<double>(n);
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  if (argc > 1 && !quick) {
    std::printf("usage: bench_certify [--quick]\n");
    return std::strcmp(argv[1], "--help") == 0 ? 0 : 2;
  }

  std::printf("== 1. certify the sticking question at eps = 0.96, a = 28.82 (from (1/2, 4)) ==\n");
  std::printf("%-10s %-14s %-8s %-10s %s\n", "max_steps", "outcome", "bits", "seconds", "statement");
  for (long long n : quick ? std::vector<long long>{20000} : std::vector<long long>{20000, 100000}) {
    StickingQuestion q;
    q.model = model("28.82");
    q.max_steps = n;
    const StickingCertificate c = certify_sticking(q);
    std::printf("%-10lld %-14s %-8ld %-10.3f %s\n", n, name(c.outcome), c.bits, c.seconds, describe(c, n).c_str());
  }

  std::printf("\n== 2. bits needed and cost per certified step as the orbit grows (eps = 0.96, a = 31, Lohner) ==\n");
  std::printf("%-8s %-8s %-12s %-14s %s\n", "steps", "bits", "seconds", "us/step", "escalation (bits:steps certified)");
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
      esc += std::to_string(a.bits) + ":" + std::to_string(a.steps) + " ";
      last = a.seconds;
    }
    std::printf("%-8lld %-8ld %-12.3f %-14.2f %s\n", n, c.bits, c.seconds, 1e6 * last / static_cast<double>(n),
                esc.c_str());
  }

  std::printf("\n== 3. certified horizon per bit: naive boxes vs Lohner (from (1/2, 4), eps = 0.96) ==\n");
  std::printf("%-7s %-6s %-14s %-14s %-10s %-14s %-10s\n", "a", "bits", "naive steps", "lohner steps", "ratio",
              "lohner s", "steps/bit");
  const long long cap = quick ? 20000 : 100000;
  for (const char* a : {"28.82", "31"}) {
    for (long bits : quick ? std::vector<long>{64, 256, 1024} : std::vector<long>{64, 128, 256, 512, 1024, 2048}) {
      const Horizon h0 = certified_horizon(model(a), release(), bits, EnclosureMethod::naive, cap);
      const Horizon h1 = certified_horizon(model(a), release(), bits, EnclosureMethod::lohner, cap);
      std::printf("%-7s %-6ld %-14lld %-14s %-10.1f %-14.3f %.2f\n", a, bits, h0.steps,
                  (std::to_string(h1.steps) + (h1.reached_max ? "+" : "")).c_str(),
                  static_cast<double>(h1.steps) / static_cast<double>(std::max(1LL, h0.steps)), h1.seconds,
                  static_cast<double>(h1.steps) / static_cast<double>(bits));
    }
  }
  std::printf("('+': the cap of %lld steps was reached, the horizon is longer)\n", cap);

  std::printf("\n== 4. certified periodic orbits (Krawczyk, escalation from 64 bits) ==\n");
  std::printf("%-44s %-10s %-9s %-6s %-8s %s\n", "case", "outcome", "certified", "bits", "pieces", "seconds");
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
      std::printf("%-44s %-10s %-9s %-6ld %-8zu %.3f\n", k.label, "isolated", r.uncertified_length == 0 ? "yes" : "no", bits,
                  r.pieces.size(), r.seconds);
    } else {
      const PeriodicCertificate c = certify_periodic(q);
      std::printf("%-44s %-10s %-9s %-6ld %-8d %.3f\n", k.label, name(c.outcome), c.certified ? "yes" : "no", c.bits, 1,
                  c.seconds);
    }
  }

  std::printf("\n== 5. the certified step per precision (eps = 0.96, a = 28.82 from (1/2, 4); thread CPU time) ==\n");
  const long n = quick ? 2000 : 20000;
  const ModelSpec m = model("28.82");
  const double dbl = step_ns<double>(m, 53, n * 20);
  std::printf("%-18s %-16s %-10s %-16s %s\n", "scalar", "interval step ns", "/double", "Lohner step ns", "/double");
  std::printf("%-18s %-16.1f %-10s %-16s %s\n", "double (point)", dbl, "1.00x", "-", "-");
  auto row = [&](const char* label, double iv, double lo) {
    std::printf("%-18s %-16.1f %-10s %-16.1f %.1fx\n", label, iv, (std::to_string(iv / dbl).substr(0, 5) + "x").c_str(), lo,
                lo / dbl);
  };
  row("interval:double", step_ns<DoubleInterval>(m, 53, n * 5), lohner_ns<DoubleInterval>(m, 53, n));
  for (long bits : quick ? std::vector<long>{64, 256} : std::vector<long>{53, 64, 128, 256, 1024})
    row(("interval:" + std::to_string(bits)).c_str(), step_ns<Mpfi>(m, bits, n), lohner_ns<Mpfi>(m, bits, n / 2));
  return 0;
}
