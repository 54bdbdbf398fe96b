// Attractor types of orbits built to be fixed, periodic, sticking, unbounded, chaotic,
// quasiperiodic or effectively sticking, each label checked against an independent fact
// about the orbit (an analytic family, a direct count of sticking steps, an exact growth
// law, the sign of an exponent measured by orbit separation elsewhere).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <set>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "test_support.hpp"

using namespace bouncer;
using bouncer::test_support::spec;

namespace {

Classification run(const ModelSpec& m, double theta, double v, ClassifyOptions o = {}) {
  const ImpactMap<double> map(make_model<double>(m, 53));
  return classify(map, State<double>{theta, v}, o);
}

// Steps between two consecutive sticking steps, counted directly from the release state.
long sticking_gap(const ModelSpec& m) {
  const ImpactMap<double> map(make_model<double>(m, 53));
  State<double> s{0.5, 4};
  for (long k = 1; k < 100000; ++k) {
    const StepResult<double> r = map.step(s);
    if (r.kind == EventKind::sticking) return k;
    s = r.next;
  }
  return -1;
}

}  // namespace

TEST(Classify, Eq5FamilyIsFixed) {
  // a = 24, eps = 0.5: the family v* = 12, theta* in (1/6, 1/2); multipliers {1, 1/4}.
  const Classification c = run(spec(Law::constant, "24", "0.5"), 0.3, 11.5);
  EXPECT_EQ(c.cls, OrbitClass::fixed) << c.evidence;
  EXPECT_EQ(c.period, 1);
  EXPECT_NE(c.evidence.find("marginal"), std::string::npos) << c.evidence;
  // Same in MPFR.
  const ImpactMap<Mpfr> map(make_model<Mpfr>(spec(Law::constant, "24", "0.5"), 128));
  const Classification cm =
      classify(map, State<Mpfr>{ScalarTraits<Mpfr>::from_decimal("0.3", 128), ScalarTraits<Mpfr>::from_decimal("11.5", 128)}, {});
  EXPECT_EQ(cm.cls, OrbitClass::fixed) << cm.evidence;
}

TEST(Classify, PeriodicOrbits) {
  // Constant eps: a = 19, eps = 0.9 has a stable period-2 orbit near (0.168, 14.14).
  const Classification c2 = run(spec(Law::constant, "19", "0.9"), 0.17, 14.1);
  EXPECT_EQ(c2.cls, OrbitClass::periodic) << c2.evidence;
  EXPECT_EQ(c2.period, 2);
  EXPECT_NEAR(c2.lambda, std::log(0.9), 1e-9);  // |mu| = eps^2 over the period (measure identity)
  // Velocity-dependent, a = 20, c = 1000: a period-15 attractor.
  const Classification c15 = run(spec(Law::veldep, "20"), 0.1, 11);
  EXPECT_EQ(c15.cls, OrbitClass::periodic) << c15.evidence;
  EXPECT_EQ(c15.period, 15);
  EXPECT_LT(c15.lambda, 0);
}

TEST(Classify, StickingWithItsPeriod) {
  for (const char* a : {"30", "20", "35"}) {
    const ModelSpec m = spec(Law::constant, a, "0.3");
    const long k = sticking_gap(m);
    ASSERT_GT(k, 0);
    const Classification c = run(m, 0.3, 9);
    EXPECT_EQ(c.cls, OrbitClass::sticking) << c.evidence;
    EXPECT_EQ(c.period, k) << "a=" << a;
    EXPECT_TRUE(std::isinf(c.lambda) && c.lambda < 0);
  }
  // Strong dissipation: period-1 sticking from the release (1/2, 4).
  const Classification c1 = run(spec(Law::constant, "24", "0.1"), 0.5, 4);
  EXPECT_EQ(c1.cls, OrbitClass::sticking);
  EXPECT_EQ(c1.period, 1);
}

TEST(Classify, FermiAccelerationIsUnbounded) {
  // Elastic, a = 16, (1/4, 8): each flight lasts v/8 whole periods and each impact on the
  // rising wall adds 8, so v_n = 8(n+1) (exactly; to rounding here): linear growth, alpha = 1.
  const ImpactMap<double> map(make_model<double>(spec(Law::elastic, "16"), 53));
  State<double> s{0.25, 8};
  for (int n = 1; n <= 100; ++n) {
    s = map.step(s).next;
    ASSERT_NEAR(s.v, 8.0 * (n + 1), 1e-9);
    ASSERT_NEAR(s.theta, 0.25, 1e-9);
  }
  const Classification c = run(spec(Law::elastic, "16"), 0.25, 8);
  EXPECT_EQ(c.cls, OrbitClass::unbounded) << c.evidence;
  EXPECT_NEAR(c.alpha, 1, 0.05) << c.evidence;
}

