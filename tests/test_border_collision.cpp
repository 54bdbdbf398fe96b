// certify_border_collision (verify/border_collision.hpp): two-sided enclosures of a border
// collision a* by the Krawczyk operator on the augmented system.
//
// Truth independent of the code (derivation in test_continuation.cpp's header): the period-1
// sticking orbit through the release state (1/2, 4) of the constant-eps model exists for
// 8((1+eps)/(1-eps))^2 <= a < 32; at eps = 1/4 its branch in a ends at a* = 200/9 (the
// sticking threshold: eps sqrt(8a) = a(1-eps)/2 (1 - sqrt(8/a))) and at a* = 32 (the impact
// theta = sqrt(8/a) - 1/2 reaches the knot theta = 0). The exact rationals must lie in the
// certified enclosures, each at most 1e-30 wide at 128 bits. A question far from any end
// must not be certified.
//
// The velocity-dependent period-7 branch (c = 1000, scene continue-veldep-period7.toml) has no
// closed form: its ends, located by double continuation, are certified here and compared with
// the mpfr:128 continuation's a* quoted in docs/guide/dynamics.md ("Accuracy and tests", 27.72056130544585948764
// 2437424316, from a different algorithm: bisection on the margin along Newton orbits).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "bouncer/analysis/continuation.hpp"
#include "bouncer/scalar/mpfi.hpp"
#include "bouncer/verify/border_collision.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

BorderCollisionQuestion release_question(const std::pair<std::string, std::string>& interval, bool high) {
  BorderCollisionQuestion q;
  q.end.model = test_support::spec(Law::constant, "24", "0.25");
  q.end.vary = Parameter::a;
  q.end.period = 1;
  q.end.last_point = {parse_decimal("theta", "0.5"), parse_decimal("v", "4")};
  q.end.lo = parse_decimal("lo", interval.first);
  q.end.hi = parse_decimal("hi", interval.second);
  q.end.high_end = high;
  q.bits = 128;
  return q;
}

