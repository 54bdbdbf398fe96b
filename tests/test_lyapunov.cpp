// Leading Lyapunov exponents against independent truth:
//   * sticking: -inf (the release state does not depend on the input);
//   * a periodic orbit of the constant-eps model with a complex pair of multipliers: the
//     measure identity det J = eps^2 (v0-u0)/(v1-u1) telescopes over a period to eps^(2q),
//     so |mu| = eps^q and lambda = log(eps) exactly;
//   * the eq. 5 fixed-point family: multipliers {1, eps^2}, so the leading exponent is 0;
//   * chaotic orbits (velocity-dependent attractor at a = 27, c = 1000; the elastic chaotic
//     sea at a = 20): lambda > 0, and the AD value equals the growth rate of the distance
//     of two orbits 1e-60 apart iterated separately at 256 bits (no derivatives at all).
#include <gtest/gtest.h>

#include <cmath>

#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "test_support.hpp"

using namespace bouncer;
using bouncer::test_support::spec;

namespace {

constexpr long kBits = 256;

Mpfr mp(const std::string& s) { return ScalarTraits<Mpfr>::from_decimal(s, kBits); }

// Finite-time exponent from two orbits: log(|y_N - x_N| / delta) / N, y_0 = x_0 + delta (1,1)/sqrt 2.
double separation_rate(const Model<Mpfr>& m, State<Mpfr> x, long N) {
  const ImpactMap<Mpfr> map(m);
  Mpfr delta(1, kBits);
  mpfr_div_2si(delta.get(), delta.get(), 200, MPFR_RNDN);  // 2^-200 ~ 6e-61
  const Mpfr d = delta / sqrt(Mpfr(2, kBits));
  State<Mpfr> y{x.theta + d, x.v + d};
  for (long n = 0; n < N; ++n) {
    x = map.step(x).next;
    y = map.step(y).next;
  }
  Mpfr dt = y.theta - x.theta;
  dt = dt - floor(dt + Mpfr(1, kBits) / 2);  // theta on the circle
  const Mpfr dv = y.v - x.v;
  return (log(sqrt(dt * dt + dv * dv) / delta)).to_double() / static_cast<double>(N);
}

}  // namespace

TEST(Lyapunov, StickingIsMinusInfinity) {
  const Model<double> m = make_model<double>(spec(Law::constant, "30", "0.3"), 53);
  LyapunovOptions o;
  o.transient = 10;
  o.steps = 1000;
  const LyapunovResult r = lyapunov(m, State<double>{0.3, 9}, o);
  EXPECT_TRUE(r.contracted);
  EXPECT_TRUE(std::isinf(r.lambda) && r.lambda < 0);
  EXPECT_NE(r.note.find("sticking"), std::string::npos) << r.note;
  EXPECT_NE(r.note.find("does not depend on the input"), std::string::npos) << r.note;
}

TEST(Lyapunov, StablePeriodicOrbitHasLogEps) {
  // The period-2 orbit of a = 19, eps = 0.9 has a complex pair of multipliers.
  const Model<double> m = make_model<double>(spec(Law::constant, "19", "0.9"), 53);
  const PeriodicOrbit<double> o = search_periodic(m, 2);
  ASSERT_TRUE(o.converged && o.minimal_period == 2 && o.multipliers.complex);
  LyapunovOptions opt;
  opt.transient = 200;
  opt.steps = 4000;
  const LyapunovResult r = lyapunov(m, State<double>{o.points[0].theta + 1e-4, o.points[0].v - 1e-3}, opt);
  ASSERT_FALSE(r.contracted || r.undecided || r.unbounded) << r.note;
  EXPECT_NEAR(r.lambda, std::log(0.9), 2e-3) << "stderr " << r.stderr_;
  EXPECT_LT(r.lambda, 0);
  // Also in MPFR.
  const Model<Mpfr> mm = make_model<Mpfr>(spec(Law::constant, "19", "0.9"), 128);
  opt.steps = 1000;
  const LyapunovResult rm =
      lyapunov(mm, State<Mpfr>{ScalarTraits<Mpfr>::from_decimal(std::to_string(o.points[0].theta + 1e-4), 128),
                               ScalarTraits<Mpfr>::from_decimal(std::to_string(o.points[0].v - 1e-3), 128)},
               opt);
  EXPECT_NEAR(rm.lambda, std::log(0.9), 5e-3);
}

