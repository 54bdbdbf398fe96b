// Continuation on the sine wall (`continue --wall sine`, analysis/continuation.hpp) against
// truth that does not come from the map's code:
//
//  1. The period-1 families in closed form (tests/sine_truth.hpp, derived in
//     test_sine_wall.cpp): along the stable branch every point is the closed-form fixed
//     point, its stability changes at the closed-form period doubling a_pd, where the
//     branch's located period doubling is, and the branch ends in a fold at the closed-form
//     saddle-node a_sn; in double and in Mpfr at 128 bits (there a_pd and a_sn to 30 digits);
//     continued in eps at a = 30, the fold and the doubling where a_sn and a_pd equal 30.
//  2. The saddle branch ends where the closed-form orbit stops being an orbit of the map: the
//     flight's gap touches the wall (a grazing), found here by a bisection on the least gap of
//     the closed-form flight in MPFR, with no bouncer code.
//  3. The period-3 sticking cycle at a = 8, eps = 1/2 lives on a short window of a: its two
//     ends are where certify_sticking (interval arithmetic from the release state, no Newton
//     and no continuation) finds the sticking period change from 3.
//  4. continue --certify's proofs on the sine wall: the period doubling's enclosure holds the
//     closed form; the fold at a_sn, at theta = 0 exactly where the phase coordinate wraps,
//     is refused with that reason (no claim).
//  5. The tongues of `tongues --wall sine` (analysis/tongues.hpp, sine_tongues): a_pd and a_sn
//     are sine_truth's closed forms, and between them the map's Newton finds the closed-form
//     orbit with a flight of p periods, stable; just below a_pd a multiplier is below -1.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bouncer/analysis/continuation.hpp"
#include "bouncer/analysis/tongues.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/verify/border_collision.hpp"
#include "bouncer/verify/sticking.hpp"
#include "sine_truth.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

namespace st = sine_truth;
using st::num;

ModelSpec sine_spec(const std::string& a, const std::string& eps) {
  ModelSpec m = bouncer::test_support::spec(Law::constant, a, eps, "1000");
  m.wall = parse_wall("wall", "sine");
  validate(m);
  return m;
}

double d(const Mpfr& x) { return x.to_double(); }
// At the sampler's precision: a rational, a value of another precision.
Mpfr wide(const mpq_class& x) {
  Mpfr r(st::kBits);
  mpfr_set_q(r.get(), x.get_mpq_t(), MPFR_RNDN);
  return r;
}
Mpfr wide(const Mpfr& x) {
  Mpfr r(st::kBits);
  mpfr_set(r.get(), x.get(), MPFR_RNDN);
  return r;
}
Mpfr circle_distance(const Mpfr& x, const Mpfr& y) {
  const Mpfr t = x - y;
  const Mpfr f = t - st::floor(t);
  return f < num(0.5) ? f : Mpfr(num(1L) - f);
}

ContinuationOptions quick() {
  ContinuationOptions o;
  o.classify_beyond = false;  // the beyond orbit's class is not under test
  return o;
}

// The stable (+1) or saddle (-1) period-1 branch of flight time n (n wall periods between
// impacts, one impact per period of the map), started at a0 and continued over [lo, hi].
template <class T>
Branch<T> period1_branch(const std::string& eps, long n, int branch, const std::string& a0, double lo, double hi, long bits) {
  const ModelSpec spec = sine_spec(a0, eps);
  const Model<T> m = make_model<T>(spec, bits);
  const st::Period1 p = st::period1(st::dec(a0), st::dec(eps), n, branch);
  const State<T> guess{ScalarTraits<T>::from_decimal(st::fixed(p.theta, 30), bits), ScalarTraits<T>::from_decimal(st::fixed(p.v, 30), bits)};
  return continue_branch(m, Parameter::a, 1, guess, ScalarTraits<T>::from_decimal(std::to_string(lo), bits),
                         ScalarTraits<T>::from_decimal(std::to_string(hi), bits), quick());
}

