// The Arnold-tongue figure (`bouncer tongues`, fig. arnold) draws the eq. 5 curves
//     a = 8 (1 + eps) / (p (1 - eps))
// solid where the proved family theta* in (max(0, 1/2 - 2p eps/(1+eps)), 1/2) is all of
// (0, 1/2), i.e. eps >= 1/(4p-1). These tests check the picture's premises against the
// impact map itself, in MPFR at 256 bits (independent of the drawing code):
//   * derivation: v* = a p / 2 (back at the same height after p periods) and eq. 2 with
//     v^- = -v*, fdot = 4 give v* = 4(1+eps)/(1-eps), hence the curve (exact rationals);
//   * on the curve, (theta*, v*) is a fixed point of ImpactMap (flight of exactly p periods)
//     for theta* just above the lower end of the proved interval, also where eps < 1/(4p-1);
//   * just below that end it is not: the lower end is where the family stops, so the
//     dashed part of each curve really has a smaller family (the picture's distinction);
//   * the switch: the lower end is 0 exactly at eps = 1/(4p-1), where a = 16/(2p-1).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"

namespace bouncer {
namespace {

constexpr long kBits = 256;

mpq_class curve_a(const mpq_class& eps, long p) { return mpq_class(8 * (1 + eps) / (p * (1 - eps))); }
mpq_class lower_end(const mpq_class& eps, long p) {
  mpq_class t = mpq_class(1, 2) - mpq_class(2 * p * eps / (1 + eps));
  return t > 0 ? t : mpq_class(0);
}

Mpfr mpfr_of(const mpq_class& q) {
  Mpfr x(kBits);
  mpfr_set_q(x.get(), q.get_mpq_t(), MPFR_RNDN);
  return x;
}
double dist(const Mpfr& x, const Mpfr& y) {
  Mpfr d = x - y;
  return std::fabs(d.to_double());
}

struct Case {
  long p;
  const char* eps;
};

// The model on the curve: eps exact (decimal), a rounded once to 256 bits.
ImpactMap<Mpfr> map_on_curve(long p, const mpq_class& eps, const std::string& eps_text) {
  ModelSpec m;
  m.law = Law::constant;
  m.eps = *Decimal::parse(eps_text);
  m.a = Decimal::from_int(1);
  m.wall = parse_wall("wall", "triangle");
  validate(m);
  const Model<Mpfr> base = make_model<Mpfr>(m, kBits);
  return ImpactMap<Mpfr>(with_parameter(base, Parameter::a, mpfr_of(curve_a(eps, p))));
}

TEST(Tongues, CurveJoinsFlightAndImpactConditions) {
  // v* from the flight (v* p - a p^2 / 2 = 0) equals v* from eq. 2 exactly on the curve.
  for (long p = 1; p <= 10; ++p)
    for (const mpq_class& eps : {mpq_class(0), mpq_class(1, 10), mpq_class(1, 2), mpq_class(24, 25)}) {
      const mpq_class a = curve_a(eps, p);
      const mpq_class v_flight = a * p / 2;
      const mpq_class v_impact = 4 * (1 + eps) / (1 - eps);
      EXPECT_EQ(v_flight, v_impact) << "p=" << p << " eps=" << eps;
      // eq. 2: v+ = (1 + eps) * 4 - eps * v- with v- = -v*
      EXPECT_EQ(mpq_class((1 + eps) * 4 + eps * v_impact), v_impact);
    }
}

TEST(Tongues, SwitchIsWhereTheFamilyFillsTheInterval) {
  for (long p = 1; p <= 50; ++p) {
    const mpq_class e(1, 4 * p - 1);
    EXPECT_EQ(lower_end(e, p), 0) << p;
    EXPECT_GT(lower_end(mpq_class(e - mpq_class(1, 1000000)), p), 0) << p;
    EXPECT_EQ(curve_a(e, p), mpq_class(16, 2 * p - 1)) << p;
  }
}

TEST(Tongues, FixedPointAboveTheLowerEndNotBelow) {
  // eps < 1/(4p-1): the dashed part of each curve.
  const Case cases[] = {{1, "0.2"}, {2, "0.05"}, {3, "0.05"}, {5, "0.02"}, {10, "0.01"}};
  for (const Case& c : cases) {
    const mpq_class eps = Decimal::parse(c.eps)->value();
    ASSERT_LT(eps, mpq_class(1, 4 * c.p - 1));
    const mpq_class lo = lower_end(eps, c.p);
    ASSERT_GT(lo, 0);
    const ImpactMap<Mpfr> map = map_on_curve(c.p, eps, c.eps);
    const Mpfr v = mpfr_of(mpq_class(4 * (1 + eps) / (1 - eps)));
    for (const mpq_class& off : {mpq_class(1, 1000), mpq_class(1, 100), mpq_class(-1, 1000), mpq_class(-1, 100)}) {
      const mpq_class theta = lo + off;
      SCOPED_TRACE("p=" + std::to_string(c.p) + " eps=" + c.eps + " theta=lower end + " + off.get_str());
      State<Mpfr> s{mpfr_of(theta), v};
      const StepResult<Mpfr> r = map.step(s);
      const bool fixed = r.kind == EventKind::impact && r.periods == c.p && dist(r.next.theta, s.theta) < 1e-60 &&
                         dist(r.next.v, s.v) < 1e-60;
      if (off > 0) {
        EXPECT_TRUE(fixed) << "theta' - theta = " << dist(r.next.theta, s.theta) << ", periods " << r.periods;
        EXPECT_LT(dist(r.tau, mpfr_of(mpq_class(c.p))), 1e-60);
      } else {
        // Below the end the particle meets the wall earlier (the previous peak).
        EXPECT_FALSE(fixed);
        EXPECT_LT(r.tau.to_double(), static_cast<double>(c.p));
      }
    }
  }
}

TEST(Tongues, FullIntervalOnTheSolidPart) {
  // eps >= 1/(4p-1): theta* anywhere in (0, 1/2), here near both ends.
  const Case cases[] = {{1, "0.5"}, {2, "0.2"}, {3, "0.1"}, {10, "0.03"}};
  for (const Case& c : cases) {
    const mpq_class eps = Decimal::parse(c.eps)->value();
    ASSERT_GE(eps, mpq_class(1, 4 * c.p - 1));
    const ImpactMap<Mpfr> map = map_on_curve(c.p, eps, c.eps);
    const Mpfr v = mpfr_of(mpq_class(4 * (1 + eps) / (1 - eps)));
    for (const mpq_class& theta : {mpq_class(1, 1000), mpq_class(1, 4), mpq_class(499, 1000)}) {
      SCOPED_TRACE("p=" + std::to_string(c.p) + " eps=" + c.eps + " theta=" + theta.get_str());
      State<Mpfr> s{mpfr_of(theta), v};
      const StepResult<Mpfr> r = map.step(s);
      EXPECT_EQ(r.kind, EventKind::impact);
      EXPECT_EQ(r.periods, c.p);
      EXPECT_LT(dist(r.next.theta, s.theta), 1e-60);
      EXPECT_LT(dist(r.next.v, s.v), 1e-60);
    }
  }
}

}  // namespace
}  // namespace bouncer
