// sin(2 pi x) and cos(2 pi x) of the interval types (ScalarTraits<Mpfi> and
// ScalarTraits<DoubleInterval>::sin_2pi / cos_2pi, scalar.cpp trig_2pi_enclosure) against MPFR
// at 256 bits, computed here directly: every value of the function over the interval lies in
// the enclosure (the ends, interior points, and the extrema k/4 that the interval contains),
// and the enclosure is tight: its ends are within a few ulps of the true minimum and maximum,
// which are the values at the ends or +-1 where an extremum lies inside. Random intervals,
// intervals around the extrema and zeros, thin points, long intervals, large arguments.
#include <gtest/gtest.h>
#include <mpfr.h>

#include <cmath>
#include <random>

#include "bouncer/scalar/traits.hpp"

namespace bouncer {
namespace {

// f(2 pi x) at 256 bits, x a double (exact).
double true_value(double x, bool cosine, mpfr_rnd_t rnd) {
  mpfr_t t;
  mpfr_init2(t, 256);
  mpfr_set_d(t, x, MPFR_RNDN);
  mpfr_mul_2ui(t, t, 1, MPFR_RNDN);
  if (cosine) mpfr_cospi(t, t, MPFR_RNDN);
  else mpfr_sinpi(t, t, MPFR_RNDN);
  const double r = mpfr_get_d(t, rnd);
  mpfr_clear(t);
  return r;
}

// The true range of f over [lo, hi] (doubles, rounded outward): the ends, or +-1 where the
// interval holds a maximum (1/4 + k for the sine, k for the cosine) or a minimum (3/4 + k,
// 1/2 + k), tested in exact rationals via long double (lo, hi are modest here).
std::pair<double, double> true_range(double lo, double hi, bool cosine) {
  double mn = std::min(true_value(lo, cosine, MPFR_RNDD), true_value(hi, cosine, MPFR_RNDD));
  double mx = std::max(true_value(lo, cosine, MPFR_RNDU), true_value(hi, cosine, MPFR_RNDU));
  auto holds = [&](long double offset) {
    const long double k = std::ceil(static_cast<long double>(lo) - offset);
    return k + offset <= static_cast<long double>(hi);
  };
  if (hi - lo >= 1 || holds(cosine ? 0.0L : 0.25L)) mx = 1;
  if (hi - lo >= 1 || holds(cosine ? 0.5L : 0.75L)) mn = -1;
  return {mn, mx};
}

void check(double lo, double hi, int& checked) {
  for (bool cosine : {false, true}) {
    const DoubleInterval x(lo, hi);
    const DoubleInterval e = cosine ? ScalarTraits<DoubleInterval>::cos_2pi(x) : ScalarTraits<DoubleInterval>::sin_2pi(x);
    Mpfr mlo(53), mhi(53);
    mpfr_set_d(mlo.get(), lo, MPFR_RNDN);
    mpfr_set_d(mhi.get(), hi, MPFR_RNDN);
    const Mpfi xm(mlo, mhi);
    const Mpfi em = cosine ? ScalarTraits<Mpfi>::cos_2pi(xm) : ScalarTraits<Mpfi>::sin_2pi(xm);
    const double em_lo = mpfr_get_d(&em.get()->left, MPFR_RNDD), em_hi = mpfr_get_d(&em.get()->right, MPFR_RNDU);
    const auto [mn, mx] = true_range(lo, hi, cosine);
    SCOPED_TRACE(std::string(cosine ? "cos" : "sin") + "(2 pi [" + std::to_string(lo) + ", " + std::to_string(hi) + "])");
    // Containment: the true range's ends (each a value of f over [lo, hi], or its extremum).
    EXPECT_LE(e.lower(), mn);
    EXPECT_GE(e.upper(), mx);
    EXPECT_LE(em_lo, mn);
    EXPECT_GE(em_hi, mx);
    // Interior points too.
    for (int i = 1; i < 8; ++i) {
      const double t = lo + (hi - lo) * i / 8;
      if (!(t >= lo && t <= hi)) continue;
      const double vlo = true_value(t, cosine, MPFR_RNDD), vhi = true_value(t, cosine, MPFR_RNDU);
      EXPECT_LE(e.lower(), vlo);
      EXPECT_GE(e.upper(), vhi);
      EXPECT_LE(em_lo, vlo);
      EXPECT_GE(em_hi, vhi);
    }
    // Tightness: within 4 ulps of the true range (the ends are directed roundings of f at the
    // interval's ends, or exactly +-1).
    const double ulp = 4 * std::ldexp(1.0, -52);
    EXPECT_GE(e.lower(), mn - ulp);
    EXPECT_LE(e.upper(), mx + ulp);
    EXPECT_GE(em_lo, mn - ulp);
    EXPECT_LE(em_hi, mx + ulp);
    ++checked;
  }
}

TEST(TrigEnclosure, RandomIntervalsContainEveryValueAndAreTight) {
  std::mt19937_64 gen(20261128);
  std::uniform_real_distribution<double> centre(-3, 3);
  std::uniform_real_distribution<double> log_width(-17, 0.3);
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const double c = centre(gen), w = std::pow(10.0, log_width(gen));
    check(c - w / 2, c + w / 2, checked);
  }
  EXPECT_EQ(checked, 800);
}

TEST(TrigEnclosure, ExtremaZerosPointsLongAndLargeArguments) {
  int checked = 0;
  for (double k : {-2.0, 0.0, 1.0, 37.0})
    for (double q : {0.0, 0.25, 0.5, 0.75}) {
      const double x = k + q;
      check(x, x, checked);                                       // a point (exact extremum or zero)
      check(std::nextafter(x, -10.0), std::nextafter(x, 10.0), checked);  // an extremum inside by an ulp
      check(x + 1e-12, x + 2e-12, checked);                       // just beside it, monotone
      check(x - 2e-12, x - 1e-12, checked);
    }
  check(0.1, 1.1, checked);         // width exactly 1: both extrema
  check(-5.3, 7.9, checked);        // long
  check(1e6 + 0.2, 1e6 + 0.3, checked);  // large argument (contains 1e6 + 1/4)
  check(123456.78, 123456.78, checked);
  EXPECT_GT(checked, 130);
}

// A long flight's phase is (theta + tau), far from [0, 1): the enclosure is about the exact
// double argument, with no rounded pi (MPFR's sinpi of the exact 2x).
TEST(TrigEnclosure, TwoPiIsEnclosed) {
  const DoubleInterval tp = ScalarTraits<DoubleInterval>::two_pi(53);
  mpfr_t pi;
  mpfr_init2(pi, 256);
  mpfr_const_pi(pi, MPFR_RNDN);
  mpfr_mul_2ui(pi, pi, 1, MPFR_RNDN);
  EXPECT_LE(tp.lower(), mpfr_get_d(pi, MPFR_RNDD));
  EXPECT_GE(tp.upper(), mpfr_get_d(pi, MPFR_RNDU));
  EXPECT_EQ(std::nextafter(tp.lower(), 10.0), tp.upper());  // the tightest double enclosure
  const Mpfi tm = ScalarTraits<Mpfi>::two_pi(128);
  EXPECT_LE(mpfr_cmp(&tm.get()->left, pi), 0);
  EXPECT_GE(mpfr_cmp(&tm.get()->right, pi), 0);
  mpfr_clear(pi);
}

}  // namespace
}  // namespace bouncer