TEST(SineContinuation, StableBranchIsTheClosedFormAndEndsInTheSaddleNode) {
  struct Row {
    long n;
    std::string a0;
    double lo, hi;
  };
  for (const Row& row : {Row{1, "30", 20, 39}, Row{2, "18", 12, 19.5}}) {
    const Mpfr eps = st::dec("0.5");
    const double a_pd = d(st::a_period_doubling(eps, row.n)), a_sn = d(st::a_saddle_node(eps, row.n));
    SCOPED_TRACE("n = " + std::to_string(row.n) + ": a_pd = " + std::to_string(a_pd) + ", a_sn = " + std::to_string(a_sn));
    const Branch<double> b = period1_branch<double>("0.5", row.n, 1, row.a0, row.lo, row.hi, 53);
    ASSERT_TRUE(b.started) << b.note;
    ASSERT_GT(b.points.size(), 20u);
    for (const BranchPoint<double>& pt : b.points) {
      const st::Period1 p = st::period1(num(pt.param), eps, row.n, 1);
      ASSERT_TRUE(p.exists) << pt.param;
      EXPECT_NEAR(pt.orbit.points[0].v, d(p.v), 1e-9 * d(p.v)) << pt.param;
      EXPECT_LT(d(circle_distance(num(pt.orbit.points[0].theta), p.theta)), 1e-9) << pt.param;
      if (std::fabs(pt.param - a_pd) > 1e-6 * a_pd) {
        EXPECT_EQ(pt.stability, pt.param > a_pd ? "stable" : "unstable") << pt.param;
      }
    }
    EXPECT_EQ(b.low.reason, EndReason::range_end);
    EXPECT_EQ(b.high.reason, EndReason::fold) << b.high.detail;
    EXPECT_NEAR(b.high.param, a_sn, 1e-8 * a_sn);
    ASSERT_EQ(b.bifurcations.size(), 1u);
    EXPECT_EQ(b.bifurcations[0].kind, SmoothKind::period_doubling);
    EXPECT_NEAR(b.bifurcations[0].param, a_pd, 1e-10 * a_pd);
  }
}

TEST(SineContinuation, InEpsTheBranchFoldsAndDoublesWhereTheClosedFormsMeetA) {
  // At a = 30 the stable period-1 orbit is born where a_sn(eps) = 30, eps = (30 - 4 pi) /
  // (30 + 4 pi), and period-doubles where a_pd(eps) = 30 (found here by bisection on the
  // closed form, which increases with eps).
  const ModelSpec spec = sine_spec("30", "0.5");
  const Model<double> m = make_model<double>(spec, 53);
  const st::Period1 p = st::period1(st::dec("30"), st::dec("0.5"), 1, 1);
  const Branch<double> b = continue_branch(m, Parameter::eps, 1, State<double>{d(p.theta), d(p.v)}, 0.3, 0.95, quick());
  ASSERT_TRUE(b.started) << b.note;
  const double fold = d(Mpfr((num(30L) - 4 * st::pi()) / (num(30L) + 4 * st::pi())));
  EXPECT_EQ(b.low.reason, EndReason::fold) << b.low.detail;
  EXPECT_NEAR(b.low.param, fold, 1e-9);
  Mpfr lo = num(0.45), hi = num(0.9);
  for (int k = 0; k < 80; ++k) {
    const Mpfr mid = (lo + hi) / 2;
    (st::a_period_doubling(mid, 1) < num(30L) ? lo : hi) = mid;
  }
  ASSERT_EQ(b.bifurcations.size(), 1u);
  EXPECT_EQ(b.bifurcations[0].kind, SmoothKind::period_doubling);
  EXPECT_NEAR(b.bifurcations[0].param, d(lo), 1e-10);
}

TEST(SineContinuation, Mpfr128LocatesThePeriodDoublingAndTheFoldToThirtyDigits) {
  const Branch<Mpfr> b = period1_branch<Mpfr>("0.5", 1, 1, "27", 25, 28, 128);
  ASSERT_TRUE(b.started) << b.note;
  EXPECT_EQ(b.low.reason, EndReason::range_end);
  EXPECT_EQ(b.high.reason, EndReason::range_end);
  ASSERT_EQ(b.bifurcations.size(), 1u);
  EXPECT_EQ(b.bifurcations[0].kind, SmoothKind::period_doubling);
  const Mpfr a_pd = st::a_period_doubling(st::dec("0.5"), 1);
  const Mpfr err = st::abs(wide(b.bifurcations[0].param) - a_pd);
  EXPECT_TRUE(err < num(1e-30) * a_pd) << st::show(err) << " (located " << ScalarTraits<Mpfr>::to_string(b.bifurcations[0].param) << ")";
  // The fold: Newton's pseudo-inverse cutoff scales with the precision (a fixed 1e-9 stopped
  // the corrector ~1e-18 short of a_sn at every precision).
  const Branch<Mpfr> f = period1_branch<Mpfr>("0.5", 1, 1, "37", 36, 39, 128);
  ASSERT_TRUE(f.started) << f.note;
  EXPECT_EQ(f.high.reason, EndReason::fold) << f.high.detail;
  const Mpfr a_sn = st::a_saddle_node(st::dec("0.5"), 1);
  const Mpfr fold_err = st::abs(wide(f.high.param) - a_sn);
  EXPECT_TRUE(fold_err < num(1e-30) * a_sn) << st::show(fold_err) << " (located " << ScalarTraits<Mpfr>::to_string(f.high.param) << ")";
}