TEST(Lyapunov, FixedPointFamilyIsMarginal) {
  // a = 24, eps = 0.5: multipliers {1, 1/4}; the leading exponent is log 1 = 0 (the second
  // would be log(eps^2) = -1.386).
  const Model<double> m = make_model<double>(spec(Law::constant, "24", "0.5"), 53);
  LyapunovOptions opt;
  opt.transient = 100;
  opt.steps = 5000;
  const LyapunovResult r = lyapunov(m, State<double>{0.3, 11.5}, opt);
  ASSERT_FALSE(r.contracted || r.undecided) << r.note;
  EXPECT_NEAR(r.lambda, 0, 1e-3);
  EXPECT_GT(r.lambda, std::log(0.25) / 2);
}

TEST(Lyapunov, VelocityDependentAttractorIsChaotic) {
  const ModelSpec s = spec(Law::veldep, "27");
  LyapunovOptions opt;
  opt.transient = 2000;
  opt.steps = 20000;
  const LyapunovResult r = lyapunov(make_model<double>(s, 53), State<double>{0.3, 6}, opt);
  ASSERT_FALSE(r.contracted || r.undecided || r.unbounded) << r.note;
  EXPECT_GT(r.lambda, 0.03);
  EXPECT_GT(r.lambda, 5 * r.stderr_);
  // Independent: separation of two orbits at 256 bits over the same stretch.
  const Model<Mpfr> mm = make_model<Mpfr>(s, kBits);
  State<Mpfr> x{mp("0.3"), mp("6")};
  const ImpactMap<Mpfr> map(mm);
  for (int i = 0; i < 2000; ++i) x = map.step(x).next;
  LyapunovOptions one;
  one.transient = 0;
  one.steps = 500;
  one.blocks = 1;
  const LyapunovResult ad = lyapunov(mm, x, one);
  const double sep = separation_rate(mm, x, 500);
  EXPECT_NEAR(ad.lambda, sep, 1e-6);
  EXPECT_GT(sep, 0.02);
}

TEST(Lyapunov, ElasticChaoticSeaIsPositive) {
  const ModelSpec s = spec(Law::elastic, "20");
  const Model<Mpfr> mm = make_model<Mpfr>(s, kBits);
  LyapunovOptions one;
  one.transient = 0;
  one.steps = 1000;  // lambda ~ 0.07: the separation stays ~1e-28, linear
  one.blocks = 10;
  const State<Mpfr> x{mp("0.3"), mp("9")};
  const LyapunovResult ad = lyapunov(mm, x, one);
  ASSERT_FALSE(ad.contracted || ad.undecided) << ad.note;
  const double sep = separation_rate(mm, x, 1000);
  EXPECT_NEAR(ad.lambda, sep, 1e-6);
  EXPECT_GT(ad.lambda, 0.02);
  // The double run over a longer stretch agrees in sign and flags the slow growth of v.
  LyapunovOptions opt;
  opt.transient = 0;
  opt.steps = 20000;
  const LyapunovResult rd = lyapunov(make_model<double>(s, 53), State<double>{0.3, 9}, opt);
  EXPECT_GT(rd.lambda, 3 * rd.stderr_);
}

TEST(Lyapunov, EllipticIslandIsQuasiperiodic) {
  // Near the elastic period-2 orbit of a = 16 (multipliers on the unit circle): lambda ~ 0.
  const Model<double> m = make_model<double>(spec(Law::elastic, "16"), 53);
  const PeriodicOrbit<double> o = find_periodic(m, 2, State<double>{0.25, 44});
  ASSERT_TRUE(o.converged);
  LyapunovOptions opt;
  opt.transient = 0;
  opt.steps = 20000;
  const LyapunovResult r = lyapunov(m, State<double>{o.points[0].theta + 1e-3, o.points[0].v}, opt);
  ASSERT_FALSE(r.contracted || r.undecided || r.unbounded) << r.note;
  EXPECT_LT(std::fabs(r.lambda), 2e-3);
}
