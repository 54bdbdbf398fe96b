// Certified periodic orbits (verify/periodic_certify.hpp) against independent truth:
//   * closed forms: the eq. 5 family (corrected: v* = 4(1+eps)/(1-eps) at
//     a = 8(1+eps)/(p(1-eps)), multipliers 1 and eps^2) and the velocity-dependent fixed
//     points (v = ap/2 with a from the derived relation, docs/claims.md);
//   * an invariant the certifier never uses: for constant restitution the map contracts area
//     by eps^2 per impact and the relative-velocity factors telescope around a cycle, so
//     det DP^Q = eps^(2Q) on every period-Q impact orbit (1 for the elastic model);
//   * agreement between precisions: the enclosures contain an independent 256-bit Newton
//     orbit, and the double orbit at every parameter inside a certified range piece;
//   * hand-derived cases: the release state's period-1 sticking orbit.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <string>
#include <tuple>

#include "bouncer/analysis/periodic.hpp"
#include "bouncer/verify/accelerator.hpp"
#include "bouncer/verify/periodic_certify.hpp"

namespace bouncer {
namespace {

ModelSpec constant_model(const char* eps, const char* a) {
  ModelSpec m;
  m.law = Law::constant;
  m.eps = *Decimal::parse(eps);
  m.a = *Decimal::parse(a);
  m.wall = parse_wall("wall", "triangle");
  return m;
}

Mpfi interval(const Enclosure& e, long bits = 256) {
  Mpfi lo(bits), hi(bits);
  lo.set_decimal(e.lo);
  hi.set_decimal(e.hi);
  return hull(lo, hi);
}

bool contains(const Enclosure& e, const Mpfr& x) { return interval(e, x.bits() + 64).contains(x); }
// Does the enclosure contain the exact rational num/den?
bool contains_rational(const Enclosure& e, long num, long den) {
  const Mpfi x = interval(e, 512);
  Mpfi q(512);
  q = Mpfi(num, 512) / den;
  return x.contains(q);
}

TEST(CertifyPeriodic, Eq5FamilyIsCertifiedWithTheParameterAsUnknown) {
  // eps = 1/2, p = 1: a = 8 (3/2) / (1/2) = 24, v* = 4 (3/2) / (1/2) = 12, free theta in
  // (1/2 - 2p eps/(1+eps), 1/2) = (1/6, 1/2); multipliers 1 and eps^2 = 1/4.
  PeriodicQuestion q;
  q.model = constant_model("0.5", "24");
  q.period = 1;
  q.guess = InitialCondition{*Decimal::parse("0.3"), *Decimal::parse("12")};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.outcome, PeriodicOutcome::family);
  ASSERT_TRUE(c.family_parameter.has_value());
  EXPECT_TRUE(contains_rational(*c.family_parameter, 24, 1));
  EXPECT_TRUE(contains_rational(c.points[0].v, 12, 1));
  EXPECT_LT(c.family_parameter->width, 1e-15);
  EXPECT_EQ(c.given_parameter, "inside");
  EXPECT_EQ(c.multipliers.kind, "real");
  EXPECT_TRUE(contains_rational(c.multipliers.mu[0], 1, 1));
  EXPECT_TRUE(contains_rational(c.multipliers.mu[1], 1, 4));
  EXPECT_EQ(c.stability, "neutral-stable");
  // The strip statement: every theta of a strip around 0.3 has its (v, a), and the a
  // enclosure of the strip still contains 24.
  ASSERT_TRUE(c.strip_theta.has_value());
  EXPECT_GT(c.strip_theta->width, 1e-4);
  EXPECT_TRUE(contains_rational(*c.strip_parameter, 24, 1));
  EXPECT_EQ(c.minimal_period, 1);
}

TEST(CertifyPeriodic, Eq5FamilyAtAnotherEpsAndP) {
  // eps = 0.6, p = 2: a = 8 (1.6) / (2 (0.4)) = 16, v* = 4 (1.6) / 0.4 = 16.
  PeriodicQuestion q;
  q.model = constant_model("0.6", "16");
  q.period = 1;
  q.guess = InitialCondition{*Decimal::parse("0.2"), *Decimal::parse("16")};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.outcome, PeriodicOutcome::family);
  EXPECT_TRUE(contains_rational(*c.family_parameter, 16, 1));
  EXPECT_TRUE(contains_rational(c.points[0].v, 16, 1));
  EXPECT_TRUE(contains_rational(c.multipliers.mu[1], 9, 25));  // eps^2
  EXPECT_EQ(c.wall_periods[0], 2);
}