// The least gap of the closed-form saddle orbit's flight at a (eps = 1/2, n = 1): the gap
// g(s) = sin(2 pi theta*) + v* s - a s^2 / 2 - sin(2 pi (theta* + s)) on (0, 1), minimised by
// a grid of 400 points and Newton on g'.
Mpfr least_gap(const Mpfr& a) {
  const st::Period1 p = st::period1(a, st::dec("0.5"), 1, -1);
  const Mpfr tp = 2 * st::pi();
  const auto g = [&](const Mpfr& s) { return Mpfr(st::sin2pi(p.theta) + p.v * s - a * s * s / 2 - st::sin2pi(Mpfr(p.theta + s))); };
  Mpfr best_s = num(0.5);
  Mpfr best = g(best_s);
  for (int i = 1; i < 400; ++i) {
    const Mpfr s = num(i / 400.0);
    const Mpfr v = g(s);
    if (v < best) {
      best = v;
      best_s = s;
    }
  }
  Mpfr s = best_s;
  for (int k = 0; k < 60; ++k) {
    const Mpfr g1 = p.v - a * s - tp * st::cos2pi(Mpfr(p.theta + s));
    const Mpfr g2 = tp * tp * st::sin2pi(Mpfr(p.theta + s)) - a;
    s = s - g1 / g2;
  }
  return g(s);
}

TEST(SineContinuation, SaddleBranchEndsInAGrazingWhereTheClosedFormFlightTouchesTheWall) {
  // The grazing value by bisection on the least gap (positive above it).
  Mpfr lo = num(10L), hi = num(30L);
  ASSERT_TRUE(least_gap(lo) < num(0L));
  ASSERT_TRUE(least_gap(hi) > num(0L));
  for (int k = 0; k < 60; ++k) {
    const Mpfr mid = (lo + hi) / 2;
    (least_gap(mid) > num(0L) ? hi : lo) = mid;
  }
  const double a_graze = d(hi), a_sn = d(st::a_saddle_node(st::dec("0.5"), 1));
  SCOPED_TRACE("the closed-form flight grazes at a = " + std::to_string(a_graze));
  const Branch<double> b = period1_branch<double>("0.5", 1, -1, "30", 5, 39, 53);
  ASSERT_TRUE(b.started) << b.note;
  for (const BranchPoint<double>& pt : b.points) EXPECT_EQ(pt.stability, "unstable") << pt.param;
  EXPECT_TRUE(b.bifurcations.empty());
  EXPECT_EQ(b.high.reason, EndReason::fold) << b.high.detail;
  EXPECT_NEAR(b.high.param, a_sn, 1e-8 * a_sn);
  EXPECT_EQ(b.low.reason, EndReason::border) << b.low.detail;
  EXPECT_EQ(b.low.margin, static_cast<int>(Margin::clearance)) << b.low.detail;
  EXPECT_NEAR(b.low.param, a_graze, 1e-7 * a_graze) << b.low.detail;
  EXPECT_NE(b.low.detail.find("grazes the wall at theta ~"), std::string::npos) << b.low.detail;
}

long sticking_period_at(double a) {
  StickingQuestion q;
  char text[64];
  std::snprintf(text, sizeof text, "%.12f", a);
  q.model = sine_spec(text, "0.5");
  q.from_release = true;
  q.max_steps = 200;
  const StickingCertificate c = certify_sticking(q);
  EXPECT_TRUE(c.certified) << text << ": " << c.reason;
  return c.period.value_or(0);
}