TEST(Classify, ConstantRestitutionIsNeverUnbounded) {
  // eps = 0.96, a = 31 from the release state, 20000 quad steps, then a 500-step window with
  // no transient (what `bouncer sweep` asks): the running maximum of v still grows there, but
  // every orbit of constant eps < 1 enters the trapping region v <= 4(1+3eps)/(1-eps) = 388
  // (proofs/trapping_region), so the growth is a transient and must not read as unbounded.
  const ImpactMap<Quad> map(make_model<Quad>(spec(Law::constant, "31", "0.96"), 113));
  State<Quad> s = make_state<Quad>(map.model(), InitialCondition{*Decimal::parse("0.5"), *Decimal::parse("4")});
  double vmax = 0;
  for (int n = 0; n < 20000; ++n) {
    s = map.step(s).next;
    vmax = std::max(vmax, static_cast<double>(s.v));
  }
  EXPECT_LE(vmax, 388.0);
  ClassifyOptions o;
  o.transient = 0;
  o.steps = 500;
  const Classification c = classify(map, s, o);
  EXPECT_NE(c.cls, OrbitClass::unbounded) << c.evidence;
}

TEST(Classify, ChaoticAndQuasiperiodic) {
  // The velocity-dependent attractor at a = 27, c = 1000 (positive exponent confirmed by
  // orbit separation in test_lyapunov).
  const Classification ch = run(spec(Law::veldep, "27"), 0.3, 6);
  EXPECT_EQ(ch.cls, OrbitClass::chaotic) << ch.evidence;
  EXPECT_GT(ch.lambda, 0);
  // Near the elliptic elastic period-2 orbit of a = 16 (multipliers on the unit circle).
  ClassifyOptions o;
  o.transient = 1000;
  o.steps = 4000;
  const Classification q = run(spec(Law::elastic, "16"), 0.251, 44, o);
  EXPECT_EQ(q.cls, OrbitClass::quasiperiodic) << q.evidence;
  EXPECT_LT(std::fabs(q.lambda), 0.02);
}

// A short window must not make a chaotic orbit periodic. With steps = 128 and max-period 64,
// the shift q = 64 used to be "verified" over zero pairs of the window's second half, and the
// attractor at a = 27, c = 1000 came out periodic with period 64 (and every cell of a quick
// (a, c) scan periodic). Each q is now compared over at least one full period.
TEST(Classify, ShortWindowNeverCallsChaosPeriodic) {
  ClassifyOptions o;
  o.transient = 500;
  o.steps = 128;
  o.max_period = 64;
  o.recheck_factor = 0;
  const Classification c = run(spec(Law::veldep, "27"), 0.3, 6, o);
  EXPECT_NE(c.cls, OrbitClass::periodic) << c.evidence;
  EXPECT_NE(c.period, 64) << c.evidence;
  // A true period is still found in the same window: the eq. 5 fixed point.
  const Classification f = run(spec(Law::constant, "24", "0.5"), 0.3, 12, o);
  EXPECT_EQ(f.cls, OrbitClass::fixed) << f.evidence;
}

TEST(Classify, VelocityDependentChatterIsEffectiveSticking) {
  // c = 1: eps(w) = exp(-w^(3/5)) is small for every relative speed above ~1 and the
  // relative velocity then decays on a rising segment through ever shorter flights.
  const ModelSpec m = spec(Law::veldep, "14", "1", "1");
  const Classification c = run(m, 0.3, 6);
  EXPECT_EQ(c.cls, OrbitClass::effective_sticking) << c.evidence;
  // Independent look: in the window the relative speed on one segment keeps decreasing.
  const ImpactMap<double> map(make_model<double>(m, 53));
  State<double> s{0.3, 6};
  for (int i = 0; i < 5000; ++i) s = map.step(s).next;
  int decreasing = 0;
  double prev = INFINITY;
  for (int i = 0; i < 500; ++i) {
    const StepResult<double> r = map.step(s);
    const double rel = r.next.v - map.model().wall.velocity[r.segment];
    if (rel < prev) ++decreasing;
    prev = rel;
    s = r.next;
  }
  EXPECT_GT(decreasing, 400);
}

TEST(Classify, LongPeriodBeyondMaxPeriod) {
  // eps = 0.96, a = 28.82 (the paper's fig. bifurcation value): from (0.1, 10) the orbit
  // settles on a period-103 attractor, longer than max-period 64: found by the extended
  // search of contracting orbits, and confirmed by Newton on P^103 at 256 bits.
  const ModelSpec m = spec(Law::constant, "28.82", "0.96");
  const Classification c = run(m, 0.1, 10);
  ASSERT_EQ(c.cls, OrbitClass::periodic) << c.evidence;
  EXPECT_EQ(c.period, 103);
  const ImpactMap<double> map(make_model<double>(m, 53));
  State<double> s{0.1, 10};
  for (int i = 0; i < 20000; ++i) s = map.step(s).next;
  const Model<Mpfr> mm = make_model<Mpfr>(m, 256);
  const PeriodicOrbit<Mpfr> o = find_periodic(
      mm, 103, State<Mpfr>{ScalarTraits<Mpfr>::from_decimal(std::to_string(s.theta), 256),
                           ScalarTraits<Mpfr>::from_decimal(std::to_string(s.v), 256)});
  ASSERT_TRUE(o.converged) << o.note;
  EXPECT_EQ(o.minimal_period, 103);
  EXPECT_LT(o.multipliers.modulus(0), 1);
}