TEST(CertifyPeriodic, Eq10PeriodTwoFamilyInItsCorrectedForm) {
  // docs/claims.md row 3 (corrected): a = 8(1+e)^3/((1-e)(1+e^2)), v = 4 + 8e(1+e)/((1-e)(1+e^2)),
  // multipliers 1 and e^4. e = 1/2: a = 43.2 = 216/5, v = 13.6 = 68/5, lambda2 = 1/16.
  PeriodicQuestion q;
  q.model = constant_model("0.5", "43.2");
  q.period = 2;
  q.guess = InitialCondition{*Decimal::parse("0.03"), *Decimal::parse("13.6")};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.outcome, PeriodicOutcome::family);
  EXPECT_TRUE(contains_rational(*c.family_parameter, 216, 5));
  EXPECT_TRUE(contains_rational(c.points[0].v, 68, 5));
  EXPECT_TRUE(contains_rational(c.multipliers.mu[1], 1, 16));
  EXPECT_EQ(c.minimal_period, 2);
}

TEST(CertifyPeriodic, VelocityDependentFixedPointFamilyHasVEqualsAHalf) {
  // The derived condition (docs/claims.md): v = ap/2 and ap/2 = 2^(5/3) c arccoth(ap/8)^(5/3) - 4.
  const double c10 = 10, a_star = veldep_fixed_point_a(c10, 1);
  PeriodicQuestion q;
  q.model.law = Law::veldep;
  q.model.c = Decimal::from_int(10);
  q.model.a = *Decimal::parse(std::to_string(a_star));
  q.model.wall = parse_wall("wall", "triangle");
  q.period = 1;
  q.family = FamilyMode::family;  // a (6 decimals) is off the family's: Newton solves for (v, a)
  q.guess = InitialCondition{*Decimal::parse("0.25"), *Decimal::parse(std::to_string(a_star / 2))};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.outcome, PeriodicOutcome::family);
  const Mpfi a = interval(*c.family_parameter), v = interval(c.points[0].v);
  // v = a/2 on the family: the two enclosures are consistent.
  EXPECT_TRUE(v.contains((a / 2).mid()) || (a / 2).contains(v.mid()));
  EXPECT_NEAR(c.family_parameter->mid, a_star, 1e-9 * a_star);
  EXPECT_EQ(c.given_parameter, "outside");
  EXPECT_EQ(c.stability, "neutral-stable");
}

TEST(CertifyPeriodic, IsolatedOrbitContainsTheMpfrNewtonOrbitAndItsDeterminantIsEpsToThe2Q) {
  // eps = 0.8, a = 19: an unstable period-2 orbit.
  PeriodicQuestion q;
  q.model = constant_model("0.8", "19");
  q.period = 2;
  q.guess = InitialCondition{*Decimal::parse("0.944"), *Decimal::parse("-0.345")};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.outcome, PeriodicOutcome::isolated);
  EXPECT_EQ(c.minimal_period, 2);
  EXPECT_TRUE(c.minimal_period_certified);
  ASSERT_EQ(c.points.size(), 2u);
  // det = 0.8^4 = 256/625 exactly.
  EXPECT_TRUE(contains_rational(c.multipliers.det, 256, 625));
  EXPECT_EQ(c.stability, "unstable");

  // An independent 256-bit Newton orbit lies in the enclosures.
  const Model<Mpfr> m = make_model<Mpfr>(q.model, 256);
  const PeriodicOrbit<Mpfr> o = find_periodic(m, 2, make_state<Mpfr>(*q.guess, 256));
  ASSERT_TRUE(o.converged);
  EXPECT_TRUE(contains(c.points[0].theta, o.points[0].theta));
  EXPECT_TRUE(contains(c.points[0].v, o.points[0].v));
  EXPECT_TRUE(contains(c.points[1].theta, o.points[1].theta));
  EXPECT_TRUE(contains(c.points[1].v, o.points[1].v));
  // And Newton's own multiplier lies in the certified one.
  EXPECT_TRUE(contains(c.multipliers.mu[0], o.multipliers.re[0]));
}