TEST(SineContinuation, StickingCycleEndsWhereCertifiedStickingChangesPeriod) {
  const ModelSpec spec = sine_spec("8", "0.5");
  const Model<double> m = make_model<double>(spec, 53);
  const Branch<double> b = continue_branch(m, Parameter::a, 3, release_state(m), 4.0, 20.0, quick());
  ASSERT_TRUE(b.started) << b.note;
  EXPECT_EQ(b.points[b.start].stability, "stable");
  for (const BranchEnd<double>* e : {&b.low, &b.high}) {
    SCOPED_TRACE(e->detail);
    EXPECT_EQ(e->reason, EndReason::border);
    const double inside = e == &b.low ? e->param + 1e-6 : e->param - 1e-6;
    const double outside = e == &b.low ? e->param - 1e-6 : e->param + 1e-6;
    EXPECT_EQ(sticking_period_at(inside), 3) << inside;
    EXPECT_NE(sticking_period_at(outside), 3) << outside;
  }
  EXPECT_EQ(b.low.margin, static_cast<int>(Margin::sticking));
  EXPECT_EQ(b.high.margin, static_cast<int>(Margin::clearance));
  EXPECT_LT(b.high.param - b.low.param, 0.05);
}

TEST(SineContinuation, CertifiedPeriodDoublingHoldsTheClosedFormAndTheFoldAtThetaZeroIsRefused) {
  const Branch<double> b = period1_branch<double>("0.5", 1, 1, "30", 20, 39, 53);
  ASSERT_EQ(b.bifurcations.size(), 1u);
  CertifiedBranchEnds c;
  certify_smooth_events(sine_spec("30", "0.5"), Parameter::a, 1, b, 53, c);
  ASSERT_EQ(c.bifurcations.size(), 1u);
  const PeriodDoublingCertificate& pd = c.bifurcations[0];
  ASSERT_TRUE(pd.certified) << pd.reason;
  const Mpfr a_pd = st::a_period_doubling(st::dec("0.5"), 1);
  EXPECT_TRUE(wide(pd.lo) <= a_pd && a_pd <= wide(pd.hi))
      << pd.lo.get_str() << " " << st::show(a_pd, 40);
  ASSERT_TRUE(c.high_smooth.has_value());
  EXPECT_FALSE(c.high_smooth->certified);
  EXPECT_NE(c.high_smooth->reason.find("phase coordinate wraps"), std::string::npos) << c.high_smooth->reason;
}

TEST(SineTongues, AreTheClosedFormsAndBoundTheStableOrbitOfTheMap) {
  TonguesRequest r;
  r.p_max = 6;
  r.samples = 11;  // eps = 0, 1/10, ..., 1: the ends are left out
  const SineTongues t = sine_tongues(r);
  ASSERT_EQ(t.curves.size(), 6u);
  for (const SineTongueCurve& c : t.curves) {
    ASSERT_EQ(c.points.size(), 9u) << c.p;
    for (const SineTonguePoint& q : c.points) {
      Mpfr eps(st::kBits);
      mpfr_set_q(eps.get(), q.eps.get_mpq_t(), MPFR_RNDN);
      const Mpfr a_pd = st::a_period_doubling(eps, c.p), a_sn = st::a_saddle_node(eps, c.p);
      SCOPED_TRACE("p = " + std::to_string(c.p) + ", eps = " + q.eps.get_str());
      EXPECT_TRUE(st::abs(wide(q.a_pd) - a_pd) < num(1e-35) * a_pd) << st::show(a_pd);
      EXPECT_TRUE(st::abs(wide(q.a_sn) - a_sn) < num(1e-35) * a_sn) << st::show(a_sn);
      // The map, in double, at the middle of the tongue (within the sine wall's a < 4 pi^2)
      // and 1e-4 below a_pd.
      const double e = d(eps), lo = d(a_pd), hi = std::min(d(a_sn), 39.4);
      for (const double a : {(lo + hi) / 2, lo * (1 - 1e-4)}) {
        char text[64];
        std::snprintf(text, sizeof text, "%.12f", a);
        const std::string eps_text = std::to_string(e);
        const ModelSpec spec = sine_spec(text, eps_text);
        const st::Period1 cf = st::period1(st::dec(text), st::dec(eps_text), c.p, 1);
        ASSERT_TRUE(cf.exists);
        const Model<double> m = make_model<double>(spec, 53);
        const PeriodicOrbit<double> o = find_periodic(m, 1, State<double>{d(cf.theta), d(cf.v)});
        SCOPED_TRACE(std::string("a = ") + text);
        ASSERT_TRUE(o.converged) << o.note;
        EXPECT_EQ(o.wall_periods[0], c.p);
        EXPECT_LT(d(circle_distance(num(o.points[0].theta), cf.theta)), 1e-9);
        if (a > lo) EXPECT_LT(o.multipliers.modulus(0), 1.0);
        else EXPECT_LT(o.multipliers.re[1] < o.multipliers.re[0] ? o.multipliers.re[1] : o.multipliers.re[0], -1.0);
      }
    }
  }
}

}  // namespace
}  // namespace bouncer
