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
//   * the switch: the lower end is 0 exactly at eps = 1/(4p-1), where a = 16/(2p-1);
//   * the library's figure (arnold_tongues): every point exactly on the curve inside the
//     window, theta_min, `full` and the switch as derived here, uniform in a, and sampled
//     points fixed points of the map.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "bouncer/analysis/tongues.hpp"
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


// arnold_tongues (analysis/tongues.hpp), the figure's points, against the derivation above.
TonguesRequest tongues_request(long p_max, long samples, const char* a_lo, const char* a_hi, const char* e_lo,
                               const char* e_hi) {
  TonguesRequest r;
  r.p_max = p_max;
  r.samples = samples;
  r.a_range = {*Decimal::parse(a_lo), *Decimal::parse(a_hi)};
  r.eps_range = {*Decimal::parse(e_lo), *Decimal::parse(e_hi)};
  return r;
}

TEST(Tongues, PointsLieOnTheCurvesInsideTheWindow) {
  const TonguesRequest r = tongues_request(12, 41, "2.5", "30", "0.05", "0.9");
  const Tongues t = arnold_tongues(r);
  ASSERT_EQ(t.curves.size(), 12u);
  long total = 0;
  for (const TongueCurve& c : t.curves) {
    const long p = c.p;
    SCOPED_TRACE("p=" + std::to_string(p));
    EXPECT_EQ(c.switch_eps, mpq_class(1, 4 * p - 1));
    EXPECT_EQ(c.switch_a, curve_a(c.switch_eps, p));
    // The curve's a-extent in the window: from eps = 0.05 (or a = 2.5) to eps = 0.9 (or a = 30).
    const mpq_class lo = std::max(mpq_class(5, 2), curve_a(mpq_class(1, 20), p));
    const mpq_class hi = std::min(mpq_class(30), curve_a(mpq_class(9, 10), p));
    ASSERT_LT(lo, hi);
    const bool switch_inside = lo < c.switch_a && c.switch_a < hi;
    ASSERT_EQ(c.points.size(), 41u + (switch_inside ? 1 : 0));
    EXPECT_EQ(c.points.front().a, lo);
    EXPECT_EQ(c.points.back().a, hi);
    long switches = 0;
    for (size_t i = 0; i < c.points.size(); ++i) {
      const TonguePoint& q = c.points[i];
      EXPECT_EQ(q.a, curve_a(q.eps, p));  // on the curve, exactly
      EXPECT_TRUE(lo <= q.a && q.a <= hi && mpq_class(1, 20) <= q.eps && q.eps <= mpq_class(9, 10));
      EXPECT_EQ(q.theta_min, lower_end(q.eps, p));
      EXPECT_EQ(q.full, lower_end(q.eps, p) == 0);  // solid iff the family is all of (0, 1/2)
      EXPECT_EQ(q.at_switch, q.eps == mpq_class(1, 4 * p - 1));
      switches += q.at_switch;
      if (i > 0) {
        EXPECT_LT(c.points[i - 1].a, q.a);
      }
    }
    EXPECT_EQ(switches, switch_inside ? 1 : 0);
    total += static_cast<long>(c.points.size());
  }
  EXPECT_EQ(t.points, total);
  // Uniform in a: the samples (the switch point aside) are lo + (hi - lo) i / 40.
  const TongueCurve& c1 = t.curves[0];
  long i = 0;
  for (const TonguePoint& q : c1.points)
    if (!q.at_switch) {
      EXPECT_EQ(q.a, c1.points.front().a + (c1.points.back().a - c1.points.front().a) * i++ / 40);
    }
}

TEST(Tongues, CurvesOutsideTheWindowAreEmpty) {
  // a = 8(1+eps)/(p(1-eps)) >= 8/p: p = 1 starts at a = 8 and p = 2 at 4, beyond a = 3.
  const Tongues t = arnold_tongues(tongues_request(3, 16, "0", "3", "0", "1"));
  EXPECT_TRUE(t.curves[0].points.empty());
  EXPECT_TRUE(t.curves[1].points.empty());
  EXPECT_FALSE(t.curves[2].points.empty());  // 8/3 < 3
  EXPECT_EQ(t.points, static_cast<long>(t.curves[2].points.size()));
}

TEST(Tongues, TonguePointsAreFixedPointsOfTheMap) {
  // Points of the figure, stepped by the impact map at 256 bits: a fixed point just above
  // theta_min (or at 1/4 on the solid part), after exactly p periods.
  const Tongues t = arnold_tongues(tongues_request(4, 16, "0", "30", "0.01", "0.9"));
  long checked = 0;
  for (const TongueCurve& c : t.curves)
    for (size_t i = 0; i < c.points.size(); i += 5) {
      const TonguePoint& q = c.points[i];
      ModelSpec m;
      m.law = Law::constant;
      m.eps = Decimal::from_int(0);  // replaced by the exact rational below
      m.a = Decimal::from_int(1);
      m.wall = parse_wall("wall", "triangle");
      validate(m);
      Model<Mpfr> model = with_parameter(make_model<Mpfr>(m, kBits), Parameter::eps, mpfr_of(q.eps));
      model = with_parameter(model, Parameter::a, mpfr_of(q.a));
      const ImpactMap<Mpfr> map(model);
      const mpq_class theta = q.full ? mpq_class(1, 4) : mpq_class(q.theta_min + mpq_class(1, 1000));
      SCOPED_TRACE("p=" + std::to_string(c.p) + " a=" + q.a.get_str() + " theta=" + theta.get_str());
      const State<Mpfr> s{mpfr_of(theta), mpfr_of(mpq_class(4 * (1 + q.eps) / (1 - q.eps)))};
      const StepResult<Mpfr> r = map.step(s);
      EXPECT_EQ(r.kind, EventKind::impact);
      EXPECT_EQ(r.periods, c.p);
      EXPECT_LT(dist(r.next.theta, s.theta), 1e-60);
      EXPECT_LT(dist(r.next.v, s.v), 1e-60);
      ++checked;
    }
  EXPECT_GE(checked, 10);
}

TEST(Tongues, NearestDoubleRoundsToNearest) {
  // IEEE division of small integers is correctly rounded: the independent truth.
  for (long n = -50; n <= 50; ++n)
    for (long d : {3L, 7L, 10L, 49L, 1000003L}) EXPECT_EQ(nearest_double(mpq_class(n) / mpq_class(d)), static_cast<double>(n) / static_cast<double>(d)) << n << "/" << d;
  EXPECT_EQ(nearest_double(mpq_class(1) / 3), 1.0 / 3);
}

}  // namespace
}  // namespace bouncer
