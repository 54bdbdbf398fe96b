// Honest digits of a located branch end (analysis/end_estimate.hpp, estimate_end_accuracy in
// analysis/continuation.hpp, issue 23).
//
// Truth, independent of the estimate:
//   * backed_digits: hand-rounded decimals, and the containment it promises checked in
//     exact rationals;
//   * the ends the suite computes elsewhere, each with its widened double bracket checked to
//     contain a*: the closed forms 200/9 (sticking threshold), 32 (knot) and 2 - sqrt(3)
//     (threshold in eps, mpfr:128 run; derivations in test_continuation.cpp's header), and a
//     sign change of det(J + I) at 256 bits across a period doubling's widened bracket. The
//     velocity-dependent period-7 ends (27.72, 28.76 and the unstable orbit's 24.62), which
//     have no closed form and where the double bracket itself misses a*, are checked in
//     test_border_collision.cpp against the Krawczyk enclosures of a* at 128 and 256 bits
//     (a proof, and a tighter truth than a point run at mpfr:256, at no extra cost there).
#include <gtest/gtest.h>

#include <random>

#include "bouncer/analysis/continuation.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using test_support::spec;

mpq_class q(const std::string& text) { return parse_decimal("x", text).value(); }
mpq_class q_of(const Mpfr& x) {
  mpq_class r;
  mpfr_get_q(r.get_mpq_t(), x.get());
  return r;
}

TEST(BackedDigits, RoundsToTheRadiusLeadingDigit) {
  // 27.720561305427225 -+ 7.2e-11: the 1e-11 place; rounding the center moves it by
  // 2.775e-12, so the radius shown is ceil(7.4775) = 8 units.
  const BackedDigits d = backed_digits(q("27.720561305427225"), 7.2e-11);
  EXPECT_EQ(d.value, "27.72056130543");
  EXPECT_EQ(d.plus_minus, "8e-11");
  EXPECT_EQ(d.digits, 13);
  EXPECT_EQ(d.lo, "27.72056130535");  // floor(27.720561305355225)
  EXPECT_EQ(d.hi, "27.72056130550");  // ceil(27.720561305499225): the trailing 0 is a digit
  // A radius that rounds up to 10 units goes to the next place.
  const BackedDigits e = backed_digits(q("1"), 9.6e-5);
  EXPECT_EQ(e.value, "1.0000");
  EXPECT_EQ(e.plus_minus, "1e-4");
  EXPECT_EQ(e.digits, 5);
  const BackedDigits f = backed_digits(q("0.00123456"), 3e-7);
  EXPECT_EQ(f.value, "0.0012346");
  EXPECT_EQ(f.plus_minus, "4e-7");
  EXPECT_EQ(f.digits, 5);
  EXPECT_THROW(backed_digits(q("1"), 0), std::invalid_argument);
}

TEST(BackedDigits, TheShownIntervalContainsTheEstimate) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 2000; ++i) {
    const double c = (unit(rng) - 0.3) * std::pow(10.0, 6 * unit(rng) - 2);
    const double r = std::pow(10.0, -16 * unit(rng)) * std::max(std::fabs(c), 1e-3);
    const mpq_class center(c), radius(r);
    const BackedDigits d = backed_digits(center, r);
    const mpq_class v = q(d.value), pm = q(d.plus_minus);
    EXPECT_LE(v - pm, center - radius) << c << " " << r;
    EXPECT_GE(v + pm, center + radius) << c << " " << r;
    EXPECT_LE(q(d.lo), center - radius);
    EXPECT_GE(q(d.hi), center + radius);
    EXPECT_LE(pm, 20 * radius);  // at most one place coarser than the radius
  }
}

TEST(EndEstimate, ValueTextByKind) {
  EndEstimate e;
  EXPECT_EQ(end_value_text(e, "1.25"), "1.25 (accuracy not estimated)");
  e.kind = EndEstimate::Kind::given;
  EXPECT_EQ(end_value_text(e, "1.25"), "1.25");
  e.kind = EndEstimate::Kind::estimate;
  e.center = q("22.222222222222221");
  e.radius = 1.5e-12;
  EXPECT_EQ(end_value_text(e, "22.222222222222221"), "22.222222222222 ± 2e-12 (estimate)");
}