namespace {

double dist(const State<double>& x, const State<double>& y) {
  double dt = std::fabs(x.theta - y.theta);
  dt = std::min(dt, 1 - dt);
  return std::max(dt, std::fabs(x.v - y.v) / std::max(1.0, std::fabs(x.v)));
}

}  // namespace

TEST(Classify, TransientChaosIsRecheckedAndSettles) {
  // eps = 0.96, a = 28 from the release state (1/2, 4): the paper's window (5000 + 500)
  // sees a bounded aperiodic orbit with a positive exponent, but the orbit later falls onto
  // a stable period-2 orbit. Facts checked here by direct iteration, not by classify: no
  // period <= 64 in the window; period 2 from some step S on; the 2-cycle is a Newton
  // solution (256 bits) with |mu_1 mu_2| = eps^4 (det J = eps^2 (v0-u0)/(v1-u1) per step).
  const ModelSpec m = spec(Law::constant, "28", "0.96");
  const ImpactMap<double> map(make_model<double>(m, 53));
  std::vector<State<double>> orbit{{0.5, 4}};
  for (int n = 1; n <= 120000; ++n) orbit.push_back(map.step(orbit.back()).next);
  for (int q = 1; q <= 64; ++q) {
    double worst = 0;
    for (int n = 5250; n + q <= 5500; ++n) worst = std::max(worst, dist(orbit[n], orbit[n + q]));
    ASSERT_GT(worst, 1e-3) << "the window is periodic with q = " << q;
  }
  long S = 0;
  for (long n = 119990; n >= 5500; --n)
    if (dist(orbit[n], orbit[n + 2]) > 1e-9) { S = n + 1; break; }
  ASSERT_GT(S, 5500);
  ASSERT_LT(S, 100000);
  const Model<Mpfr> mm = make_model<Mpfr>(m, 256);
  const PeriodicOrbit<Mpfr> po = find_periodic(
      mm, 2, State<Mpfr>{ScalarTraits<Mpfr>::from_decimal(std::to_string(orbit[S + 10].theta), 256),
                         ScalarTraits<Mpfr>::from_decimal(std::to_string(orbit[S + 10].v), 256)});
  ASSERT_TRUE(po.converged) << po.note;
  EXPECT_EQ(po.minimal_period, 2);
  EXPECT_NEAR(po.multipliers.modulus(0) * po.multipliers.modulus(1), std::pow(0.96, 4), 1e-12);

  const Classification c = run(m, 0.5, 4);
  EXPECT_EQ(c.cls, OrbitClass::transient_chaos) << c.evidence;
  EXPECT_EQ(c.settled_class, OrbitClass::periodic);
  EXPECT_EQ(c.period, 2);
  EXPECT_EQ(c.settled_at, S) << c.evidence;
  EXPECT_NE(c.evidence.find("recheck 100000"), std::string::npos) << c.evidence;
  // The re-check off: the old label of the window alone.
  ClassifyOptions off;
  off.recheck_factor = 0;
  const Classification old = run(m, 0.5, 4, off);
  EXPECT_EQ(old.cls, OrbitClass::chaotic) << old.evidence;
  EXPECT_NE(old.evidence.find("recheck off"), std::string::npos) << old.evidence;

  // From (0.0375, 4.6) the window's exponent is within its error of 0 (quasiperiodic by the
  // window alone); in this dissipative map that is re-checked too, and the orbit is on the
  // same 2-cycle from a step found here directly.
  std::vector<State<double>> o2{{0.0375, 4.6}};
  for (int n = 1; n <= 120000; ++n) o2.push_back(map.step(o2.back()).next);
  long S2 = 0;
  for (long n = 119990; n >= 5500; --n)
    if (dist(o2[n], o2[n + 2]) > 1e-9) { S2 = n + 1; break; }
  ASSERT_GT(S2, 5500);
  auto on_cycle = [&](const State<double>& x) {
    double d = 1;
    for (const State<Mpfr>& p : po.points)
      d = std::min(d, dist(x, State<double>{ScalarTraits<Mpfr>::to_double(p.theta), ScalarTraits<Mpfr>::to_double(p.v)}));
    return d;
  };
  EXPECT_LT(on_cycle(o2[119000]), 1e-9);  // the same Newton 2-cycle as from the release state
  EXPECT_EQ(run(m, 0.0375, 4.6, off).cls, OrbitClass::quasiperiodic);
  const Classification q = run(m, 0.0375, 4.6);
  EXPECT_EQ(q.cls, OrbitClass::transient_chaos) << q.evidence;
  EXPECT_EQ(q.period, 2);
  EXPECT_EQ(q.settled_at, S2) << q.evidence;
}