TEST(CertifyPeriodic, AMultipleOfThePeriodHasTheTrueMinimalPeriod) {
  PeriodicQuestion q;
  q.model = constant_model("0.8", "19");
  q.period = 6;
  q.guess = InitialCondition{*Decimal::parse("0.944202742064793"), *Decimal::parse("-0.34492841331585")};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.minimal_period, 2);
  EXPECT_TRUE(c.minimal_period_certified);
  // 0.8^12 = 68719476736 / 10^12.
  Mpfi det12(512);
  det12 = Mpfi(68719476736L, 512) / 1000000000000L;
  EXPECT_TRUE(interval(c.multipliers.det, 512).contains(det12));
}

TEST(CertifyPeriodic, ThePeriod103AttractorAtEps096A2882IsProvedStable) {
  // docs/claims.md row 9: the release orbit at eps = 0.96, a = 28.82 falls onto a period-103
  // attractor. The guess is the double orbit's state after 20000 steps from (1/2, 4).
  PeriodicQuestion q;
  q.model = constant_model("0.96", "28.82");
  q.period = 103;
  q.guess = InitialCondition{*Decimal::parse("0.30576639227782704"), *Decimal::parse("43.55500361255162")};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.outcome, PeriodicOutcome::isolated);
  EXPECT_EQ(c.minimal_period, 103);
  EXPECT_TRUE(c.minimal_period_certified);
  EXPECT_EQ(c.stability, "stable");
  // det DP^103 = 0.96^206 = (24/25)^206, enclosed in exact interval arithmetic here.
  Mpfi p(1, 1024);
  for (int i = 0; i < 206; ++i) p = p * 24 / 25;
  EXPECT_TRUE(interval(c.multipliers.det, 1024).contains(p));
}

TEST(CertifyPeriodic, MultipleShootingProvesALongPeriodThatTheComposedMapCannotAt128Bits) {
  // The stable period 100 of the veldep model at c = 1000, a = 19.5 (the orbit of
  // tools/bench/bench_border's P100 ends). Shooting proves it at 64 bits; the composed P^100
  // is undecided at 64 and 128 (its interval evaluation widens the box by the product of
  // 100 steps' derivative norms). Independent truth: a 256-bit Newton orbit of P^100 (the
  // composed map in MPFR, no intervals) lies in every one of the 100 point boxes, and its
  // multipliers in the enclosures from the Lohner-form product.
  PeriodicQuestion q;
  q.model.law = Law::veldep;
  q.model.a = *Decimal::parse("19.5");
  q.model.c = Decimal::from_int(1000);
  q.model.wall = parse_wall("wall", "triangle");
  q.period = 100;
  q.guess = InitialCondition{*Decimal::parse("0.014057849515324"), *Decimal::parse("23.970073801684368")};
  q.schedule = EscalationSchedule{64, 128, false};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_TRUE(c.shooting);
  EXPECT_EQ(c.bits, 64);
  EXPECT_EQ(c.minimal_period, 100);
  EXPECT_EQ(c.stability, "stable");
  ASSERT_EQ(c.points.size(), 100u);
  ASSERT_EQ(c.events.size(), 100u);

  const Model<Mpfr> m = make_model<Mpfr>(q.model, 256);
  const PeriodicOrbit<Mpfr> o = find_periodic(m, 100, make_state<Mpfr>(*q.guess, 256));
  ASSERT_TRUE(o.converged);
  ASSERT_EQ(o.points.size(), 100u);
  // The certified orbit starts at the box Newton's first point lies in; compare cyclically.
  size_t shift = 100;
  for (size_t k = 0; k < 100 && shift == 100; ++k)
    if (contains(c.points[k].theta, o.points[0].theta) && contains(c.points[k].v, o.points[0].v)) shift = k;
  ASSERT_LT(shift, 100u) << "the 256-bit Newton point is in no certified box";
  for (size_t i = 0; i < 100; ++i) {
    EXPECT_TRUE(contains(c.points[(shift + i) % 100].theta, o.points[i].theta)) << "point " << i;
    EXPECT_TRUE(contains(c.points[(shift + i) % 100].v, o.points[i].v)) << "point " << i;
  }
  ASSERT_EQ(c.multipliers.kind, "real");
  ASSERT_FALSE(o.multipliers.complex);
  EXPECT_TRUE(contains(c.multipliers.mu[0], o.multipliers.re[0]));

  q.formulation = Formulation::composed;
  const PeriodicCertificate composed = certify_periodic(q);
  EXPECT_FALSE(composed.certified) << composed.statement;
  EXPECT_EQ(composed.outcome, PeriodicOutcome::undecided);
}