TEST(BorderCollision, StickingThresholdAt200Over9IsEnclosedTwoSided) {
  const BorderCollisionQuestion q =
      release_question(branch_end_interval<double>(200.0 / 9 - 1e-9, 200.0 / 9 + 1e-9, false, 53), false);
  const BorderCollisionCertificate c = certify_border_collision(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_TRUE(c.through_release);
  EXPECT_EQ(c.margin, Margin::sticking) << c.margin_text;
  EXPECT_LE(c.lo, mpq_class(200, 9));
  EXPECT_GE(c.hi, mpq_class(200, 9));
  EXPECT_LE(mpq_class(c.hi - c.lo).get_d(), 1e-30);
  EXPECT_GT(c.hi, c.lo);
  // The branch (sticking) lies above a*: the proof covers [a*_hi, z_hi] there, and the
  // step's own events were checked on that side.
  EXPECT_GT(c.z_hi, c.hi);
  EXPECT_LT(c.z_lo, c.lo);
  EXPECT_GE(c.checked_at, c.hi);
  EXPECT_EQ(c.events, "S0^");
  EXPECT_EQ(c.bits, 128);
  EXPECT_NE(c.statement.find("exactly one a*"), std::string::npos) << c.statement;
}

TEST(BorderCollision, KnotAt32IsEnclosedTwoSided) {
  const BorderCollisionQuestion q = release_question(branch_end_interval<double>(32 - 1e-9, 32, true, 53), true);
  const BorderCollisionCertificate c = certify_border_collision(q);
  ASSERT_TRUE(c.certified) << c.statement;
  // The impact reaches the knot theta = 0 as the flight's clearance at that corner reaches
  // 0 (the same event seen from both sides): either margin names it.
  EXPECT_TRUE(c.margin == Margin::knot || c.margin == Margin::clearance) << c.margin_text;
  EXPECT_EQ(c.knot, 0) << c.margin_text;
  EXPECT_LE(c.lo, mpq_class(32));
  EXPECT_GE(c.hi, mpq_class(32));
  EXPECT_LE(mpq_class(c.hi - c.lo).get_d(), 1e-30);
  EXPECT_LT(c.z_lo, c.lo);
  EXPECT_LE(c.checked_at, c.lo);
  ASSERT_EQ(c.orbit.size(), 1u);  // the release state itself
}

TEST(BorderCollision, StickingThresholdInEpsIsTwoMinusSqrt3) {
  // In eps at a = 24 the threshold is eps* = 2 - sqrt(3) (test_continuation.cpp's header):
  // irrational, so the check is that an MPFI enclosure of 2 - sqrt(3) meets the certificate's.
  BorderCollisionQuestion q = release_question(branch_end_interval<double>(0.2679491924 - 1e-10, 0.2679491924 + 1e-10, true, 53), true);
  q.end.model = test_support::spec(Law::constant, "24", "0.2");
  q.end.vary = Parameter::eps;
  const BorderCollisionCertificate c = certify_border_collision(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.margin, Margin::sticking);
  Mpfi truth = 2 - sqrt(Mpfi(3, 256));
  Mpfi got(256);
  ASSERT_TRUE(got.set_decimal(c.parameter.lo));
  Mpfi hi(256);
  ASSERT_TRUE(hi.set_decimal(c.parameter.hi));
  got = hull(got, hi);
  EXPECT_TRUE(got.contains(truth)) << c.parameter.lo << " " << c.parameter.hi;
  EXPECT_LE(c.width, 1e-30);
}

// The long-flight period-1 sticking orbit through the release state (claims row 17), derived
// by hand: from (1/2, 4) the height above the peak is 4t - a t^2/2, so for a < 8 the particle
// clears the next peak (t = 1) by 4 - a/2 and lands on the falling wall 1 - 4(t - 1) where
// a t^2 - 16 t + 8 = 0, with relative speed q = a t - 8 = sqrt(8 (8 - a)); below the sticking
// threshold it collapses there (chatter time 2 eps q / (a (1 - eps)) within the 3/2 - t left
// of the fall), rides down, through the upward turn (the paper's convention) and up to the
// next peak: period 1 for every eps < 1. Its branch in a ends
//   - at a* = 8 (for every eps): the clearance 4 - a/2 at the peak, the impact's distance to
//     the peak and the impact speed reach 0 together: a corner touchdown;
//   - at eps = 1/2, at the sticking threshold 2q/a = 3/2 - t: with the impact equation,
//     9a^2 + 192a - 2048 = 0, a* = 32 (sqrt(3) - 1) / 3 = 7.8085...
BorderCollisionQuestion touchdown_question(const std::string& eps, const std::pair<std::string, std::string>& interval,
                                           bool high) {
  BorderCollisionQuestion q = release_question(interval, high);
  q.end.model = test_support::spec(Law::constant, "7.9", eps);
  return q;
}

TEST(BorderCollision, CornerTouchdownAt8IsEnclosedTwoSidedForEveryEps) {
  for (const char* eps : {"0.5", "0.25", "0.9"}) {
    const BorderCollisionCertificate c =
        certify_border_collision(touchdown_question(eps, branch_end_interval<double>(8 - 1e-9, 8, true, 53), true));
    ASSERT_TRUE(c.certified) << eps << ": " << c.statement;
    EXPECT_TRUE(c.through_release);
    // Three margins vanish together at the peak (knot 1); the one named carries the others.
    EXPECT_TRUE(c.margin == Margin::clearance || c.margin == Margin::knot) << c.margin_text;
    EXPECT_EQ(c.knot, 1) << c.margin_text;
    EXPECT_LE(c.lo, mpq_class(8));
    EXPECT_GE(c.hi, mpq_class(8));
    EXPECT_LE(mpq_class(c.hi - c.lo).get_d(), 1e-30);
    EXPECT_LT(c.checked_at, mpq_class(8));  // on the branch side, not a* itself
    EXPECT_LT(c.z_lo, c.lo);
    EXPECT_EQ(c.events, "S1^");
    if (c.margin == Margin::clearance) {
      EXPECT_NE(c.margin_text.find("corner touchdown"), std::string::npos) << c.margin_text;
    }
  }
}

TEST(BorderCollision, StickingThresholdThroughAnUpwardTurnIs32Sqrt3Minus1Over3) {
  const double guess = 32 * (std::sqrt(3.0) - 1) / 3;
  const BorderCollisionCertificate c = certify_border_collision(
      touchdown_question("0.5", branch_end_interval<double>(guess - 1e-9, guess + 1e-9, false, 53), false));
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.margin, Margin::sticking) << c.margin_text;
  const Mpfi truth = 32 * (sqrt(Mpfi(3, 256)) - 1) / 3;
  Mpfi got(256), hi(256);
  ASSERT_TRUE(got.set_decimal(c.parameter.lo));
  ASSERT_TRUE(hi.set_decimal(c.parameter.hi));
  got = hull(got, hi);
  EXPECT_TRUE(got.contains(truth)) << c.parameter.lo << " " << c.parameter.hi;
  EXPECT_LE(c.width, 1e-30);
  EXPECT_GT(c.checked_at, c.hi);
}

TEST(BorderCollision, SameEndWithTheMarginGivenAndAtMoreBits) {
  BorderCollisionQuestion q = release_question(branch_end_interval<double>(32 - 1e-9, 32, true, 53), true);
  q.margin = Margin::knot;
  q.bits = 256;
  const BorderCollisionCertificate c = certify_border_collision(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.margin, Margin::knot);
  EXPECT_LE(c.lo, mpq_class(32));
  EXPECT_GE(c.hi, mpq_class(32));
  EXPECT_LE(mpq_class(c.hi - c.lo).get_d(), 1e-60);
}