TEST(Classify, StartOnAnUnstableOrbitIsPeriodic) {
  // Unstable orbits found by Newton at 256 bits (an independent code path), rounded to
  // double: velocity-dependent a = 27, c = 1000, period 2 (inside the chaotic attractor),
  // and constant eps = 0.96, a = 28, period 3. A start on them is periodic with their
  // period; a start 1e-7 away is carried off (not periodic).
  struct Case {
    ModelSpec m;
    long q;
    double theta, v;
  };
  for (const Case& k : {Case{spec(Law::veldep, "27"), 2, 0.886, 2.3}, Case{spec(Law::constant, "28", "0.96"), 3, 0.687, -0.597}}) {
    const Model<Mpfr> mm = make_model<Mpfr>(k.m, 256);
    const PeriodicOrbit<Mpfr> po = find_periodic(
        mm, k.q, State<Mpfr>{ScalarTraits<Mpfr>::from_decimal(std::to_string(k.theta), 256),
                             ScalarTraits<Mpfr>::from_decimal(std::to_string(k.v), 256)});
    ASSERT_TRUE(po.converged) << po.note;
    ASSERT_EQ(po.minimal_period, k.q);
    const double mu = po.multipliers.modulus(0);
    ASSERT_GT(mu, 1.5);
    const double th = static_cast<double>(ScalarTraits<Mpfr>::to_double(po.points[0].theta));
    const double v = static_cast<double>(ScalarTraits<Mpfr>::to_double(po.points[0].v));
    const Classification c = run(k.m, th, v);
    EXPECT_EQ(c.cls, OrbitClass::periodic) << c.evidence;
    EXPECT_EQ(c.period, k.q);
    EXPECT_NEAR(c.lambda, std::log(mu) / k.q, 1e-6);
    EXPECT_NE(c.evidence.find("unstable period-" + std::to_string(k.q)), std::string::npos) << c.evidence;
    const Classification off = run(k.m, th, v + 1e-7);
    EXPECT_EQ(off.evidence.find("start lies"), std::string::npos) << off.evidence;
    EXPECT_FALSE(off.cls == OrbitClass::periodic && off.period == k.q) << off.evidence;
  }
}

TEST(Classify, AcceleratorModeAndDiffusiveGrowth) {
  // The exact accelerating orbit of a = 16: theta_n = 1/4, v_n = 8(n + 1) (see
  // FermiAccelerationIsUnbounded): one branch, phases repeat every step, gain 8 per step.
  const Classification a = run(spec(Law::elastic, "16"), 0.25, 8);
  ASSERT_EQ(a.cls, OrbitClass::unbounded) << a.evidence;
  EXPECT_EQ(a.growth_kind, "accelerator") << a.evidence;
  EXPECT_EQ(a.accel_period, 1);
  EXPECT_NEAR(a.accel_gain, 8, 1e-6);
  EXPECT_NEAR(a.growth_rate, 8, 1e-6);
  EXPECT_EQ(a.branches, 1);
  // Elastic a = 19 from (0.8, 5): v grows like sqrt(n) with falls in between. Checked
  // directly: in the window, for every Q <= 64 some v_{i+Q} < v_i, so no accelerator mode.
  const ModelSpec m = spec(Law::elastic, "19");
  const Classification d = run(m, 0.8, 5);
  ASSERT_EQ(d.cls, OrbitClass::unbounded) << d.evidence;
  EXPECT_NE(d.growth_kind, "accelerator") << d.evidence;
  EXPECT_EQ(d.accel_period, 0);
  EXPECT_LT(d.alpha, 0.7);
  const ImpactMap<double> map(make_model<double>(m, 53));
  std::vector<State<double>> w{{0.8, 5}};
  for (int n = 1; n <= 5500; ++n) w.push_back(map.step(w.back()).next);
  for (int q = 1; q <= 64; ++q) {
    bool falls = false;
    for (int n = 5250; n + q <= 5500 && !falls; ++n) falls = w[n + q].v < w[n].v;
    EXPECT_TRUE(falls) << "q = " << q;
  }
}