// The widened bracket [lo, hi] of an estimated end contains `truth`.
void expect_contains(const EndEstimate& e, const mpq_class& truth, const std::string& what) {
  ASSERT_EQ(e.kind, EndEstimate::Kind::estimate) << what << ": " << e.note;
  EXPECT_LE(e.lo, truth) << what << ": " << e.lo.get_d() << " " << truth.get_d();
  EXPECT_GE(e.hi, truth) << what << ": " << e.hi.get_d() << " " << truth.get_d();
  // The printed digits are those of the bracket: it is no wider than 10x the estimate's radius
  // and the radius no wider than needed by far (1e-9 relative is ~4 digits lost in double).
  EXPECT_LT(e.radius, 1e-9 * std::max(1.0, std::fabs(truth.get_d()))) << what;
}

TEST(EndEstimate, ClosedFormEndsInDouble) {
  // eps = 1/4: the sticking threshold a* = 200/9 below, the knot a* = 32 above.
  const ModelSpec s = spec(Law::constant, "26", "0.25");
  const Model<double> m = make_model<double>(s, 53);
  Branch<double> b = continue_branch(m, Parameter::a, 1, State<double>{0.5, 4}, 20.0, 33.5);
  ASSERT_EQ(b.low.reason, EndReason::border);
  ASSERT_EQ(b.high.reason, EndReason::border);
  estimate_end_accuracy(s, b);
  expect_contains(b.low.estimate, mpq_class(200, 9), "200/9");
  expect_contains(b.high.estimate, mpq_class(32), "32");
  EXPECT_EQ(b.low.estimate.bits, 53 + 64);
  EXPECT_EQ(b.low.estimate.center, mpq_class(b.low.param));
  // The re-located a* is the closed form to far more than double's digits.
  EXPECT_LT(std::fabs(mpq_class(q(b.low.estimate.refined) - mpq_class(200, 9)).get_d()), 1e-18);
  EXPECT_LT(std::fabs(mpq_class(q(b.high.estimate.refined) - 32).get_d()), 1e-18);
  // A range end is the value where the branch stopped: nothing to widen.
  Branch<double> r = continue_branch(m, Parameter::a, 1, State<double>{0.5, 4}, 20.0, 31.0);
  estimate_end_accuracy(s, r);
  EXPECT_EQ(r.high.reason, EndReason::range_end);
  EXPECT_EQ(r.high.estimate.kind, EndEstimate::Kind::given);
  expect_contains(r.low.estimate, mpq_class(200, 9), "200/9 (range 20:31)");
}

// The same two closed-form ends in the other fixed-width point types (64 and 106 bits).
template <class T>
void closed_form_ends_in(long bits) {
  using Tr = ScalarTraits<T>;
  const ModelSpec s = spec(Law::constant, "26", "0.25");
  Branch<T> b = continue_branch(make_model<T>(s, bits), Parameter::a, 1, State<T>{Tr::from_decimal("0.5", bits), Tr::from_int(4, bits)},
                                Tr::from_int(20, bits), Tr::from_decimal("33.5", bits));
  ASSERT_EQ(b.low.reason, EndReason::border);
  ASSERT_EQ(b.high.reason, EndReason::border);
  estimate_end_accuracy(s, b);
  expect_contains(b.low.estimate, mpq_class(200, 9), "200/9");
  expect_contains(b.high.estimate, mpq_class(32), "32");
  EXPECT_EQ(b.low.estimate.bits, Tr::bits(b.low.param) + 64);
  EXPECT_LT(b.low.estimate.radius, 1e-14);  // more digits than double's
}
TEST(EndEstimate, ClosedFormEndsInLongDoubleAndDoubleDouble) {
  closed_form_ends_in<long double>(64);
  closed_form_ends_in<DoubleDouble>(106);
}

TEST(EndEstimate, ThresholdInEpsAtMpfr128) {
  // eps* = 2 - sqrt(3) at a = 24, located at 128 bits and re-located at 192.
  const ModelSpec s = spec(Law::constant, "24", "0.2");
  const Model<Mpfr> m = make_model<Mpfr>(s, 128);
  const Mpfr lo = ScalarTraits<Mpfr>::from_decimal("0.1", 128), hi = ScalarTraits<Mpfr>::from_decimal("0.4", 128);
  Branch<Mpfr> b = continue_branch(m, Parameter::eps, 1, State<Mpfr>{ScalarTraits<Mpfr>::from_decimal("0.5", 128), Mpfr(4, 128)}, lo, hi);
  ASSERT_EQ(b.high.reason, EndReason::border);
  estimate_end_accuracy(s, b);
  EXPECT_EQ(b.high.estimate.bits, 128 + 64);
  // 2 - sqrt(3) enclosed by two 300-bit roundings.
  Mpfr three(3, 300), r_lo(300), r_hi(300);
  mpfr_sqrt(r_hi.get(), three.get(), MPFR_RNDD);  // sqrt rounded down: 2 - it is an upper bound
  mpfr_sqrt(r_lo.get(), three.get(), MPFR_RNDU);
  const mpq_class t_lo = 2 - q_of(r_lo), t_hi = 2 - q_of(r_hi);
  expect_contains(b.high.estimate, t_lo, "2 - sqrt(3), lower");
  expect_contains(b.high.estimate, t_hi, "2 - sqrt(3), upper");
  EXPECT_LT(b.high.estimate.radius, 1e-30);
  EXPECT_EQ(b.low.estimate.kind, EndEstimate::Kind::given);
}