TEST(BorderCollision, AWrongGuessFarFromAnyEndIsNotCertified) {
  // a in [28, 28.000028] lies inside the branch (200/9 < a < 32): no margin vanishes there.
  const BorderCollisionCertificate c = certify_border_collision(release_question({"28", "28.000028"}, true));
  EXPECT_FALSE(c.certified);
  EXPECT_FALSE(c.reason.empty());
  EXPECT_NE(c.statement.find("Not certified at 128 bits"), std::string::npos) << c.statement;
}

TEST(BorderCollision, BeyondTheEndIsNotCertified) {
  // Past a* = 32 the release state's period-1 sticking orbit does not exist.
  const BorderCollisionCertificate c = certify_border_collision(release_question({"32.001", "32.002"}, true));
  EXPECT_FALSE(c.certified) << c.statement;
  EXPECT_FALSE(c.reason.empty());
}

// The stable period-7 orbit of the velocity-dependent model at c = 1000, continued in double,
// with the error estimate of its ends (analysis/end_estimate.hpp).
Branch<double> veldep_p7() {
  const ModelSpec s = test_support::spec(Law::veldep, "28", "1", "1000");
  Branch<double> b = continue_branch(make_model<double>(s, 53), Parameter::a, 7,
                                     State<double>{0.19204436106841707, 26.916257785320354}, 27.0, 29.0);
  estimate_end_accuracy(s, b);
  return b;
}

// The widened bracket of an estimated end (issue 23, "honest digits") contains the
// certified enclosure of a*, where the bracket itself need not.
void expect_estimate_contains(const BranchEnd<double>& e, const BorderCollisionCertificate& c, const char* what) {
  ASSERT_EQ(e.estimate.kind, EndEstimate::Kind::estimate) << what << ": " << e.estimate.note;
  EXPECT_LE(e.estimate.lo, c.lo) << what << ": estimate [" << e.estimate.lo.get_d() << ", " << e.estimate.hi.get_d()
                                  << "], certified " << c.parameter.lo;
  EXPECT_GE(e.estimate.hi, c.hi) << what << ": certified " << c.parameter.hi;
  EXPECT_LT(e.estimate.radius, 1e-9) << what;  // still ~10 of double's digits
}

BorderCollisionQuestion question_of(const BranchEnd<double>& end, bool high, long period = 7) {
  BorderCollisionQuestion q;
  q.end.model = test_support::spec(Law::veldep, "28", "1", "1000");
  q.end.vary = Parameter::a;
  q.end.period = period;
  q.end.last_point = {parse_decimal("theta", ScalarTraits<double>::to_string(end.last_point.theta)),
                      parse_decimal("v", ScalarTraits<double>::to_string(end.last_point.v))};
  const auto [lo, hi] = branch_end_interval<double>(end.bracket_lo, end.bracket_hi, high, 53);
  q.end.lo = parse_decimal("lo", lo);
  q.end.hi = parse_decimal("hi", hi);
  q.end.high_end = high;
  if (end.margin >= 0) q.margin = static_cast<Margin>(end.margin);
  return q;
}

// Distance of the double bracket [blo, bhi] to the certified enclosure (0: they overlap).
double gap(double blo, double bhi, const mpq_class& clo, const mpq_class& chi) {
  const mpq_class lo(blo), hi(bhi);
  if (hi < clo) return mpq_class(clo - hi).get_d();
  if (chi < lo) return mpq_class(lo - chi).get_d();
  return 0;
}
double gap(double blo, double bhi, const BorderCollisionCertificate& c) { return gap(blo, bhi, c.lo, c.hi); }

