// The velocity-dependent collapse test in the step (issue 3 item 4): the bound on the total
// chatter time is a true upper bound, and the step sticks only when the bound is below the
// time left in the segment.
#include <gtest/gtest.h>

#include <cmath>

#include "bouncer/model/impact_map.hpp"

namespace bouncer {
namespace {

ModelSpec veldep(const char* a, const char* c, bool collapse) {
  ModelSpec m;
  m.law = Law::veldep;
  m.a = *Decimal::parse(a);
  m.c = *Decimal::parse(c);
  m.wall = parse_wall("wall", "triangle");
  m.veldep_collapse = collapse;
  return m;
}

// The chatter recurrence w_{n+1} = w_n exp(-(w_n/c)^(3/5)), summed in long double until the
// terms no longer change the sum; w_n ~ n^(-5/3) so the tail after N terms is ~ N^(-2/3):
// add the integral tail estimate with the true asymptotics to stay an honest comparison.
long double chatter_sum(long double w, long double c, long n_terms) {
  long double sum = 0;
  for (long n = 0; n < n_terms; ++n) {
    sum += w;
    w *= std::exp(-std::pow(w / c, 0.6L));
  }
  return sum;
}

TEST(VeldepCollapse, BoundExceedsTheTrueChatterSum) {
  for (long double c : {1.0L, 10.0L, 1000.0L}) {
    for (long double w0 : {1e-3L, 0.1L, 1.0L, 8.0L}) {
      const long double bound = w0 + 2.5L * c * std::pow(w0 / c, 0.4L);
      const long double partial = chatter_sum(w0, c, 200000);
      EXPECT_GT(bound, partial) << "c=" << static_cast<double>(c) << " w0=" << static_cast<double>(w0);
      // The bound is not absurdly loose either (the sum converges like the integral).
      EXPECT_LT(bound, 20 * partial + 1e-12L);
    }
  }
}

TEST(VeldepCollapse, SticksOnlyWhenTheBoundIsBelowTheTimeLeft) {
  // Start on the up wall at theta = 0.1 with relative speed 0.5; a = 25.
  const InitialCondition ic{*Decimal::parse("0.1"), *Decimal::parse("4.5")};
  // c = 1: out ~ 0.5 exp(-0.66) ~ 0.26, bound (2/25)(0.26 + 2.5 * 0.26^0.4) ~ 0.13 < 0.36 left.
  {
    ImpactMap<double> map(make_model<double>(veldep("25", "1", true), 53));
    const StepResult<double> r = map.step(make_state<double>(ic, 53));
    EXPECT_EQ(r.kind, EventKind::sticking);
    EXPECT_EQ(r.next.theta, 0.5);
    EXPECT_EQ(r.next.v, 4.0);
    EXPECT_NEAR(r.tau, 0.4, 1e-15);  // collapse + ride to the corner
  }
  // Without the option the same start just bounces (exact chatter).
  {
    ImpactMap<double> map(make_model<double>(veldep("25", "1", false), 53));
    const StepResult<double> r = map.step(make_state<double>(ic, 53));
    EXPECT_EQ(r.kind, EventKind::impact);
    EXPECT_NEAR(r.next.theta, 0.1 + 2 * 0.5 / 25, 1e-15);
  }
  // c = 1000: eps ~ 1 - 0.01, the chatter is long: bound ~ 9.6 > 0.36, no sticking.
  {
    ImpactMap<double> map(make_model<double>(veldep("25", "1000", true), 53));
    EXPECT_EQ(map.step(make_state<double>(ic, 53)).kind, EventKind::impact);
  }
}

TEST(VeldepCollapse, IntervalDecisionIsCertain) {
  const InitialCondition ic{*Decimal::parse("0.1"), *Decimal::parse("4.5")};
  ImpactMap<Mpfi> map(make_model<Mpfi>(veldep("25", "1", true), 128));
  const StepResult<Mpfi> r = map.step(make_state<Mpfi>(ic, 128));
  EXPECT_EQ(r.kind, EventKind::sticking);
  EXPECT_TRUE(r.next.theta.contains(Mpfr(1, 128) / 2));
  EXPECT_TRUE(r.next.v.contains(Mpfr(4, 128)));
}

TEST(VeldepCollapse, OptionOnlyForVeldep) {
  ModelSpec m = veldep("25", "1", true);
  m.law = Law::constant;
  m.eps = *Decimal::parse("0.5");
  // model_from rejects it through the option parser; the spec itself just ignores it.
  ImpactMap<double> map(make_model<double>(m, 53));
  EXPECT_FALSE(map.model().law == Law::veldep);
}

}  // namespace
}  // namespace bouncer
