// bench_certify: the cost of certified answers (issue 3, items 1 and 7).
//
//   1. time to certify the sticking question at eps = 0.96, a = 28.82 from the release
//      state (the answer: never sticks, period-103 attractor, trapping-box proof);
//   2. bits needed and cost per certified step as the orbit grows, at eps = 0.96, a = 31
//      (a long chaotic transient): escalation 64, 128, ... until N steps are certified;
//   3. certified horizon per bit, naive interval boxes vs Lohner's QR mean-value form,
//      on both orbits;
//   4. certified periodic orbits (Krawczyk): an isolated orbit, a parameter range, a family
//      and the period-103 attractor of claim 9.
// Wall-clock timings on a shared machine: indicative only; nothing is asserted.
//
// Usage: bench_certify [--quick]
#include <cstdio>
#include <cstring>
#include <string>

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
  return 0;
}