TEST(BorderCollision, VeldepPeriod7EndsAgainstDoubleContinuation) {
  const Branch<double> b = veldep_p7();
  ASSERT_TRUE(b.started) << b.note;
  ASSERT_EQ(b.low.reason, EndReason::border) << b.low.detail;
  ASSERT_EQ(b.high.reason, EndReason::border) << b.high.detail;

  const BorderCollisionCertificate lo = certify_border_collision(question_of(b.low, false));
  ASSERT_TRUE(lo.certified) << lo.statement;
  EXPECT_EQ(lo.margin, Margin::knot) << lo.margin_text;  // impact 4 reaches theta = 1/2
  EXPECT_EQ(lo.knot, 1) << lo.margin_text;
  EXPECT_LE(lo.width, 1e-30);
  EXPECT_EQ(lo.orbit.size(), 7u);
  // The mpfr:128 continuation's a* (docs/guide/dynamics.md) lies in the enclosure, to its 32 digits.
  const mpq_class readme = parse_decimal("a", "27.720561305445859487642437424316").value();
  EXPECT_LT(std::fabs(mpq_class(readme - (lo.lo + lo.hi) / 2).get_d()), 1e-29) << lo.parameter.lo;
  // The double bracket is the truth to the location's tolerance, 2^-44 |a*| = 1.6e-12: the
  // secant steps on the knot margin end next to a*. (Bisection, before them, ended up to
  // 1.8e-11 off, at a point where Newton had converged past a*.)
  const double d_lo = gap(b.low.bracket_lo, b.low.bracket_hi, lo);
  EXPECT_LT(d_lo, 2e-12);
  // More bits: an enclosure inside the first (each is a theorem about the same a*).
  BorderCollisionQuestion q256 = question_of(b.low, false);
  q256.bits = 256;
  const BorderCollisionCertificate lo256 = certify_border_collision(q256);
  ASSERT_TRUE(lo256.certified) << lo256.statement;
  EXPECT_LE(lo.lo, lo256.lo);
  EXPECT_LE(lo256.hi, lo.hi);
  EXPECT_LE(lo256.width, 1e-70);
  // The widened bracket contains both enclosures.
  expect_estimate_contains(b.low, lo, "low end, 128 bits");
  expect_estimate_contains(b.low, lo256, "low end, 256 bits");

  const BorderCollisionCertificate hi = certify_border_collision(question_of(b.high, true));
  ASSERT_TRUE(hi.certified) << hi.statement;
  EXPECT_TRUE(hi.margin == Margin::knot || hi.margin == Margin::clearance) << hi.margin_text;
  EXPECT_LE(hi.width, 1e-30);
  const double d_hi = gap(b.high.bracket_lo, b.high.bracket_hi, hi);
  EXPECT_LT(d_hi, 2e-12);
  BorderCollisionQuestion h256 = question_of(b.high, true);
  h256.bits = 256;
  const BorderCollisionCertificate hi256 = certify_border_collision(h256);
  ASSERT_TRUE(hi256.certified) << hi256.statement;
  expect_estimate_contains(b.high, hi, "high end, 128 bits");
  expect_estimate_contains(b.high, hi256, "high end, 256 bits");
  std::printf("veldep P7 low end: double bracket [%.17g, %.17g], certified [%s, %s] (%s), double off by %.3g\n",
              b.low.bracket_lo, b.low.bracket_hi, lo.parameter.lo.c_str(), lo.parameter.hi.c_str(), lo.margin_text.c_str(),
              d_lo);
  std::printf("veldep P7 high end: double bracket [%.17g, %.17g], certified [%s, %s] (%s), double off by %.3g\n",
              b.high.bracket_lo, b.high.bracket_hi, hi.parameter.lo.c_str(), hi.parameter.hi.c_str(),
              hi.margin_text.c_str(), d_hi);
}

TEST(BorderCollision, VeldepUnstablePeriod7GrazingEnd) {
  // The unstable period-7 orbit (docs/guide/dynamics.md, "bouncer continue") ends going down where a flight
  // grazes theta = 1/2; issue 23 quotes an independent high-precision implementation's
  // a* = 24.61675675147981...
  const ModelSpec s = test_support::spec(Law::veldep, "25", "1", "1000");
  const Model<double> m = make_model<double>(s, 53);
  Branch<double> b =
      continue_branch(m, Parameter::a, 7, State<double>{0.016124178545083214, 10.063538832537404}, 22.0, 28.0);
  ASSERT_TRUE(b.started) << b.note;
  estimate_end_accuracy(s, b);
  ASSERT_EQ(b.low.reason, EndReason::border) << b.low.detail;
  BorderCollisionQuestion q = question_of(b.low, false);
  q.end.model = test_support::spec(Law::veldep, "25", "1", "1000");
  const BorderCollisionCertificate c = certify_border_collision(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.margin, Margin::clearance) << c.margin_text;
  EXPECT_LE(c.width, 1e-30);
  const mpq_class independent = parse_decimal("a", "24.61675675147981").value();
  EXPECT_LT(std::fabs(mpq_class(independent - c.lo).get_d()), 1e-14) << c.parameter.lo;
  expect_estimate_contains(b.low, c, "unstable low end");
  std::printf("veldep unstable P7 low end: double bracket [%.17g, %.17g], certified [%s, %s] (%s), double off by %.3g\n",
              b.low.bracket_lo, b.low.bracket_hi, c.parameter.lo.c_str(), c.parameter.hi.c_str(), c.margin_text.c_str(),
              gap(b.low.bracket_lo, b.low.bracket_hi, c));
}