TEST(Classify, AcceleratorStatisticsAreThoseAfterCapture) {
  // Elastic a = 18 from (0.1, 10), windows 20000 + 20000, at mpfr:256: the orbit wanders,
  // then is captured by an accelerator mode of period 33 (v_{n+33} - v_n = D for every n
  // after capture). By that definition the mean growth after capture is D/33 per step, and
  // the phases take at most 33 values to 0.01 (branches, not a filled circle). Measured over
  // the whole window, with the wander in it, the rate was 1.34 and the phases filled the
  // circle (issue 23).
  ClassifyOptions o;
  o.transient = 20000;
  o.steps = 20000;
  Precision p;
  p.kind = Precision::Kind::mpfr;
  p.bits = 256;
  const Classification c = classify_start(spec(Law::elastic, "18"), p, {parse_decimal("theta", "0.1"), parse_decimal("v", "10")}, o);
  ASSERT_EQ(c.cls, OrbitClass::unbounded) << c.evidence;
  ASSERT_EQ(c.growth_kind, "accelerator") << c.evidence;
  EXPECT_EQ(c.accel_period, 33) << c.evidence;
  EXPECT_NEAR(c.growth_rate, c.accel_gain / static_cast<double>(c.accel_period), 1e-3 * c.accel_gain) << c.evidence;
  EXPECT_GT(c.branches, 0) << c.evidence;
  EXPECT_LE(c.branches, c.accel_period) << c.evidence;
}

TEST(Classify, SameBehaviour) {
  Classification x, y;
  x.cls = y.cls = OrbitClass::periodic;
  x.period = y.period = 7;
  x.lambda = -0.1;
  y.lambda = -0.2;  // exponents and evidence are not the behaviour
  y.evidence = "other words";
  EXPECT_TRUE(same_behaviour(x, y));
  y.period = 3;
  EXPECT_FALSE(same_behaviour(x, y));
  y.period = 7;
  y.cls = OrbitClass::fixed;
  EXPECT_FALSE(same_behaviour(x, y));
  x.cls = y.cls = OrbitClass::unbounded;
  x.growth_kind = y.growth_kind = "accelerator";
  x.accel_period = 33;
  y.accel_period = 1;
  EXPECT_FALSE(same_behaviour(x, y));
  x.cls = y.cls = OrbitClass::transient_chaos;
  x.settled_class = OrbitClass::periodic;
  y.settled_class = OrbitClass::sticking;
  EXPECT_FALSE(same_behaviour(x, y));
}

TEST(Classify, BehaviourDifferenceNamesWhatDiffers) {
  Classification x, y;
  x.cls = y.cls = OrbitClass::periodic;
  x.period = y.period = 7;
  EXPECT_EQ(behaviour_difference(x, y), "");
  y.period = 3;
  EXPECT_EQ(behaviour_difference(x, y), "period");
  y.cls = OrbitClass::chaotic;
  EXPECT_EQ(behaviour_difference(x, y), "class");
  // Unbounded in both, period 0 in both: the growth says why they differ.
  x.cls = y.cls = OrbitClass::unbounded;
  x.period = y.period = 0;
  x.growth_kind = y.growth_kind = "accelerator";
  x.accel_period = 33;
  y.accel_period = 11;
  EXPECT_EQ(behaviour_difference(x, y), "accelerator period 33 vs 11");
  y.growth_kind = "irregular";
  y.accel_period = 0;
  EXPECT_EQ(behaviour_difference(x, y), "growth kind accelerator vs irregular");
  x.cls = y.cls = OrbitClass::transient_chaos;
  x.settled_class = OrbitClass::periodic;
  y.settled_class = OrbitClass::sticking;
  EXPECT_EQ(behaviour_difference(x, y), "settles on periodic vs sticking");
  // Never a comma (it is a CSV field as it stands).
  EXPECT_EQ(behaviour_difference(y, x).find(','), std::string::npos);
}

TEST(ClassifyChecked, DoublesQuasiperiodicAnswerIsAnArtefactThere) {
  // The case of issue 23: double calls the start quasiperiodic (it is never captured in
  // 40000 steps); mpfr:256 and mpfr:512 follow the exact orbit into the period-33
  // accelerator mode. The check must say that double's class is the artefact.
  ClassifyOptions o;
  o.transient = 20000;
  o.steps = 20000;
  const Precision dbl = parse_precision("precision", "double");
  const CheckedClassification r =
      classify_checked(spec(Law::elastic, "18"), dbl, {parse_decimal("theta", "0.1"), parse_decimal("v", "10")}, o, 256);
  EXPECT_EQ(r.result.cls, OrbitClass::quasiperiodic) << r.result.evidence;
  ASSERT_EQ(r.checks.size(), 2u);
  EXPECT_EQ(r.checks[0].precision.text(), "mpfr:256");
  EXPECT_EQ(r.checks[1].precision.text(), "mpfr:512");
  EXPECT_EQ(r.checks[0].result.accel_period, 33) << r.checks[0].result.evidence;
  EXPECT_EQ(r.verdict, PrecisionVerdict::artefact) << r.summary;
  EXPECT_NE(r.summary.find("artefact"), std::string::npos) << r.summary;
  EXPECT_NE(r.summary.find("period 33"), std::string::npos) << r.summary;
}