TEST(EndEstimate, Eps09Period2KnotEndAgainstMpfr256) {
  // The period-2 branch of eps = 0.9 (docs/guide/dynamics.md, "bouncer continue") ends at a* ~ 22.0114 where
  // impact 1 reaches theta = 1/2; no closed form: a* located by the same continuation at
  // mpfr:256 (to 2^-244 relative; classification beyond off) is the truth. A regression
  // case too: a re-location that predicted its first trial orbit as constant over the 4.6e-6
  // to a* had Newton fail there and reported a false end 2.3e-6 early.
  const ModelSpec s = spec(Law::constant, "19", "0.9");
  const State<double> guess{0.1678819228862684, 14.143149884133248};
  Branch<double> b = continue_branch(make_model<double>(s, 53), Parameter::a, 2, guess, 19.0, 23.0);
  ASSERT_EQ(b.high.reason, EndReason::border) << b.high.detail;
  estimate_end_accuracy(s, b);
  ContinuationOptions opt;
  opt.classify_beyond = false;
  const auto up = [](double x) { return ScalarTraits<Mpfr>::from_decimal(ScalarTraits<double>::to_string(x), 256); };
  // From the double branch's orbit nearest a = 22 (a short run: 256 bits are slow).
  const BranchPoint<double>* near = &b.points.front();
  for (const BranchPoint<double>& p : b.points)
    if (std::fabs(p.param - 22) < std::fabs(near->param - 22)) near = &p;
  const std::string at = ScalarTraits<double>::to_string(near->param);
  const Branch<Mpfr> t = continue_branch(make_model<Mpfr>(spec(Law::constant, at, "0.9"), 256), Parameter::a, 2,
                                         State<Mpfr>{up(near->orbit.points[0].theta), up(near->orbit.points[0].v)},
                                         up(near->param), ScalarTraits<Mpfr>::from_decimal("22.1", 256), opt);
  ASSERT_EQ(t.high.reason, EndReason::border) << t.high.detail;
  expect_contains(b.high.estimate, q_of(t.high.param), "eps = 0.9 period-2 high end");
}

TEST(EndEstimate, PeriodDoublingIsInsideTheWidenedBracket) {
  // The period-2 branch of eps = 0.9 (test_continuation.cpp) doubles near a = 15.78. Truth
  // without the locator: at 256 bits, the orbit's det(J + I) (0 at a multiplier -1) has
  // opposite signs at the two ends of the widened bracket, so a* lies between them.
  const ModelSpec s = spec(Law::constant, "19", "0.9");
  const Model<double> m = make_model<double>(s, 53);
  Branch<double> b = continue_branch(m, Parameter::a, 2, State<double>{0.1678819228862684, 14.143149884133248}, 12.0, 21.0);
  ASSERT_EQ(b.bifurcations.size(), 1u);
  estimate_end_accuracy(s, b);
  const Bifurcation<double>& pd = b.bifurcations[0];
  ASSERT_EQ(pd.estimate.kind, EndEstimate::Kind::estimate) << pd.estimate.note;
  EXPECT_LT(pd.estimate.radius, 1e-9 * pd.param);
  const State<double>& near = b.points[b.start].orbit.points[0];
  const Model<Mpfr> m256 = make_model<Mpfr>(s, 256);
  const auto test_pd = [&](const mpq_class& a) {
    Mpfr x(256);
    mpfr_set_q(x.get(), a.get_mpq_t(), MPFR_RNDN);
    const Model<Mpfr> at = with_parameter(m256, Parameter::a, x);
    const auto up = [](double d) {
      Mpfr r(256);
      mpfr_set_d(r.get(), d, MPFR_RNDN);
      return r;
    };
    const State<Mpfr> guess{up(near.theta), up(near.v)};
    const PeriodicOrbit<Mpfr> o = find_periodic(at, 2, guess);
    EXPECT_TRUE(o.converged);
    return analyse_orbit(at, Parameter::a, o).test_pd;
  };
  EXPECT_LT(test_pd(pd.estimate.lo) * test_pd(pd.estimate.hi), 0);
}

}  // namespace
}  // namespace bouncer