// A long-period veldep (c = 1000) branch continued in double from `start` at a over [lo, hi],
// with its end estimates; one end certified at `bits` and checked against that truth: a knot
// margin, width <= 1e-30, the double bracket within 1e-9, the widened bracket containing a*.
BorderCollisionCertificate expect_long_period_end(const char* a, long period, State<double> start, double lo, double hi,
                                                  bool high, long bits,
                                                  Formulation how = Formulation::automatic) {
  const ModelSpec s = test_support::spec(Law::veldep, a, "1", "1000");
  Branch<double> b = continue_branch(make_model<double>(s, 53), Parameter::a, period, start, lo, hi);
  EXPECT_TRUE(b.started) << b.note;
  if (!b.started) return {};
  estimate_end_accuracy(s, b);
  const BranchEnd<double>& e = high ? b.high : b.low;
  EXPECT_EQ(e.reason, EndReason::border) << e.detail;
  if (e.reason != EndReason::border) return {};
  BorderCollisionQuestion q = question_of(e, high, period);
  q.bits = bits;
  q.formulation = how;
  const BorderCollisionCertificate c = certify_border_collision(q);
  EXPECT_TRUE(c.certified) << c.statement;
  if (!c.certified) return c;
  EXPECT_EQ(c.margin, Margin::knot) << c.margin_text;
  EXPECT_LE(c.width, 1e-30);
  EXPECT_LT(gap(e.bracket_lo, e.bracket_hi, c), 1e-9);
  expect_estimate_contains(e, c, high ? "high end" : "low end");
  return c;
}

TEST(BorderCollision, VeldepPeriod11EndWithACoincidentClearanceAndLongFlights) {
  // The stable period 11 at c = 1000 beside period 3 (attractors at a = 24.5: 13% of the
  // starts). At its high end impact 10 reaches the wall's top theta = 1/2 from above, so the
  // same flight's clearance at that corner vanishes with it (identity B of
  // coincident_clearance), and the other margins of eleven steps must be decided over the
  // branch side: one interval evaluation over the proof's box straddled 0 (+-0.3 for a
  // clearance of 0.1); the side is now cut into pieces with tight orbit enclosures. Truth
  // independent of the certifier: the double continuation's bracket (bisection on the
  // margin along Newton orbits) within 1e-9, and its widened bracket (the end re-located at
  // 117 bits) contains the enclosure.
  for (const bool high : {false, true})
    expect_long_period_end("24.5", 11, {0.01685443925323413, 25.227892214860187}, 24.0, 25.0, high, 128);
}

TEST(BorderCollision, ComposedAndShootingFormulationsEncloseTheSameEnd) {
  // Two different systems for the same a*: the composed map (unknowns x_0, p) and multiple
  // shooting (all 11 points and p; other Jacobian, other preconditioner, margins over other
  // boxes). Both must prove it, and their enclosures must intersect.
  const State<double> start{0.01685443925323413, 25.227892214860187};
  const BorderCollisionCertificate composed =
      expect_long_period_end("24.5", 11, start, 24.0, 25.0, true, 128, Formulation::composed);
  const BorderCollisionCertificate shot =
      expect_long_period_end("24.5", 11, start, 24.0, 25.0, true, 128, Formulation::shooting);
  ASSERT_TRUE(composed.certified && shot.certified);
  EXPECT_FALSE(composed.shooting);
  EXPECT_TRUE(shot.shooting);
  EXPECT_NE(shot.statement.find("multiple shooting"), std::string::npos) << shot.statement;
  EXPECT_LE(composed.lo, shot.hi);
  EXPECT_LE(shot.lo, composed.hi);
  EXPECT_EQ(composed.events, shot.events);
  EXPECT_EQ(composed.step, shot.step);
}

TEST(BorderCollision, VeldepLongPeriodEndsByMultipleShooting) {
  // The stable period 66 at c = 1000, a = 15.2 (every start of a 32 x 32 grid reaches it)
  // lives on a = 15.1876..15.2031 and ends at both sides where an impact reaches theta = 1/2.
  // Composed, sixty-six interval steps widen a box by about 2^66: at 128 bits no parameter
  // interval is both narrow enough for the Krawczyk operator and wide enough for the margins'
  // signs at its ends (bench_border: that needs 256 bits). Multiple shooting never composes:
  // proved at 128. Truth as for period 11: the double bracket within 1e-9, and the widened
  // bracket contains a*.
  const BorderCollisionCertificate c66 =
      expect_long_period_end("15.2", 66, {0.007894477576029256, 43.635535422440235}, 15.0, 15.5, /*high=*/false, 128);
  EXPECT_TRUE(c66.shooting);
  EXPECT_EQ(c66.bits, 128);
  // (The period-100 ends at a = 19.4979 and 19.5005, where composed intervals fail even at
  // 256 bits, are proved the same way: bench_border, 2 to 3 s each.)
}

