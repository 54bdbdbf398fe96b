// The precision sweep (verify/sweep.hpp) against independent truth:
//   * the default list: every point type of the scalar set (scalar_set.hpp), those of
//     variable precision at 64, 128, ..., 4096 bits, each text parsing back;
//   * the eq. 5 fixed point (constant eps = 1/2, a = 24, start (1/4, 12), flight time one
//     period; derivation in test_orbit_io.cpp): every precision stays inside the certified
//     enclosure and settles on period 1, certified free of sticking;
//   * the period-1 sticking orbit through R = (1/2, 4) at eps = 1/4, a = 24 (tests/README.md
//     "Continuation"): every precision and the reference stick at step 1;
//   * the exact corner hit from R at eps = 1/2, a = 63.5 (test_sticking.cpp: the 7th impact
//     is at theta = 1): no reference covers step 7, so the report says it covers 1..6;
//   * a chaotic elastic orbit (a = 24, start (0.1, 7)): where a precision of b bits leaves
//     the enclosure is compared with an experiment outside the sweep, in MPFR at 600 bits:
//     the step at which a start moved by 2^-b drifts 2^-20 from the unmoved one. Rounding
//     at every step makes a run leave somewhat earlier than a single perturbation; the two
//     must agree within a factor of 2, and the implied Lyapunov exponent with the
//     experiment's ln 2 (128 - 64) / (n(128) - n(64)) within a factor of 1.5.
// Runs are short: at most 450 steps, references up to 1024 bits.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <map>
#include <set>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/verify/sweep.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using test_support::spec;

SweepQuestion question(const ModelSpec& m, const char* theta, const char* v, long long steps,
                       std::vector<std::string> precisions) {
  SweepQuestion q;
  q.model = m;
  q.start = {*Decimal::parse(theta), *Decimal::parse(v)};
  q.steps = steps;
  q.reference = EscalationSchedule{64, 1024};
  for (const std::string& p : precisions) q.precisions.push_back(parse_precision("precision", p));
  q.max_period = 50;
  q.classify_steps = 100;
  return q;
}

const SweepRow& row(const SweepReport& r, const std::string& precision) {
  for (const SweepRow& x : r.rows)
    if (x.precision == precision) return x;
  ADD_FAILURE() << "no row " << precision;
  static const SweepRow none;
  return none;
}

TEST(SweepPrecisions, TheDefaultListIsEveryPointTypeAtDoublingBits) {
  const std::vector<Precision> list = default_sweep_precisions();
  std::set<std::string> texts;
  std::vector<long> mpfr_bits;
  for (const Precision& p : list) {
    EXPECT_FALSE(p.is_interval()) << p.text();
    EXPECT_TRUE(texts.insert(p.text()).second) << "twice: " << p.text();
    const Precision back = parse_precision("precision", p.text());
    EXPECT_EQ(back.kind, p.kind);
    EXPECT_EQ(back.bits, p.bits);
    if (p.kind == Precision::Kind::mpfr) mpfr_bits.push_back(p.bits);
  }
  for (const char* fixed : {"double", "long", "dd", "quad"}) EXPECT_EQ(texts.count(fixed), 1u) << fixed;
  EXPECT_EQ(mpfr_bits, (std::vector<long>{64, 128, 256, 512, 1024, 2048, 4096}));
  EXPECT_EQ(list.size(), 11u);
}

TEST(PrecisionSweep, TheEq5FixedPointStaysInsideAtEveryPrecision) {
  const SweepQuestion q =
      question(spec(Law::constant, "24", "0.5"), "0.25", "12", 40, {"double", "long", "mpfr:128", "interval:64"});
  const SweepReport r = precision_sweep(q);
  EXPECT_EQ(r.reference_steps, 40);
  EXPECT_EQ(r.reference_status, "covers all 40 steps");
  EXPECT_EQ(r.reference_answer, "no sticking within 40 steps, certified");
  EXPECT_FALSE(r.reference_attempts.empty());
  ASSERT_EQ(r.rows.size(), 3u);  // an interval precision is not a point run: left out
  for (const SweepRow& x : r.rows) {
    EXPECT_FALSE(x.leaves_at.has_value()) << x.precision << ": " << x.why;
    EXPECT_FALSE(x.sticking_period.has_value()) << x.precision;
    ASSERT_TRUE(x.attractor_period.has_value()) << x.precision << ": " << x.answer;
    EXPECT_EQ(*x.attractor_period, 1) << x.precision;
    EXPECT_FALSE(x.classification.has_value()) << x.precision;
    EXPECT_EQ(x.answer, "no sticking within 40 steps; settles on a period-1 orbit");
  }
  EXPECT_EQ(row(r, "long").bits, 64);
  EXPECT_EQ(row(r, "mpfr:128").bits, 128);
  EXPECT_FALSE(r.slope.has_value());  // no run left the enclosure: nothing to fit
  EXPECT_FALSE(r.implied_lyapunov.has_value());
}

