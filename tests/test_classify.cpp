// Attractor types of orbits built to be fixed, periodic, sticking, unbounded, chaotic,
// quasiperiodic or effectively sticking, each label checked against an independent fact
// about the orbit (an analytic family, a direct count of sticking steps, an exact growth
// law, the sign of an exponent measured by orbit separation elsewhere).
#include <gtest/gtest.h>

#include <cmath>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/analysis/periodic.hpp"

using namespace bouncer;

namespace {

ModelSpec spec(Law law, const std::string& a, const std::string& eps = "1", const std::string& c = "1000") {
  ModelSpec m;
  m.law = law;
  m.a = parse_decimal("a", a);
  if (law == Law::constant) m.eps = parse_decimal("eps", eps);
  m.c = parse_decimal("c", c);
  m.wall = parse_wall("wall", "triangle");
  validate(m);
  return m;
}

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
