// libFuzzer target: the impact map's step. Input: bytes decoded (FuzzedDataProvider) into a
// model (law elastic | constant | veldep with or without the collapse rule; a, eps or c as
// decimals of up to 17 digits and exponents -30..30 or special values; triangle, sawtooth,
// asymmetric:R or a knot wall; either downward-sticking convention) and a start (a decimal
// phase or a knot; the wall's own velocity, a release-like velocity or the wall's plus a
// decimal). Parameters and starts the library refuses (validate: InputError) are skipped.
// Up to 8 steps of ImpactMap<double>::step are checked against the invariants of
// tests/fuzz_step/step_invariants.hpp, computed independently in MPFR, the same checks that
// bouncer-fuzz-step makes on random draws. Undecided steps end the chain (they are allowed);
// any other exception, and any violated invariant, aborts with the state, the parameters and
// a `bouncer orbit` command that reproduces the step.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bouncer/model/impact_map.hpp"
#include "step_invariants.hpp"

namespace {

using namespace bouncer;
using namespace bouncer::step_check;

// A decimal text: one of `special`, or up to 17 digits with a point and an exponent.
std::string decimal(FuzzedDataProvider& in, std::initializer_list<const char*> special) {
  if (in.ConsumeBool()) {
    const size_t i = in.ConsumeIntegralInRange<size_t>(0, special.size() - 1);
    return *(special.begin() + i);
  }
  const int digits = in.ConsumeIntegralInRange<int>(1, 17);
  std::string s;
  for (int i = 0; i < digits; ++i) s += static_cast<char>('0' + in.ConsumeIntegralInRange<int>(0, 9));
  const int point = in.ConsumeIntegralInRange<int>(0, digits);
  s.insert(s.begin() + point, '.');
  const int exponent = in.ConsumeIntegralInRange<int>(-30, 30);
  if (exponent != 0) s += "e" + std::to_string(exponent);
  return s;
}

std::string wall_text(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: return "triangle";
    case 1: return "sawtooth";
    case 2: return "asymmetric:0." + std::to_string(in.ConsumeIntegralInRange<int>(1, 999));
    default: break;
  }
  // 2..6 knots at 3-digit phases (the first at 0), heights -3.00 .. 3.00.
  const int n = in.ConsumeIntegralInRange<int>(2, 6);
  std::string text = "knots:";
  int phase = 0;
  for (int j = 0; j < n; ++j) {
    if (j > 0) phase += in.ConsumeIntegralInRange<int>(1, 200);
    if (phase > 999) break;
    const int h = in.ConsumeIntegralInRange<int>(-300, 300);
    char b[64];
    std::snprintf(b, sizeof b, "%s%d.%03d:%s%d.%02d", j ? "," : "", phase / 1000, phase % 1000, h < 0 ? "-" : "",
                  std::abs(h) / 100, std::abs(h) % 100);
    text += b;
  }
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  ModelSpec spec;
  InitialCondition ic;
  try {
    spec.law = parse_law("model", in.PickValueInArray({"elastic", "constant", "veldep"}));
    spec.a = parse_decimal("a", decimal(in, {"24", "1e9", "0.01", "0.5", "28.82", "8", "19"}));
    if (spec.law == Law::constant) spec.eps = parse_decimal("eps", decimal(in, {"0", "1", "0.5", "1e-9", "0.999999999", "0.9", "0.96", "0.25"}));
    if (spec.law == Law::veldep) {
      spec.c = parse_decimal("c", decimal(in, {"1000", "1e-3", "1e7", "1"}));
      spec.veldep_collapse = in.ConsumeBool();
    }
    spec.downward = in.ConsumeBool() ? DownwardSticking::paper : DownwardSticking::impact;
    spec.wall = parse_wall("wall", wall_text(in));
    validate(spec);
    // The start: a knot or a decimal phase; the wall's velocity there, a release-like
    // velocity (the larger of the two segments' at a knot), or above the wall's.
    const size_t n = spec.wall.knots.size();
    const bool at_knot = in.ConsumeBool();
    if (at_knot) ic.theta = spec.wall.knots[in.ConsumeIntegralInRange<size_t>(0, n - 1)];
    else ic.theta = parse_decimal("theta", "0." + std::to_string(in.ConsumeIntegral<uint32_t>()));
    const mpq_class u = wall_velocity_exact(spec.wall, ic.theta.value());
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
      case 0: ic.v = decimal_at_least(u); break;
      case 1: {
        const int j = wall_segment_exact(spec.wall, ic.theta.value());
        const size_t prev = static_cast<size_t>(j == 0 ? static_cast<int>(n) - 1 : j - 1);
        const mpq_class up = wall_velocity_exact(spec.wall, spec.wall.knots[prev].value());
        ic.v = decimal_at_least(up > u ? up : u);
        break;
      }
      default: {
        const mpq_class delta = parse_decimal("v", decimal(in, {"1e-12", "1e-6", "1", "4", "1e3", "1e12"})).value();
        ic.v = decimal_at_least(mpq_class(u + delta));
      }
    }
    validate(spec, ic, "theta", "v");
  } catch (const InputError&) {
    return -1;  // refused by the library's own validation: not an input of the map
  }
  const Model<double> model = make_model<double>(spec, 53);
  const ImpactMap<double> map(model);
  State<double> s;
  try {
    s = make_state(model, ic);
  } catch (const InputError&) {
    return -1;  // theta rounds to 1 in double
  }
  Rng rng(in.ConsumeIntegral<uint64_t>());  // the checker's sampled flight times
  // A sticking step's first collision is looked for in 20,000 periods (bouncer-fuzz-step: a
  // million), so that one input takes well under a second under ASan.
  Checker<double> checker(spec, model, 256, rng, 20000);
  const int chain = in.ConsumeIntegralInRange<int>(1, 8);
  for (int k = 0; k < chain; ++k) {
    std::optional<Violation> bad;
    StepResult<double> r;
    try {
      r = map.step(s);
      bad = checker.check(s, r);
    } catch (const Undecided&) {
      break;
    } catch (const std::exception& e) {
      bad = Violation{kException, e.what()};
    }
    if (bad) {
      std::fprintf(stderr,
                   "bouncer fuzz_step: PROPERTY VIOLATED at step %d: %s: %s\n  state: theta %s v %s%s\n"
                   "  reproduce: bouncer orbit %s --theta %s --v %s --steps 1\n",
                   k + 1, kInvariantNames[bad->what], bad->detail.c_str(), ScalarTraits<double>::to_string(s.theta).c_str(),
                   ScalarTraits<double>::to_string(s.v).c_str(), s.knot >= 0 ? " (at a knot)" : "", spec_options(spec).c_str(),
                   ScalarTraits<double>::to_string(s.theta).c_str(), ScalarTraits<double>::to_string(s.v).c_str());
      std::abort();
    }
    s = r.next;
  }
  return 0;
}
