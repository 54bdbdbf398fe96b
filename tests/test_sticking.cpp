// Certified sticking periods (verify/sticking.hpp) against independent truth.
//
// Analytic truth, derived by hand: from the release state (1/2, 4) the particle leaves the
// downward wall (velocity -4) with relative speed 8. In the wall's frame (inertial on the
// segment) the gap is 8 s - a s^2 / 2, so if 16/a < 1/2 (a > 32) it lands on the same
// segment at theta_1 = 1/2 + 16/a with relative speed 8, and bounces with out = 8 eps. The
// collapse completes before theta = 1 iff out <= a (1 - eps)/2 (1 - theta_1) =
// (1 - eps)(a/4 - 8), i.e. iff a >= 32 / (1 - eps). So the sticking period is 1 exactly
// for a >= 32/(1 - eps) (with equality included, the library's "<=" convention), and the
// first step is an impact at (1/2 + 16/a, -4 + 8 eps) for 32 < a < 32/(1 - eps).
#include <gtest/gtest.h>

#include "bouncer/verify/sticking.hpp"

namespace bouncer {
namespace {

StickingQuestion question(const char* a, const char* eps, long long max_steps = 2000) {
  StickingQuestion q;
  q.model.law = Law::constant;
  q.model.a = *Decimal::parse(a);
  q.model.eps = *Decimal::parse(eps);
  q.model.wall = parse_wall("wall", "triangle");
  q.max_steps = max_steps;
  q.schedule = EscalationSchedule{64, 1024};
  return q;
}

TEST(StickingPeriod, OneAboveTheAnalyticThreshold) {
  // eps = 1/2: threshold a = 64; eps = 1/5: threshold a = 40.
  for (const char* a : {"64", "64.000001", "70", "100"}) {
    const StickingCertificate c = certify_sticking(question(a, "0.5"));
    ASSERT_EQ(c.outcome, StickingOutcome::sticks) << a;
    EXPECT_TRUE(c.certified);
    EXPECT_EQ(*c.period, 1) << a;
    EXPECT_EQ(c.steps_checked, 0);
  }
  const StickingCertificate c = certify_sticking(question("40.000001", "0.2"));
  ASSERT_EQ(c.outcome, StickingOutcome::sticks);
  EXPECT_EQ(*c.period, 1);
}

TEST(StickingPeriod, ExactlyAtANonDyadicThresholdIsUndecided) {
  // eps = 0.2 is not a binary fraction: at a = 40 exactly the test out <= threshold is an
  // equality of two enclosures that overlap at every precision. The certificate must not
  // guess (eps = 0.5, a = 64 is exact in binary and is decided: see above).
  const StickingCertificate c = certify_sticking(question("40", "0.2"));
  EXPECT_EQ(c.outcome, StickingOutcome::undecided);
  EXPECT_FALSE(c.certified);
  EXPECT_EQ(c.steps_checked, 0);
  EXPECT_NE(c.reason.find(describe(Reason::sticking_threshold)), std::string::npos) << c.reason;
}

TEST(StickingPeriod, NotOneBelowTheAnalyticThreshold) {
  for (const char* a : {"63.999999", "50", "33"}) {
    const StickingCertificate c = certify_sticking(question(a, "0.5"));
    EXPECT_NE(c.outcome, StickingOutcome::undecided) << a;
    if (c.outcome == StickingOutcome::sticks) {
      EXPECT_GT(*c.period, 1) << a;
    }
    EXPECT_GE(c.steps_checked, 1) << a;
  }
}

TEST(StickingPeriod, ExactCornerHitIsUndecidedNotGuessed) {
  // eps = 1/2, a = 63.5: in the wall's frame the chatter after the release has relative
  // speeds 8, 4, 2, ... and flights 2 w / a, so theta_k = 1/2 + (32/a)(1 - 2^-k). For
  // a = 63.5 = 64 (1 - 2^-7), theta_7 = 1 exactly: the 7th impact is exactly at the corner
  // (0 < theta_1..theta_6 < 1, none sticks: 8 eps > (1 - eps)(a/4 - 8) and later
  // collapses overrun theta = 1). Intervals cannot decide an exact equality: undecided at
  // step 7 at every precision, with steps 1..6 certified.
  const StickingCertificate c = certify_sticking(question("63.5", "0.5"));
  EXPECT_EQ(c.outcome, StickingOutcome::undecided);
  EXPECT_EQ(c.steps_checked, 6);
  EXPECT_NE(c.reason.find(describe(Reason::impact_at_corner)), std::string::npos) << c.reason;
}

TEST(StickingPeriod, FirstImpactMatchesTheAnalyticFormula) {
  // a = 50, eps = 1/2: theta_1 = 1/2 + 16/50 = 0.82, v_1 = -4 + 4 = 0.
  const ModelSpec m = question("50", "0.5").model;
  OrbitEnclosure orbit(interval_model(m, 256), make_state<Mpfi>({*Decimal::parse("0.5"), Decimal::from_int(4)}, 256),
                       EnclosureMethod::lohner);
  const EnclosedStep s = orbit.step();
  EXPECT_EQ(s.event.kind, EventKind::impact);
  EXPECT_TRUE(s.next.theta.contains(ScalarTraits<Mpfr>::from_decimal("0.82", 256)));
  EXPECT_TRUE(s.next.v.contains(Mpfr(0, 256)));
  EXPECT_LT(s.next.theta.width().to_double(), 1e-60);
}

TEST(StickingPeriod, RangeAboveThresholdIsAllPeriodOne) {
  StickingQuestion q = question("64", "0.5");
  q.a_range = std::make_pair(Decimal::parse("64")->value(), Decimal::parse("80")->value());
  const RangeReport r = certify_sticking_range(q, RangeOptions{4, 40});
  EXPECT_EQ(r.uncertified_length, 0);
  for (const RangePiece& p : r.pieces) {
    ASSERT_EQ(p.cert.outcome, StickingOutcome::sticks);
    EXPECT_EQ(*p.cert.period, 1);
  }
  EXPECT_NE(r.theorem.find("1 for a in [64, 80]"), std::string::npos) << r.theorem;
}

TEST(StickingPeriod, AgreesWithAPlainRunAt1024Bits) {
  // Independent: the plain MPFR run at 1024 bits (no intervals, no Lohner).
  for (auto [a, eps] : {std::pair{"24", "0.5"}, std::pair{"28.82", "0.5"}, std::pair{"50", "0.5"},
                        std::pair{"33.3", "0.7"}, std::pair{"45", "0.3"}}) {
    const StickingQuestion q = question(a, eps);
    const StickingCertificate c = certify_sticking(q);
    const PlainSticking p = plain_sticking_period<Mpfr>(q.model, q.start, 1024, q.max_steps);
    ASSERT_TRUE(c.certified) << a << " " << eps << ": " << c.reason;
    if (c.outcome == StickingOutcome::sticks) {
      ASSERT_TRUE(p.period) << a << " " << eps;
      EXPECT_EQ(*c.period, *p.period) << a << " " << eps;
    } else {
      EXPECT_FALSE(p.period) << a << " " << eps;
    }
  }
}

TEST(StickingPeriod, RangeIsConsistentWithPointRuns) {
  StickingQuestion q = question("24", "0.5", 500);
  q.a_range = std::make_pair(Decimal::parse("24")->value(), Decimal::parse("25")->value());
  const RangeReport r = certify_sticking_range(q, RangeOptions{5, 60});
  ASSERT_FALSE(r.pieces.empty());
  mpq_class covered = 0;
  int checked = 0;
  for (const RangePiece& p : r.pieces) {
    covered += p.hi - p.lo;
    if (!p.cert.certified || checked >= 6) continue;
    for (const mpq_class& x : {mpq_class(p.lo), mpq_class((p.lo + p.hi) / 2), mpq_class(p.hi)}) {
      StickingQuestion pq = question(exact_decimal(x).c_str(), "0.5", 500);
      const StickingCertificate c = certify_sticking(pq);
      ASSERT_TRUE(c.certified) << exact_decimal(x);
      EXPECT_EQ(c.outcome, p.cert.outcome) << exact_decimal(x);
      if (c.outcome == StickingOutcome::sticks) {
        EXPECT_EQ(*c.period, *p.cert.period) << exact_decimal(x);
      }
      ++checked;
    }
  }
  EXPECT_EQ(covered, 1);  // the pieces tile [24, 25]
  EXPECT_GT(checked, 0);
}

TEST(StickingPeriod, PaperCaseFallsOntoAPeriodicAttractor) {
  // eps = 0.96, a = 28.82 (paper Fig. 4b: "sticking with period k > 1000"). Independent
  // evidence for the certified answer: a plain 256-bit run sees no sticking in 20000 steps
  // and recurs with the same period.
  StickingQuestion q = question("28.82", "0.96", 20000);
  const StickingCertificate c = certify_sticking(q);
  ASSERT_EQ(c.outcome, StickingOutcome::never_sticks) << describe(c, q.max_steps);
  ASSERT_TRUE(c.attractor);
  EXPECT_EQ(c.attractor->iterate % c.attractor->period, 0);
  const ImpactMap<Mpfr> map(make_model<Mpfr>(q.model, 256));
  State<Mpfr> x = make_state<Mpfr>(q.start, 256);
  std::vector<State<Mpfr>> tail;
  for (long n = 1; n <= 20000; ++n) {
    const StepResult<Mpfr> r = map.step(x);
    ASSERT_EQ(r.kind, EventKind::impact) << n;
    x = r.next;
    if (n > 20000 - 2 * c.attractor->period) tail.push_back(x);
  }
  const State<Mpfr>& back = tail[tail.size() - 1 - c.attractor->period];
  EXPECT_LT(std::fabs((back.theta - x.theta).to_double()) + std::fabs((back.v - x.v).to_double()), 1e-9);
}

TEST(StickingPeriod, RejectsOtherLaws) {
  StickingQuestion q = question("24", "0.5");
  q.model.law = Law::elastic;
  EXPECT_THROW(certify_sticking(q), InputError);
}

TEST(ExactDecimal, PrintsBisectionPointsExactly) {
  EXPECT_EQ(exact_decimal(mpq_class(1, 8)), "0.125");
  EXPECT_EQ(exact_decimal(mpq_class(-3, 4)), "-0.75");
  EXPECT_EQ(exact_decimal(mpq_class(29)), "29");
  EXPECT_EQ(exact_decimal(Decimal::parse("28.8203125")->value()), "28.8203125");
  EXPECT_EQ(exact_decimal((Decimal::parse("28.82")->value() + Decimal::parse("28.83")->value()) / 2), "28.825");
  EXPECT_EQ(exact_decimal(mpq_class(1, 3)), "1/3");
}

}  // namespace
}  // namespace bouncer