TEST(CertifyPeriodic, ElasticOrbitsPreserveArea) {
  PeriodicQuestion q;
  q.model.law = Law::elastic;
  q.model.a = Decimal::from_int(26);
  q.model.wall = parse_wall("wall", "triangle");
  q.period = 3;
  q.guess = InitialCondition{*Decimal::parse("0.047325721153847186"), *Decimal::parse("7.249999999999995")};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_TRUE(contains_rational(c.multipliers.det, 1, 1));
  EXPECT_EQ(c.stability, "unstable");
  // The elliptic period-2 orbit at a = 20 (the paper's island): complex pair, |mu| ~ 1.
  q.model.a = Decimal::from_int(20);
  q.period = 2;
  q.guess = InitialCondition{*Decimal::parse("0.05"), *Decimal::parse("19")};
  const PeriodicCertificate e = certify_periodic(q);
  ASSERT_TRUE(e.certified) << e.statement;
  EXPECT_EQ(e.outcome, PeriodicOutcome::isolated);
  EXPECT_EQ(e.multipliers.kind, "complex");
  EXPECT_EQ(e.stability, "elliptic");
  EXPECT_TRUE(contains_rational(e.multipliers.modulus, 1, 1));
}

TEST(CertifyPeriodic, ParameterRangePiecesContainTheDoubleOrbitAtEveryValueInside) {
  PeriodicQuestion q;
  q.model = constant_model("0.8", "19");
  q.period = 2;
  q.guess = InitialCondition{*Decimal::parse("0.944"), *Decimal::parse("-0.345")};
  q.range = std::make_pair(mpq_class(189, 10), mpq_class(191, 10));
  const PeriodicRangeReport rep = certify_periodic_range(q);
  ASSERT_EQ(rep.uncertified_length, 0) << rep.theorem;
  ASSERT_FALSE(rep.pieces.empty());
  EXPECT_EQ(rep.pieces.front().lo, mpq_class(189, 10));
  EXPECT_EQ(rep.pieces.back().hi, mpq_class(191, 10));
  for (size_t i = 1; i < rep.pieces.size(); ++i) EXPECT_EQ(rep.pieces[i].lo, rep.pieces[i - 1].hi);
  // At a few values inside each of three pieces, the double Newton orbit lies in (or within
  // 1e-12 of) the piece's box: the box holds for every a of the piece.
  for (size_t i : {size_t(0), rep.pieces.size() / 2, rep.pieces.size() - 1}) {
    const PeriodicPiece& p = rep.pieces[i];
    for (int k = 1; k < 4; ++k) {
      const mpq_class a = p.lo + (p.hi - p.lo) * k / 4;
      ModelSpec s = q.model;
      s.a = *Decimal::parse(std::to_string(a.get_d()));
      const PeriodicOrbit<double> o = find_periodic(make_model<double>(s, 53), 2, State<double>{0.944, -0.345});
      ASSERT_TRUE(o.converged);
      bool near = false;
      for (const EnclosedOrbitPoint& cp : p.cert.points) {
        const double t = o.points[0].theta, v = o.points[0].v;
        const double tl = std::stod(cp.theta.lo), th = std::stod(cp.theta.hi), vl = std::stod(cp.v.lo), vh = std::stod(cp.v.hi);
        near = near || (t > tl - 1e-12 && t < th + 1e-12 && v > vl - 1e-12 && v < vh + 1e-12);
      }
      EXPECT_TRUE(near) << "a = " << a.get_d();
    }
  }
}

TEST(CertifyPeriodic, TheReleaseStatesPeriodOneStickingOrbit) {
  // By hand: a = 4, from (1/2, 4) the height is x(t) = 1 + 4t - 2t^2 (t from the release).
  // The gap to the wall stays positive on every segment until the up segment of the third
  // period, where the wall is 4t - 7: gap 8 - 2t^2 = 0 at t = 2, i.e. exactly at the peak
  // corner theta = 1/2, with particle velocity 4 - 4*2 = -4 = the wall's velocity there: a
  // touchdown (relative speed 0), which sticks for every eps < 1 and is released at the same
  // state. So the release state is a period-1 orbit, whatever eps.
  PeriodicQuestion q;
  q.model = constant_model("0.5", "4");
  q.period = 1;
  q.guess = InitialCondition{*Decimal::parse("0.5"), Decimal::from_int(4)};
  const PeriodicCertificate c = certify_periodic(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.outcome, PeriodicOutcome::through_release);
  EXPECT_EQ(c.stability, "superstable");
  EXPECT_EQ(c.points[0].theta.lo, "0.5");
  EXPECT_EQ(c.points[0].v.lo, "4");
}