TEST(BorderCollision, APeriod10EndIsNotMistakenForItsPeriod2Orbit) {
  // The stable period 10 at c = 1000, a = 18 (68% of a 32 x 32 grid), continued over
  // [15, 31] as `attractors --vary` does, ends at 18.1578 where an impact reaches theta =
  // 1/2. Newton for a fixed point of P^10 from the branch's last point converged to the
  // period-2 orbit (also a fixed point of P^10), and the proof followed that orbit to its
  // own border collision at 24.595: the reference orbit must have minimal period 10. Truth:
  // the double continuation's bracket within 1e-9 (24.595 is 6.4 away), and the enclosed
  // orbit has 10 points.
  const BorderCollisionCertificate c =
      expect_long_period_end("18", 10, {0.12741130263003148, 23.09769702060354}, 15.0, 31.0, /*high=*/true, 128);
  EXPECT_EQ(c.orbit.size(), 10u);
}

TEST(Fold, VeldepPeriod64FoldByMultipleShooting) {
  // The stable period 64 at c = 1000 lives on a = 16.89986..16.90042 and ends at its high end
  // in a fold. Sixty-four composed interval steps with second derivatives leave step 7's
  // impact undecided over the proof's box at 128 bits (composed, it is proved at 256, the
  // retry at twice the bits); multiple shooting (all 64 points unknowns, each step over its
  // own box) proves it at 128. Truth: the double bracket within 1e-8, a multiplier exactly 1
  // (the trace is 1 + det, both enclosed: checked as trace - det contains 1).
  const ModelSpec s = test_support::spec(Law::veldep, "16.9", "1", "1000");
  Branch<double> b = continue_branch(make_model<double>(s, 53), Parameter::a, 64,
                                     State<double>{0.00560367855987808, 15.194708996376361}, 16.89, 16.91);
  ASSERT_TRUE(b.started) << b.note;
  ASSERT_EQ(b.high.reason, EndReason::fold) << b.high.detail;
  PeriodDoublingQuestion q = smooth_event_question(s, Parameter::a, 64, b, b.high.param,
                                                   ScalarTraits<double>::to_string(b.high.bracket_lo),
                                                   ScalarTraits<double>::to_string(b.high.bracket_hi), 53);
  EXPECT_EQ(q.bits, 128);
  EXPECT_EQ(q.max_bits, 256);
  const PeriodDoublingCertificate c = certify_fold(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_EQ(c.bits, 128);
  EXPECT_NE(c.statement.find("multiple shooting"), std::string::npos) << c.statement;
  EXPECT_LE(c.width, 1e-30);
  EXPECT_LT(gap(b.high.bracket_lo, b.high.bracket_hi, c.lo, c.hi), 1e-8);
  // trace - det = 1 + mu - mu = 1 with the multipliers 1 and mu (det = mu).
  const mpq_class tlo = parse_decimal("lo", c.trace.lo).value(), thi = parse_decimal("hi", c.trace.hi).value();
  const mpq_class dlo = parse_decimal("lo", c.det.lo).value(), dhi = parse_decimal("hi", c.det.hi).value();
  EXPECT_LE(tlo - dhi, 1);
  EXPECT_GE(thi - dlo, 1);
}

// A doubling end: the stable period 62 at c = 1000 (a = 28.7, found by `attractors`) is
// born going up in a at the period doubling of a period-31 orbit; its multiplier +1 there is
// the period-31 orbit's -1 counted twice, which the multiplier test alone took for a fold
// (and a fold proof cannot succeed: two orbits, the period 62 and the period 31 traversed
// twice, meet in the box). Truth from a second computation: the period-31 branch, continued
// on its own from below, has a period doubling (regula falsi along that branch) within 1e-10
// of the period-62 end (bisection on the period-31 orbit from the period-62 branch's last
// orbit); the certified enclosure of the period-31 doubling lies within 1e-8 of both, and the
// end's error estimate (re-located at 117 bits) contains it.
TEST(PeriodDoubling, VeldepPeriod62IsBornAtThePeriod31Doubling) {
  const ModelSpec s = test_support::spec(Law::veldep, "28.7", "1", "1000");
  Branch<double> b = continue_branch(make_model<double>(s, 53), Parameter::a, 62,
                                     State<double>{0.02863575971809439, 15.428624909128757}, 28.699, 28.701);
  ASSERT_TRUE(b.started) << b.note;
  ASSERT_EQ(b.low.reason, EndReason::doubling) << b.low.detail;
  EXPECT_EQ(b.low.mother_period, 31);
  EXPECT_NE(b.low.detail.find("period-31"), std::string::npos) << b.low.detail;
  // Beyond the end Newton falls onto the period-31 orbit, named as the branch's mother.
  EXPECT_EQ(b.low.beyond_orbit_period, 31);
  EXPECT_EQ(b.low.beyond_relation, BeyondRelation::mother);
  // The period 62's own doubling (to 124) further up stays a bifurcation on the branch.
  ASSERT_FALSE(b.bifurcations.empty());
  EXPECT_EQ(b.bifurcations.front().kind, SmoothKind::period_doubling);

  const ModelSpec s31 = test_support::spec(Law::veldep, "28.6995", "1", "1000");
  const Branch<double> m = continue_branch(make_model<double>(s31, 53), Parameter::a, 31,
                                           State<double>{0.02863575971809439, 15.428624909128757}, 28.699, 28.7001);
  ASSERT_TRUE(m.started) << m.note;
  const Bifurcation<double>* pd = nullptr;
  for (const Bifurcation<double>& x : m.bifurcations)
    if (x.kind == SmoothKind::period_doubling) pd = &x;
  ASSERT_NE(pd, nullptr) << "the period-31 branch shows no period doubling";
  EXPECT_LT(std::fabs(pd->param - b.low.param), 1e-10);

  const std::optional<PeriodDoublingCertificate> c = certify_smooth_end(s, Parameter::a, 62, b, b.low, 53);
  ASSERT_TRUE(c.has_value());
  ASSERT_TRUE(c->certified) << c->statement;
  EXPECT_LE(c->width, 1e-30);
  EXPECT_LT(gap(b.low.bracket_lo, b.low.bracket_hi, c->lo, c->hi), 1e-8);
  EXPECT_LT(gap(pd->bracket_lo, pd->bracket_hi, c->lo, c->hi), 1e-8);
  EXPECT_NE(c->statement.find("period-31"), std::string::npos) << c->statement;
  // A period doubling proved by multiple shooting (automatic from period 12): the unit test
  // of that path (pd_value_shoot, pd_jet_shoot).
  EXPECT_NE(c->statement.find("multiple shooting"), std::string::npos) << c->statement;
  // The end's error estimate (a* re-located on the period-31 orbit at 117 bits) contains it.
  estimate_end_accuracy(s, b);
  ASSERT_EQ(b.low.estimate.kind, EndEstimate::Kind::estimate) << b.low.estimate.note;
  EXPECT_LE(b.low.estimate.lo, c->lo);
  EXPECT_GE(b.low.estimate.hi, c->hi);
}

// Period doubling on the eps = 0.9 period-2 branch (test_continuation.cpp): no closed form
// for a*, but truth independent of the certifier: the constant-eps map contracts area by
// eps^2 per impact, so det DP^2 = eps^4 and at a multiplier -1 the other is exactly
// -eps^4 = -0.6561 (the certifier computes det DP^2 by interval duals and never uses this).
TEST(PeriodDoubling, Eps09Period2AgainstTheAreaIdentity) {
  const Model<double> m = make_model<double>(test_support::spec(Law::constant, "19", "0.9"), 53);
  const Branch<double> b =
      continue_branch(m, Parameter::a, 2, State<double>{0.1678819228862684, 14.143149884133248}, 12.0, 21.0);
  ASSERT_EQ(b.bifurcations.size(), 1u);
  const Bifurcation<double>& pd = b.bifurcations[0];
  ASSERT_EQ(pd.kind, SmoothKind::period_doubling);
  const BranchPoint<double>* near = &b.points[0];
  for (const BranchPoint<double>& p : b.points)
    if (std::fabs(p.param - pd.param) < std::fabs(near->param - pd.param)) near = &p;
  PeriodDoublingQuestion q;
  q.model = test_support::spec(Law::constant, "19", "0.9");
  q.period = 2;
  q.point = {parse_decimal("theta", ScalarTraits<double>::to_string(near->orbit.points[0].theta)),
             parse_decimal("v", ScalarTraits<double>::to_string(near->orbit.points[0].v))};
  q.lo = parse_decimal("lo", ScalarTraits<double>::to_string(pd.bracket_lo));
  q.hi = parse_decimal("hi", ScalarTraits<double>::to_string(pd.bracket_hi));
  const PeriodDoublingCertificate c = certify_period_doubling(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_LE(c.width, 1e-30);
  // -eps^4 = -0.6561 exactly: inside the enclosure of the other multiplier, and det = eps^4.
  const mpq_class e4 = parse_decimal("e", "0.6561").value();
  EXPECT_LE(parse_decimal("lo", c.det.lo).value(), e4) << c.det.lo;
  EXPECT_GE(parse_decimal("hi", c.det.hi).value(), e4) << c.det.hi;
  EXPECT_LE(parse_decimal("lo", c.other.lo).value(), mpq_class(-e4));
  EXPECT_GE(parse_decimal("hi", c.other.hi).value(), mpq_class(-e4));
  // Double's located a* within its tolerance of the enclosure.
  EXPECT_LT(gap(pd.bracket_lo, pd.bracket_hi, c.lo, c.hi), 1e-8);
  std::printf("eps 0.9 P2 period doubling: double bracket [%.17g, %.17g], certified [%s, %s], other multiplier [%s, %s], %.3f s\n",
              pd.bracket_lo, pd.bracket_hi, c.parameter.lo.c_str(), c.parameter.hi.c_str(), c.other.lo.c_str(),
              c.other.hi.c_str(), c.seconds);
}

// A fold (saddle-node) with the same truth: the eps = 0.9 period-11 orbit (stable at a = 12.5,
// beside periods 6 and others) ends going down where a multiplier reaches +1; there the other
// multiplier is det DP^11 = eps^22 exactly (area contraction eps^2 per impact), which the
// certifier computes by interval duals without knowing it. The double continuation's bracket
// and its end estimate (the fold re-located by bisection at 117 bits, analysis/end_estimate.hpp)
// are checked against the enclosure: the first test of that re-location with a known a*.
TEST(Fold, Eps09Period11AgainstTheAreaIdentity) {
  const ModelSpec s = test_support::spec(Law::constant, "12.5", "0.9");
  Branch<double> b = continue_branch(make_model<double>(s, 53), Parameter::a, 11,
                                     State<double>{0.04780185758554826, 34.63889719838767}, 12.0, 13.0);
  ASSERT_TRUE(b.started) << b.note;
  estimate_end_accuracy(s, b);
  ASSERT_EQ(b.low.reason, EndReason::fold) << b.low.detail;
  PeriodDoublingQuestion q;
  q.model = s;
  q.period = 11;
  q.point = {parse_decimal("theta", ScalarTraits<double>::to_string(b.low.last_point.theta)),
             parse_decimal("v", ScalarTraits<double>::to_string(b.low.last_point.v))};
  q.lo = parse_decimal("lo", ScalarTraits<double>::to_string(b.low.bracket_lo));
  q.hi = parse_decimal("hi", ScalarTraits<double>::to_string(b.low.bracket_hi));
  const PeriodDoublingCertificate c = certify_fold(q);
  ASSERT_TRUE(c.certified) << c.statement;
  EXPECT_LE(c.width, 1e-30);
  mpq_class e22 = 1;
  for (int i = 0; i < 22; ++i) e22 *= mpq_class(9, 10);
  EXPECT_LE(parse_decimal("lo", c.other.lo).value(), e22) << c.other.lo;
  EXPECT_GE(parse_decimal("hi", c.other.hi).value(), e22) << c.other.hi;
  // trace = 1 + eps^22 (the multipliers 1 and eps^22).
  EXPECT_LE(parse_decimal("lo", c.trace.lo).value(), mpq_class(1 + e22)) << c.trace.lo;
  EXPECT_GE(parse_decimal("hi", c.trace.hi).value(), mpq_class(1 + e22)) << c.trace.hi;
  EXPECT_LT(gap(b.low.bracket_lo, b.low.bracket_hi, c.lo, c.hi), 1e-8);
  ASSERT_EQ(b.low.estimate.kind, EndEstimate::Kind::estimate) << b.low.estimate.note;
  EXPECT_LE(b.low.estimate.lo, c.lo) << b.low.estimate.lo.get_d() << " vs " << c.parameter.lo;
  EXPECT_GE(b.low.estimate.hi, c.hi) << b.low.estimate.hi.get_d() << " vs " << c.parameter.hi;
  std::printf("eps 0.9 P11 fold: double bracket [%.17g, %.17g], certified [%s, %s], other multiplier [%s, %s], %.3f s\n",
              b.low.bracket_lo, b.low.bracket_hi, c.parameter.lo.c_str(), c.parameter.hi.c_str(), c.other.lo.c_str(),
              c.other.hi.c_str(), c.seconds);
  // Far from the fold (the middle of the branch) Newton on the augmented system goes elsewhere
  // or the box fails: nothing is certified there.
  PeriodDoublingQuestion far = q;
  far.lo = parse_decimal("lo", "12.499");
  far.hi = parse_decimal("hi", "12.5");
  const PeriodDoublingCertificate none = certify_fold(far);
  EXPECT_FALSE(none.certified && none.lo <= mpq_class(12.5) && none.hi >= mpq_class(12.499)) << none.statement;
}

TEST(PeriodDoubling, NoMultiplierMinusOneIsNotCertified) {
  // At a = 19 the period-2 orbit's multipliers are far from -1 (the doubling is near 16.6).
  PeriodDoublingQuestion q;
  q.model = test_support::spec(Law::constant, "19", "0.9");
  q.period = 2;
  q.point = {parse_decimal("theta", "0.1678819228862684"), parse_decimal("v", "14.143149884133248")};
  q.lo = parse_decimal("lo", "19");
  q.hi = parse_decimal("hi", "19.00001");
  const PeriodDoublingCertificate c = certify_period_doubling(q);
  EXPECT_FALSE(c.certified) << c.statement;
  EXPECT_FALSE(c.reason.empty());
}

}  // namespace
}  // namespace bouncer