TEST(PrecisionSweep, TheReleaseStateSticksAtStepOneEverywhere) {
  const SweepReport r = precision_sweep(question(spec(Law::constant, "24", "0.25"), "0.5", "4", 5, {"double", "quad", "mpfr:256"}));
  EXPECT_EQ(r.reference_steps, 5);
  EXPECT_EQ(r.reference_answer, "sticks at step 1 (sticking period 1), certified");
  ASSERT_EQ(r.rows.size(), 3u);
  for (const SweepRow& x : r.rows) {
    ASSERT_TRUE(x.sticking_period.has_value()) << x.precision;
    EXPECT_EQ(*x.sticking_period, 1) << x.precision;
    EXPECT_FALSE(x.leaves_at.has_value()) << x.precision << ": " << x.why;
    EXPECT_FALSE(x.attractor_period.has_value()) << x.precision;
  }
}

TEST(PrecisionSweep, AReferenceStoppedByAnExactCornerSaysHowFarItReaches) {
  const SweepQuestion q = question(spec(Law::constant, "63.5", "0.5"), "0.5", "4", 10, {"double", "mpfr:128"});
  const SweepReport r = precision_sweep(q);
  EXPECT_EQ(r.reference_steps, 6);  // step 7 is the corner hit
  EXPECT_EQ(r.reference_status.rfind("covers steps 1..6; ", 0), 0u) << r.reference_status;
  EXPECT_EQ(r.reference_answer, "no sticking within 6 steps, certified");
  // The attempts went up the whole schedule (64 ... 1024 bits), none deciding step 7.
  ASSERT_FALSE(r.reference_attempts.empty());
  EXPECT_EQ(r.reference_attempts.back().bits, 1024);
  for (const Attempt& a : r.reference_attempts) {
    EXPECT_FALSE(a.decided) << a.scalar;
    EXPECT_EQ(a.steps, 6) << a.scalar;
  }
  // The point runs agree with the reference as far as it reaches.
  for (const SweepRow& x : r.rows) EXPECT_FALSE(x.leaves_at.has_value()) << x.precision << ": " << x.why;
}

// The step at which the orbit of a start moved by 2^-b in theta is 2^-20 away from the
// orbit of the start (max norm, theta on the circle), in MPFR at 600 bits.
long long perturbed_departure(const ModelSpec& m, const InitialCondition& s, int b, long long steps) {
  const ImpactMap<Mpfr> map(make_model<Mpfr>(m, 600));
  State<Mpfr> x = make_state<Mpfr>(map.model(), s), y = x;
  mpfr_t d;
  mpfr_init2(d, 600);
  mpfr_set_ui_2exp(d, 1, -b, MPFR_RNDN);
  mpfr_add(y.theta.get(), y.theta.get(), d, MPFR_RNDN);
  mpfr_clear(d);
  for (long long n = 1; n <= steps; ++n) {
    x = map.step(x).next;
    y = map.step(y).next;
    double dt = std::fabs(x.theta.to_double() - y.theta.to_double());
    dt = std::min(dt, 1 - dt);
    const double dv = std::fabs(x.v.to_double() - y.v.to_double());
    if (std::max(dt, dv) > 0x1p-20) return n;
  }
  return steps + 1;
}

TEST(PrecisionSweep, AChaoticOrbitLeavesWhereAnErrorOfItsBitsGrowsToTheTolerance) {
  const ModelSpec m = spec(Law::elastic, "24");
  const long long steps = 450;
  const SweepQuestion q = question(m, "0.1", "7", steps, {"double", "mpfr:64", "mpfr:128", "mpfr:512"});
  const SweepReport r = precision_sweep(q);
  ASSERT_EQ(r.reference_steps, steps) << r.reference_status;
  const std::vector<std::pair<std::string, int>> runs{{"double", 53}, {"mpfr:64", 64}, {"mpfr:128", 128}};
  std::map<int, long long> pert;
  long long previous = 0;
  for (const auto& [name, bits] : runs) {
    pert[bits] = perturbed_departure(m, q.start, bits, steps);
    ASSERT_LE(pert[bits], steps) << bits;
    const SweepRow& x = row(r, name);
    ASSERT_TRUE(x.leaves_at.has_value()) << name;
    EXPECT_GE(2 * *x.leaves_at, pert[bits]) << name << " leaves at " << *x.leaves_at << ", the 2^-" << bits << " experiment at " << pert[bits];
    EXPECT_LE(*x.leaves_at, 2 * pert[bits]) << name << " leaves at " << *x.leaves_at << ", the 2^-" << bits << " experiment at " << pert[bits];
    EXPECT_GE(*x.leaves_at, previous) << name << ": more bits must not leave earlier";
    previous = *x.leaves_at;
    EXPECT_FALSE(x.sticking_period.has_value()) << name;  // nothing sticks at eps = 1
  }
  EXPECT_FALSE(row(r, "mpfr:512").leaves_at.has_value()) << row(r, "mpfr:512").why;
  ASSERT_TRUE(r.slope.has_value());
  ASSERT_TRUE(r.implied_lyapunov.has_value());
  EXPECT_NEAR(*r.implied_lyapunov, std::log(2.0) / *r.slope, 1e-12);
  const double lambda = std::log(2.0) * (128 - 64) / static_cast<double>(pert[128] - pert[64]);
  EXPECT_GT(*r.implied_lyapunov, lambda / 1.5) << "experiment: " << lambda;
  EXPECT_LT(*r.implied_lyapunov, lambda * 1.5) << "experiment: " << lambda;
}

}  // namespace
}  // namespace bouncer