TEST(CertifyPeriodic, NoOrbitMeansNothingIsClaimed) {
  PeriodicQuestion q;
  q.model = constant_model("0.5", "10");
  q.period = 3;
  q.guess = InitialCondition{*Decimal::parse("0.5"), Decimal::from_int(4)};
  const PeriodicCertificate c = certify_periodic(q);
  EXPECT_FALSE(c.certified);
  EXPECT_EQ(c.outcome, PeriodicOutcome::not_found);
  EXPECT_NE(c.statement.find("Nothing is claimed"), std::string::npos);
}

// Accelerator ladders (verify/accelerator.hpp): the exact certificate is checked against the
// impact map itself, iterated at 256 bits (a different code path: walking segments, roots).
ModelSpec elastic_model(const char* a) {
  ModelSpec m;
  m.law = Law::elastic;
  m.a = *Decimal::parse(a);
  m.wall = parse_wall("wall", "triangle");
  return m;
}

// The largest deviation of the map's orbit from the ladder (theta0, v0 + 8k) over n steps.
double ladder_deviation(const ModelSpec& s, const char* theta, const char* v, int n) {
  const ImpactMap<Mpfr> map(make_model<Mpfr>(s, 256));
  const InitialCondition ic{*Decimal::parse(theta), *Decimal::parse(v)};
  State<Mpfr> x = make_state<Mpfr>(ic, 256);
  const double t0 = x.theta.to_double(), v0 = x.v.to_double();
  double worst = 0;
  for (int k = 1; k <= n; ++k) {
    x = map.step(x).next;
    worst = std::max({worst, std::fabs(x.theta.to_double() - t0), std::fabs(x.v.to_double() - (v0 + 8.0 * k)) / (v0 + 8.0 * k)});
  }
  return worst;
}

TEST(CertifyAccelerator, LaddersAreProvedAndTheMapFollowsThem) {
  for (const auto& [a, theta, v] : {std::tuple{"16", "0.25", "8"}, std::tuple{"16", "0.05", "24"}, std::tuple{"8", "0.1", "8"}}) {
    const LadderCertificate c = certify_ladder(elastic_model(a), {*Decimal::parse(theta), *Decimal::parse(v)}, Decimal::from_int(8));
    ASSERT_TRUE(c.certified) << c.statement;
    EXPECT_EQ(c.D, 8);
    EXPECT_EQ(c.m0, 2 * mpq_class(v) / mpq_class(a));
    EXPECT_LT(ladder_deviation(elastic_model(a), theta, v, 40), 1e-60) << "a = " << a;
  }
}

TEST(CertifyAccelerator, StartsOffALadderAreNotModes) {
  // a = 19: 2D/a = 16/19 is not whole; the map's orbit indeed leaves the ladder.
  const LadderCertificate c19 = certify_ladder(elastic_model("19"), {*Decimal::parse("0.25"), *Decimal::parse("9.5")}, Decimal::from_int(8));
  EXPECT_FALSE(c19.certified);
  EXPECT_NE(c19.statement.find("16/19"), std::string::npos) << c19.statement;
  EXPECT_GT(ladder_deviation(elastic_model("19"), "0.25", "9.5", 40), 1e-3);
  // a = 16 but 2 v0 / a = 9/8: the first flight does not land at its phase.
  EXPECT_FALSE(certify_ladder(elastic_model("16"), {*Decimal::parse("0.25"), Decimal::from_int(9)}, Decimal::from_int(8)).certified);
  EXPECT_GT(ladder_deviation(elastic_model("16"), "0.25", "9", 40), 1e-3);
  // The falling wall, and a wrong gain.
  EXPECT_FALSE(certify_ladder(elastic_model("16"), {*Decimal::parse("0.75"), Decimal::from_int(8)}, Decimal::from_int(8)).certified);
  EXPECT_FALSE(certify_ladder(elastic_model("16"), {*Decimal::parse("0.25"), Decimal::from_int(8)}, Decimal::from_int(4)).certified);
  ModelSpec constant = elastic_model("16");
  constant.law = Law::constant;
  EXPECT_THROW(certify_ladder(constant, {*Decimal::parse("0.25"), Decimal::from_int(8)}, Decimal::from_int(8)), InputError);
}

}  // namespace
}  // namespace bouncer
