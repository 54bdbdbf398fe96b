// certify_branch_end (verify/branch_end.hpp), the certified end of a continued branch.
//
// Truth independent of the code: the period-1 sticking orbit through the release state
// (1/2, 4) of the constant-eps model exists for 8((1+eps)/(1-eps))^2 <= a < 32 (derivation in
// test_continuation.cpp's header), so at eps = 1/4 its branch in a ends at a* = 200/9 (the
// sticking threshold) and at a* = 32 (impact at the knot theta = 0), and (1/2, 4) is on the
// orbit for every a. A certified bound on the branch side must therefore satisfy
// bound <= 32 at the high end and bound >= 200/9 at the low end (anything else would be a
// false theorem), and the certified run must start at the branch side of the interval.
#include <gtest/gtest.h>

#include "bouncer/verify/branch_end.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

BranchEndQuestion question(const std::pair<std::string, std::string>& interval, bool high) {
  BranchEndQuestion q;
  q.model = test_support::spec(Law::constant, "24", "0.25");
  q.vary = Parameter::a;
  q.period = 1;
  q.last_point = {parse_decimal("theta", "0.5"), parse_decimal("v", "4")};
  q.lo = parse_decimal("lo", interval.first);
  q.hi = parse_decimal("hi", interval.second);
  q.high_end = high;
  return q;
}

TEST(BranchEnd, IntervalIsOnTheBranchSideOfTheBracket) {
  // High end: [g - 1e-6 max(1, |g|), g] with g the bracket's low end; low end: [g, g + w].
  const auto [lo, hi] = branch_end_interval<double>(31.5, 32.5, true, 53);
  EXPECT_EQ(parse_decimal("hi", hi).value(), mpq_class(63, 2));
  EXPECT_NEAR(parse_decimal("lo", lo).approx(), 31.5 - 31.5e-6, 1e-12);
  const auto [lo2, hi2] = branch_end_interval<double>(0.25, 0.5, false, 53);
  EXPECT_EQ(parse_decimal("lo", lo2).value(), mpq_class(1, 2));
  EXPECT_NEAR(parse_decimal("hi", hi2).approx(), 0.5 + 1e-6, 1e-15);  // max(1, |g|) = 1
}

TEST(BranchEnd, IntervalStaysOnAShortBranch) {
  // A branch of length 8e-6 (the period 1096 at veldep c = 1000 around a = 21): the width is
  // a quarter of it, 2e-6, not 1e-6 |a| = 2.1e-5, which would reach past the branch's other end.
  const auto [lo, hi] = branch_end_interval<double>(21.0000044, 21.0000045, true, 53, 8e-6);
  EXPECT_NEAR(parse_decimal("hi", hi).approx() - parse_decimal("lo", lo).approx(), 2e-6, 1e-12);
  const auto [lo2, hi2] = branch_end_interval<double>(20.9999955, 20.9999956, false, 53, 8e-6);
  EXPECT_NEAR(parse_decimal("hi", hi2).approx() - parse_decimal("lo", lo2).approx(), 2e-6, 1e-12);
  // A long branch keeps 1e-6 |a|.
  const auto [lo3, hi3] = branch_end_interval<double>(31.5, 32.5, true, 53, 10.0);
  EXPECT_NEAR(parse_decimal("hi", hi3).approx() - parse_decimal("lo", lo3).approx(), 31.5e-6, 1e-12);
}

TEST(BranchEnd, HighEndBoundIsBelowTheKnotAtA32) {
  const BranchEndQuestion q = question(branch_end_interval<double>(32 - 1e-9, 32, true, 53), true);
  const BranchEndCertificate c = certify_branch_end(q);
  ASSERT_TRUE(c.certified) << c.theorem;
  EXPECT_EQ(c.from, q.lo.value());  // the run starts at the branch side
  EXPECT_EQ(c.bound, c.to);
  EXPECT_LE(c.bound, mpq_class(32));
  EXPECT_GT(c.bound, q.lo.value());
  EXPECT_GE(c.pieces, 1u);
  EXPECT_FALSE(c.events.empty());
}

TEST(BranchEnd, LowEndBoundIsAboveTheStickingThreshold) {
  const BranchEndQuestion q = question(branch_end_interval<double>(200.0 / 9 - 1e-9, 200.0 / 9 + 1e-9, false, 53), false);
  const BranchEndCertificate c = certify_branch_end(q);
  ASSERT_TRUE(c.certified) << c.theorem;
  EXPECT_EQ(c.to, q.hi.value());  // the run starts at the branch side
  EXPECT_EQ(c.bound, c.from);
  EXPECT_GE(c.bound, mpq_class(200, 9));
  EXPECT_LT(c.bound, q.hi.value());
}

TEST(BranchEnd, NothingIsCertifiedBeyondTheEnd) {
  // Past a* = 32 there is no period-1 orbit through (1/2, 4) with these events: an interval
  // entirely beyond it must not be certified.
  const BranchEndQuestion q = question({"32.001", "32.002"}, true);
  EXPECT_FALSE(certify_branch_end(q).certified);
}

}  // namespace
}  // namespace bouncer