TEST(ClassifyChecked, AStableFixedPointAgreesAtOnce) {
  // a = 24, eps = 0.5: the eq. 5 family, fixed in every precision (Eq5FamilyIsFixed): one
  // check, which agrees.
  const Precision dbl = parse_precision("precision", "double");
  const CheckedClassification r =
      classify_checked(spec(Law::constant, "24", "0.5"), dbl, {parse_decimal("theta", "0.3"), parse_decimal("v", "11.5")}, {}, 64);
  EXPECT_EQ(r.result.cls, OrbitClass::fixed) << r.result.evidence;
  ASSERT_EQ(r.checks.size(), 1u);
  EXPECT_EQ(r.checks[0].precision.text(), "mpfr:106");  // max(64, 2 x 53)
  EXPECT_EQ(r.verdict, PrecisionVerdict::agrees) << r.summary;
}

// classify_many steps four orbits side by side; each orbit's classification must be what
// classify() gives it alone, bit for bit, whatever rule decides it: chaos re-checked (and
// still chaotic, or settled: transient chaos), periodic orbits, sticking, unbounded growth
// (elastic), the unstable fixed point at the start (rule 0), in double and in MPFR, and for a
// number of starts that is not a multiple of four.
namespace {
bool same_bits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }

template <class T>
void expect_many_equals_one(const ModelSpec& s, const std::vector<std::pair<double, double>>& starts, const ClassifyOptions& o,
                            long bits) {
  const ImpactMap<T> map(make_model<T>(s, bits));
  std::vector<State<T>> xs;
  for (const auto& [th, v] : starts)
    xs.push_back(make_state<T>(map.model(), {parse_decimal("theta", std::to_string(th)), parse_decimal("v", std::to_string(v))}));
  const std::vector<Classification> many = classify_many<T>(map, xs, o);
  ASSERT_EQ(many.size(), xs.size());
  for (size_t i = 0; i < xs.size(); ++i) {
    const Classification one = classify<T>(map, xs[i], o);
    const Classification& m = many[i];
    EXPECT_EQ(m.cls, one.cls) << i << ": " << one.evidence;
    EXPECT_EQ(m.period, one.period) << i;
    EXPECT_TRUE(same_bits(m.lambda, one.lambda)) << i << ": " << m.lambda << " vs " << one.lambda;
    EXPECT_EQ(m.evidence, one.evidence) << i;
    EXPECT_TRUE(same_bits(m.alpha, one.alpha)) << i;
    EXPECT_EQ(m.settled_class, one.settled_class) << i;
    EXPECT_EQ(m.settled_at, one.settled_at) << i;
    EXPECT_EQ(m.accel_period, one.accel_period) << i;
    EXPECT_EQ(m.growth_kind, one.growth_kind) << i;
    EXPECT_EQ(m.recheck_joined_at, one.recheck_joined_at) << i;
  }
}
}  // namespace

// Windows of 400 + 128 steps, periods up to 32, re-checked 20 x 400 steps later: the
// classify_many tests' options (short enough for the suite, long enough for every rule).
static ClassifyOptions short_windows() { return {.transient = 400, .steps = 128, .max_period = 32, .recheck_factor = 20}; }

TEST(ClassifyMany, EachOrbitAsAloneBitForBit) {
  ClassifyOptions o = short_windows();
  std::vector<std::pair<double, double>> grid;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) grid.push_back({0.1 + 0.3 * i, 6 + 5 * j});
  grid.push_back({0.5, 4});  // the release state
  grid.push_back({0.25, 12});
  // Chaos (re-checked), transient chaos and periodic windows: eps = 0.96, a = 28.82 and 31;
  // the veldep model's chaos at c = 1000, a = 27; sticking and fixed points at eps = 0.5, a = 24;
  // unbounded growth and quasiperiodic orbits of the elastic map at a = 18.
  std::set<OrbitClass> seen;
  for (const ModelSpec& s : {spec(Law::constant, "28.82", "0.96"), spec(Law::constant, "31", "0.96"),
                             spec(Law::veldep, "27", "1", "1000"), spec(Law::constant, "24", "0.5"),
                             spec(Law::elastic, "18")}) {
    expect_many_equals_one<double>(s, grid, o, 53);
    const ImpactMap<double> map(make_model<double>(s, 53));
    for (const auto& [th, v] : grid) seen.insert(classify<double>(map, State<double>{th, v}, o).cls);
  }
  // The cases cover the rules (else this test would not test them).
  for (OrbitClass c : {OrbitClass::chaotic, OrbitClass::sticking, OrbitClass::unbounded}) EXPECT_TRUE(seen.count(c)) << name(c);
  expect_many_equals_one<Mpfr>(spec(Law::constant, "28.82", "0.96"), {{0.1, 6}, {0.4, 11}, {0.7, 16}, {0.5, 4}, {0.2, 9}}, o, 80);
  expect_many_equals_one<double>(spec(Law::constant, "28.82", "0.96"), {}, o, 53);  // nothing to do
  // A step that cannot be taken (v = 1e200: its square overflows) in a group of four: that
  // orbit is undecided at its step, the other three go on as alone.
  const std::vector<std::pair<double, double>> odd = {{0.1, 6}, {0.2, 1e200}, {0.4, 11}, {0.7, 16}};
  expect_many_equals_one<double>(spec(Law::constant, "29.125", "0.96"), odd, o, 53);
  const ImpactMap<double> map(make_model<double>(spec(Law::constant, "29.125", "0.96"), 53));
  EXPECT_EQ(classify<double>(map, State<double>{0.2, 1e200}, o).cls, OrbitClass::undecided);
}

// The recurrence rule (RecheckRule::recurrence): on a chaotic attractor, the first two
// aperiodic starts run the whole re-check (R = 20 x 400 steps here: the set and its second
// confirmation), the 8th start allowed to join after them too (an audit), and the others stop where they
// have stayed 1000 steps in the cells those visited; every label is the full rule's. The
// velocity-dependent model at c = 1000, a = 27: its chaos is an attractor (exponent ~0.11 per
// collision at every precision, claims table).
namespace {
// The join step, checked against the evidence's words (the one fact in two forms).
long joined_after(const Classification& c) {
  const bool said = c.evidence.find("re-check by recurrence: after " + std::to_string(c.recheck_joined_at) + " further steps") !=
                    std::string::npos;
  EXPECT_EQ(said, c.recheck_joined_at > 0) << c.evidence;
  return c.recheck_joined_at > 0 ? c.recheck_joined_at : -1;
}
}  // namespace

TEST(ClassifyMany, RecurrenceStopsReChecksOnAKnownChaoticSetWithTheSameLabels) {
  ClassifyOptions o = short_windows();
  const long R = 20 * 400;
  const ImpactMap<double> map(make_model<double>(spec(Law::veldep, "27", "1", "1000"), 53));
  std::vector<State<double>> xs;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) xs.push_back({0.05 + 0.23 * i, 7 + 4.5 * j});
  o.recheck = RecheckRule::full;
  const std::vector<Classification> full = classify_many<double>(map, xs, o);
  o.recheck = RecheckRule::recurrence;
  const std::vector<Classification> rec = classify_many<double>(map, xs, o);
  ASSERT_EQ(full.size(), rec.size());
  std::vector<long> joined;  // per chaotic start, in order: its join step or -1
  for (size_t i = 0; i < xs.size(); ++i) {
    EXPECT_TRUE(same_behaviour(full[i], rec[i])) << i << ": " << full[i].evidence << " | " << rec[i].evidence;
    if (full[i].cls != OrbitClass::chaotic) continue;
    const long n = joined_after(rec[i]);
    joined.push_back(n);
    if (n < 0) {
      // A whole re-check: the full rule's evidence, word for word.
      EXPECT_EQ(rec[i].evidence, full[i].evidence) << i;
      continue;
    }
    // It stopped early, after at least the 1000 steps of the stay, and its window's exponent
    // is positive (its label is its own window's, not borrowed).
    EXPECT_GE(n, 1000) << rec[i].evidence;
    EXPECT_LE(n + 128, R) << rec[i].evidence;
    EXPECT_GT(rec[i].lambda, 0.01) << rec[i].evidence;
  }
  ASSERT_EQ(joined.size(), 12u) << "every start is on the chaotic attractor";
  // The first two make and confirm the set; of the next ones the eighth is an audit.
  EXPECT_EQ(joined[0], -1);
  EXPECT_EQ(joined[1], -1);
  for (size_t i = 2; i < joined.size(); ++i) EXPECT_EQ(joined[i] < 0, (i - 2) % 8 == 7) << i;
}

// Where a chaotic set is a long-lived transient (the veldep model at c = 650, a = 22.75: a
// start settles on the period-2 attractor anywhere from 10^4 to 10^5 steps after the paper's
// window), whole re-checks see orbits settle, every start that had joined is re-checked in
// full and none joins after: the labels are the full rule's, field for field (the settled
// runs skipped along their exact cycles included).
TEST(ClassifyMany, RecurrenceFallsBackToFullReChecksWhereAnOrbitSettles) {
  ClassifyOptions o;  // the paper's window: 5000 + 500, re-checked 100000 steps later
  o.recheck = RecheckRule::recurrence;
  std::vector<std::pair<double, double>> grid;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) grid.push_back({0.05 + 0.25 * i, 5 + 3 * j});
  const ModelSpec s = spec(Law::veldep, "22.75", "1", "650");
  expect_many_equals_one<double>(s, grid, o, 53);
  const ImpactMap<double> map(make_model<double>(s, 53));
  std::vector<State<double>> xs;
  for (const auto& [th, v] : grid) xs.push_back({th, v});
  long settled = 0;
  for (const Classification& c : classify_many<double>(map, xs, o)) {
    settled += c.cls == OrbitClass::transient_chaos && c.settled_at > 5500 + 10000;
    EXPECT_EQ(c.evidence.find("re-check by recurrence"), std::string::npos) << c.evidence;
    EXPECT_EQ(c.recheck_joined_at, 0) << c.evidence;
  }
  EXPECT_GE(settled, 2) << "the case is what it claims to be";
}

// In a conservative map (elastic; eps = 1) the recurrence rule does not apply: a sticky
// episode near an island looks quiet and chaos cannot settle, so every start runs the whole
// re-check, bit for bit as classify() alone.
TEST(ClassifyMany, RecurrenceRuleLeavesConservativeMapsAlone) {
  ClassifyOptions o = short_windows();
  o.recheck = RecheckRule::recurrence;
  std::vector<std::pair<double, double>> grid;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) grid.push_back({0.1 + 0.3 * i, 6 + 5 * j});
  expect_many_equals_one<double>(spec(Law::elastic, "18"), grid, o, 53);
  expect_many_equals_one<double>(spec(Law::constant, "18", "1"), grid, o, 53);
}

TEST(ClassifyMany, RecheckRuleNames) {
  for (RecheckRule r : {RecheckRule::full, RecheckRule::recurrence}) EXPECT_EQ(recheck_rule_named(name(r)), r);
  EXPECT_EQ(recheck_rule_named("Full"), std::nullopt);
  EXPECT_EQ(recheck_rule_named(""), std::nullopt);
  EXPECT_EQ(ClassifyOptions{}.recheck, RecheckRule::full);  // classify()'s labels, start by start
}

// Carrying an exactly recurring orbit along its cycle (ClassifyOptions::exact_cycles) gives
// what stepping gives, every field, bit for bit: periodic orbits of several periods, sticking
// (the last sticking step and release state are carried), the velocity-dependent model's
// attractors and transient chaos (settled during the re-check), in double and in MPFR.
TEST(ClassifyMany, ExactCyclesAreCarriedBitForBit) {
  const ClassifyOptions on{.transient = 3000, .steps = 256, .max_period = 64, .recheck_factor = 20, .recheck = RecheckRule::full};
  ClassifyOptions off = on;
  off.exact_cycles = false;
  std::vector<std::pair<double, double>> grid;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) grid.push_back({0.05 + 0.23 * i, 5 + 4 * j});
  std::set<OrbitClass> seen;
  for (const ModelSpec& s : {spec(Law::constant, "24", "0.5"), spec(Law::constant, "28.82", "0.96"),
                             spec(Law::constant, "14", "0.8"), spec(Law::veldep, "23.1", "1", "1000"),
                             spec(Law::veldep, "22.75", "1", "650")}) {
    const ImpactMap<double> map(make_model<double>(s, 53));
    std::vector<State<double>> xs;
    for (const auto& [th, v] : grid) xs.push_back({th, v});
    const std::vector<Classification> a = classify_many<double>(map, xs, on), b = classify_many<double>(map, xs, off);
    for (size_t i = 0; i < xs.size(); ++i) {
      EXPECT_EQ(a[i].cls, b[i].cls) << i << ": " << b[i].evidence;
      EXPECT_EQ(a[i].period, b[i].period) << i;
      EXPECT_TRUE(same_bits(a[i].lambda, b[i].lambda)) << i;
      EXPECT_EQ(a[i].evidence, b[i].evidence) << i;
      EXPECT_TRUE(same_bits(a[i].alpha, b[i].alpha)) << i;
      EXPECT_EQ(a[i].settled_class, b[i].settled_class) << i;
      EXPECT_EQ(a[i].settled_at, b[i].settled_at) << i;
      seen.insert(b[i].cls);
      // classify() alone carries too: the same as classify_many.
      const Classification one = classify<double>(map, xs[i], on);
      EXPECT_EQ(one.evidence, a[i].evidence) << i;
    }
  }
  for (OrbitClass c : {OrbitClass::sticking, OrbitClass::periodic, OrbitClass::chaotic})
    EXPECT_TRUE(seen.count(c)) << name(c) << ": the cases cover it";
  // MPFR: the orbit recurs exactly at its precision too.
  const ImpactMap<Mpfr> m(make_model<Mpfr>(spec(Law::constant, "24", "0.5"), 80));
  std::vector<State<Mpfr>> xs;
  for (const auto& [th, v] : grid)
    xs.push_back(make_state<Mpfr>(m.model(), {parse_decimal("theta", std::to_string(th)), parse_decimal("v", std::to_string(v))}));
  const std::vector<Classification> a = classify_many<Mpfr>(m, xs, on), b = classify_many<Mpfr>(m, xs, off);
  for (size_t i = 0; i < xs.size(); ++i) {
    EXPECT_EQ(a[i].evidence, b[i].evidence) << i;
    EXPECT_TRUE(same_bits(a[i].lambda, b[i].lambda)) << i;
  }
}
