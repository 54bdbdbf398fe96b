// DoubleInterval (interval:double), checked against MPFR: every operation's ends against
// MPFR's directed rounding of the same exact operation (equal to RNDD / RNDU rounded to
// double, subnormals and overflow included), bit for bit against MPFI at 53 bits on random
// intervals, decimal enclosures, the printed ends, the branch predicates on hand-made cases,
// the conventions for invalid results shared with Mpfi (empty intersections, NaN operands,
// square roots below 0), and whole certified runs: a
// Lohner orbit in DoubleInterval holds the 512-bit MPFR orbit, and certify-sticking gives
// the same certificates with the interval:double tier as with MPFI alone.
// (Randomized containment of the whole step in every model, and of its Jacobian: the
// DoubleInterval case of tests/test_interval_containment.cpp.)
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <utility>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "bouncer/verify/sticking.hpp"

namespace bouncer {
namespace {

using D = DoubleInterval;
using Tr = ScalarTraits<D>;
using interval_double_detail::next_down;
using interval_double_detail::next_up;

// A random double: sign, exponent in [-60, 60], 53 random bits; now and then an integer, a
// power of two, a number near 1 or a subnormal, where rounding is exact or borderline.
double random_double(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 9), ex(-60, 60), small(-20, 20);
  std::uniform_real_distribution<double> U(0.5, 1.0);
  const double sign = rng() & 1 ? -1.0 : 1.0;
  switch (kind(rng)) {
    case 0: return sign * small(rng);
    case 1: return sign * std::ldexp(1.0, ex(rng));
    case 2: return sign * (1.0 + std::ldexp(static_cast<double>(rng() % 1024), -52));
    case 3: return sign * std::ldexp(U(rng), -1060);  // subnormal
    default: return sign * std::ldexp(U(rng), ex(rng));
  }
}

// Where every transformation is exact (interval_double.hpp): 0, or 2^-900 <= |x| < 2^900.
bool normal_range(double x) { return x == 0 || (std::fabs(x) >= 0x1p-900 && std::fabs(x) < 0x1p900); }

// MPFR's result of a 2-argument operation at 53 bits, rounded as asked (a double exactly).
using Op2 = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_srcptr, mpfr_rnd_t);
using Op1 = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t);
double mpfr2(Op2 f, double x, double y, mpfr_rnd_t rnd) {
  mpfr_t a, b, r;
  mpfr_inits2(53, a, b, r, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_d(a, x, MPFR_RNDN);
  mpfr_set_d(b, y, MPFR_RNDN);
  f(r, a, b, rnd);
  const double out = mpfr_get_d(r, rnd);
  mpfr_clears(a, b, r, static_cast<mpfr_ptr>(nullptr));
  return out;
}
double mpfr1(Op1 f, double x, mpfr_rnd_t rnd) {
  mpfr_t a, r;
  mpfr_inits2(53, a, r, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_d(a, x, MPFR_RNDN);
  f(r, a, rnd);
  const double out = mpfr_get_d(r, rnd);
  mpfr_clears(a, r, static_cast<mpfr_ptr>(nullptr));
  return out;
}

// The interval's ends are [down, up] (MPFR's directed results over the corners, rounded to
// double in the same direction): the tightest enclosure.
void expect_tight_enclosure(const D& r, double down, double up, const std::string& what) {
  EXPECT_LE(r.lower(), down) << what << ": lower end above MPFR's RNDD";
  EXPECT_GE(r.upper(), up) << what << ": upper end below MPFR's RNDU";
  EXPECT_EQ(r.lower(), down) << what << ": lower end below MPFR's RNDD";
  EXPECT_EQ(r.upper(), up) << what << ": upper end above MPFR's RNDU";
}

TEST(IntervalDouble, NextUpAndDownStepOneDouble) {
  EXPECT_EQ(next_up(1.0), 1.0 + 0x1p-52);
  EXPECT_EQ(next_down(1.0), 1.0 - 0x1p-53);
  EXPECT_EQ(next_up(0.0), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(next_down(0.0), -std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(next_up(-std::numeric_limits<double>::denorm_min()), 0.0);
  EXPECT_EQ(next_up(std::numeric_limits<double>::max()), std::numeric_limits<double>::infinity());
  EXPECT_EQ(next_up(std::numeric_limits<double>::infinity()), std::numeric_limits<double>::infinity());
  EXPECT_EQ(next_down(-std::numeric_limits<double>::infinity()), -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(next_up(std::nan(""))));
  for (double x : {0.1, -3.5, 1e300, -1e-310, 7.0})
    EXPECT_EQ(next_up(x), std::nextafter(x, std::numeric_limits<double>::infinity())) << x;
}

// The branch-free rounding step (bit arithmetic, no branch on the error's sign) is checked
// against std::nextafter, the C library's own definition of the next double, at the ends of
// the range, both zeros, the subnormals and across the sign change.
TEST(IntervalDouble, BranchFreeRoundingStepsLikeNextafter) {
  using interval_double_detail::round_to;
  const double inf = std::numeric_limits<double>::infinity(), tiny = std::numeric_limits<double>::denorm_min();
  const double big = std::numeric_limits<double>::max(), low = std::numeric_limits<double>::min();
  auto same = [](double x, double y) { return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y) || (x == 0 && y == 0); };
  for (double c : {0.0, -0.0, tiny, -tiny, 2 * tiny, -2 * tiny, low, -low, 1.0, -1.0, 0.1, -0.1, 1e300, -1e300, big, -big}) {
    for (double e : {-1e-300, -0.0, 0.0, 1e-300, -1.0, 1.0}) {
      const double up = e > 0 ? std::nextafter(c, inf) : c;
      const double down = e < 0 ? std::nextafter(c, -inf) : c;
      EXPECT_TRUE(same(round_to<true>(c, e), up)) << c << " error sign " << e << ": " << round_to<true>(c, e);
      EXPECT_TRUE(same(round_to<false>(c, e), down)) << c << " error sign " << e << ": " << round_to<false>(c, e);
      EXPECT_GE(round_to<true>(c, e), c);
      EXPECT_LE(round_to<false>(c, e), c);
    }
  }
}

TEST(IntervalDouble, ArithmeticOnPointsIsDirectedRounding) {
  std::mt19937_64 rng(20261124);
  struct Case {
    const char* name;
    Op2 mpfr;
    std::function<D(const D&, const D&)> f;
  };
  const Case cases[] = {
      {"+", mpfr_add, [](const D& x, const D& y) { return x + y; }},
      {"-", mpfr_sub, [](const D& x, const D& y) { return x - y; }},
      {"*", mpfr_mul, [](const D& x, const D& y) { return x * y; }},
      {"/", mpfr_div, [](const D& x, const D& y) { return x / y; }},
  };
  for (const Case& c : cases) {
    for (int i = 0; i < 20000; ++i) {
      const double x = random_double(rng), y = random_double(rng);
      if (c.mpfr == mpfr_div && y == 0) continue;
      const D r = c.f(D(x, x), D(y, y));
      const double down = mpfr2(c.mpfr, x, y, MPFR_RNDD), up = mpfr2(c.mpfr, x, y, MPFR_RNDU);
      const std::string what = std::to_string(x) + " " + c.name + " " + std::to_string(y);
      // Subnormal operands and results included (the slow paths scale them).
      expect_tight_enclosure(r, down, up, what);
      if (::testing::Test::HasFailure()) return;
    }
  }
}

TEST(IntervalDouble, ArithmeticOnWideIntervalsEnclosesEveryCorner) {
  std::mt19937_64 rng(7);
  auto wide = [&rng]() {
    double a = random_double(rng), b = random_double(rng);
    if (rng() % 4 == 0) b = a;  // thin now and then
    return D(std::min(a, b), std::max(a, b));
  };
  for (int i = 0; i < 20000; ++i) {
    const D x = wide(), y = wide();
    const double xs[2] = {x.lower(), x.upper()}, ys[2] = {y.lower(), y.upper()};
    struct Op {
      Op2 f;
      D r;
      const char* name;
    };
    std::vector<Op> ops = {{mpfr_add, x + y, "+"}, {mpfr_sub, x - y, "-"}, {mpfr_mul, x * y, "*"}};
    const bool divisor_has_zero = y.lower() <= 0 && y.upper() >= 0;
    if (!divisor_has_zero) ops.push_back({mpfr_div, x / y, "/"});
    else EXPECT_FALSE(Tr::is_finite(x / y)) << "a divisor holding 0 gives no bound";
    for (const Op& op : ops) {
      double down = std::numeric_limits<double>::infinity(), up = -down;
      for (double a : xs)
        for (double b : ys) {
          down = std::min(down, mpfr2(op.f, a, b, MPFR_RNDD));
          up = std::max(up, mpfr2(op.f, a, b, MPFR_RNDU));
        }
      // + and - are monotone in each argument and * and / are bilinear / monotone on sign-
      // definite boxes: the extremes over the box are at corners.
      expect_tight_enclosure(op.r, down, up, std::string("wide ") + op.name);
    }
    if (::testing::Test::HasFailure()) return;
  }
}

// The same operations on random intervals, bit for bit against MPFI at 53 bits (whose ends
// are MPFR's directed roundings): the fast type is as tight as MPFI at its precision.
TEST(IntervalDouble, BitForBitWithMpfiAt53Bits) {
  std::mt19937_64 rng(53);
  auto wide = [&rng]() {
    double a = std::ldexp(random_double(rng), 0), b = random_double(rng);
    if (!normal_range(a)) a = 1.5;
    if (!normal_range(b) || rng() % 3 == 0) b = a;
    return D(std::min(a, b), std::max(a, b));
  };
  auto md = [](double v) {
    Mpfr r(53);
    mpfr_set_d(r.get(), v, MPFR_RNDN);  // exact
    return r;
  };
  auto mpfi = [&md](const D& x) { return Mpfi(md(x.lower()), md(x.upper())); };
  auto same = [](const D& x, const Mpfi& m) {
    return mpfr_cmp_d(&m.get()->left, x.lower()) == 0 && mpfr_cmp_d(&m.get()->right, x.upper()) == 0;
  };
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const D x = wide(), y = wide();
    const Mpfi mx = mpfi(x), my = mpfi(y);
    EXPECT_TRUE(same(x + y, mx + my)) << Tr::to_string(x) << " + " << Tr::to_string(y);
    EXPECT_TRUE(same(x - y, mx - my)) << Tr::to_string(x) << " - " << Tr::to_string(y);
    EXPECT_TRUE(same(x * y, mx * my)) << Tr::to_string(x) << " * " << Tr::to_string(y);
    if (y.lower() > 0 || y.upper() < 0) {
      const D q = x / y;
      if (normal_range(q.lower()) && normal_range(q.upper())) {
        EXPECT_TRUE(same(q, mx / my)) << Tr::to_string(x) << " / " << Tr::to_string(y);
      }
    }
    if (x.lower() > 0) {
      EXPECT_TRUE(same(sqrt(x), sqrt(mx))) << "sqrt " << Tr::to_string(x);
    }
    compared += 1;
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_EQ(compared, 20000);
}

TEST(IntervalDouble, SqrtExpLogMatchMpfrDirectedRounding) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 20000; ++i) {
    const double a = std::fabs(random_double(rng)), b = std::fabs(random_double(rng));
    const D x(std::min(a, b), std::max(a, b));
    expect_tight_enclosure(sqrt(x), mpfr1(mpfr_sqrt, x.lower(), MPFR_RNDD), mpfr1(mpfr_sqrt, x.upper(), MPFR_RNDU), "sqrt");
    if (x.lower() > 0) {
      const D l = log(x);
      EXPECT_EQ(l.lower(), mpfr1(mpfr_log, x.lower(), MPFR_RNDD));
      EXPECT_EQ(l.upper(), mpfr1(mpfr_log, x.upper(), MPFR_RNDU));
    }
    const double e = std::ldexp(random_double(rng), -55);  // |e| up to ~32: no overflow
    const D y(std::min(e, -e), std::max(e, -e));
    const D ex = exp(y);
    EXPECT_EQ(ex.lower(), mpfr1(mpfr_exp, y.lower(), MPFR_RNDD));
    EXPECT_EQ(ex.upper(), mpfr1(mpfr_exp, y.upper(), MPFR_RNDU));
    if (::testing::Test::HasFailure()) return;
  }
  // Outside the domains: no finite enclosure, never a guess.
  EXPECT_FALSE(Tr::is_finite(sqrt(D(-2.0, -1.0))));
  EXPECT_FALSE(Tr::is_finite(log(D(-1.0, 2.0))));
  EXPECT_FALSE(Tr::is_finite(log(D(0.0, 2.0))));
  // sqrt of an interval reaching below 0 roots its non-negative part (IEEE 1788; mpfi_sqrt
  // gives NaN there: InvalidResultsAsMpfi).
  EXPECT_EQ(sqrt(D(-1.0, 4.0)).lower(), 0.0);
  EXPECT_EQ(sqrt(D(-1.0, 4.0)).upper(), 2.0);
  EXPECT_EQ(sqrt(D(-1.0, 2.0)).upper(), mpfr1(mpfr_sqrt, 2.0, MPFR_RNDU));
}

// The conventions for invalid results (interval_double.hpp, "Invalid intervals"), next to
// the MPFI wrapper's: an empty intersection is the NaN interval in both (never an inverted
// pair that has_nan() and bounded() would pass), NaN operands give NaN (hull and intersect
// included), and sqrt below 0 differs as documented.
TEST(IntervalDouble, InvalidResultsAsMpfi) {
  auto mp = [](double lo, double hi) {
    Mpfr l(53), h(53);
    mpfr_set_d(l.get(), lo, MPFR_RNDN);
    mpfr_set_d(h.get(), hi, MPFR_RNDN);
    return Mpfi(l, h);
  };
  Mpfi mnan(53);  // NaN ends
  mpfr_set_nan(&mnan.get()->left);
  mpfr_set_nan(&mnan.get()->right);
  const D nan = D::nan_interval();
  using MTr = ScalarTraits<Mpfi>;

  // Disjoint: NaN, so invalid for every predicate and never finite.
  for (const auto& [x, y] : {std::pair{D(1.0, 2.0), D(3.0, 4.0)}, std::pair{D(3.0, 4.0), D(1.0, 2.0)},
                             std::pair{D(-1e-300, -1e-300), D(0.0, 1.0)}}) {
    const D d = intersect(x, y);
    EXPECT_TRUE(d.has_nan()) << Tr::to_string(x) << " n " << Tr::to_string(y) << " = " << Tr::to_string(d);
    EXPECT_FALSE(Tr::is_finite(d));
    EXPECT_EQ(Tr::lt(d, D(0.0, 0.0)), Truth::invalid);
    const Mpfi m = intersect(mp(x.lower(), x.upper()), mp(y.lower(), y.upper()));
    EXPECT_TRUE(m.has_nan()) << MTr::to_string(m);
    EXPECT_FALSE(MTr::is_finite(m));
    EXPECT_EQ(MTr::lt(m, mp(0.0, 0.0)), Truth::invalid);
    // Computing on with it stays invalid (an inverted [3, 2] + [1, 2] was once [4, 4]).
    EXPECT_TRUE((d + D(1.0, 2.0)).has_nan());
    EXPECT_TRUE((m + mp(1.0, 2.0)).has_nan());
  }
  // Touching and nested intervals meet in a valid interval.
  EXPECT_EQ(intersect(D(1.0, 2.0), D(2.0, 3.0)).lower(), 2.0);
  EXPECT_EQ(intersect(D(1.0, 2.0), D(2.0, 3.0)).upper(), 2.0);
  EXPECT_EQ(intersect(D(-5.0, 5.0), D(1.0, 2.0)).lower(), 1.0);
  EXPECT_EQ(intersect(D(-5.0, 5.0), D(1.0, 2.0)).upper(), 2.0);
  EXPECT_FALSE(intersect(mp(1.0, 2.0), mp(2.0, 3.0)).has_nan());
  EXPECT_EQ(mpfr_cmp_d(&intersect(mp(1.0, 2.0), mp(2.0, 3.0)).get()->left, 2.0), 0);
  // NaN operands, in either place (std::max / std::min alone would drop them).
  for (const D& x : {D(1.0, 2.0), D::entire()}) {
    EXPECT_TRUE(intersect(x, nan).has_nan());
    EXPECT_TRUE(intersect(nan, x).has_nan());
    EXPECT_TRUE(hull(x, nan).has_nan());
    EXPECT_TRUE(hull(nan, x).has_nan());
    EXPECT_TRUE(abs(nan).has_nan());
    EXPECT_TRUE((-nan).has_nan());
    EXPECT_TRUE(sqrt(nan).has_nan());
  }
  EXPECT_TRUE(intersect(mp(1.0, 2.0), mnan).has_nan());
  EXPECT_TRUE(intersect(mnan, mp(1.0, 2.0)).has_nan());
  EXPECT_TRUE(hull(mp(1.0, 2.0), mnan).has_nan());
  EXPECT_TRUE(hull(mnan, mp(1.0, 2.0)).has_nan());
  // clamp (the map's cut to a known range) of an enclosure outside the range: invalid.
  EXPECT_TRUE(Tr::clamp(D(5.0, 6.0), D(0.0, 0.0), D(1.0, 1.0)).has_nan());
  EXPECT_TRUE(MTr::clamp(mp(5.0, 6.0), mp(0.0, 0.0), mp(1.0, 1.0)).has_nan());
  EXPECT_EQ(Tr::clamp(D(0.5, 6.0), D(0.0, 0.0), D(1.0, 1.0)).upper(), 1.0);
  // sqrt: DoubleInterval roots the non-negative part, mpfi_sqrt gives NaN; below 0 both NaN.
  EXPECT_EQ(sqrt(D(-1.0, 4.0)).lower(), 0.0);
  EXPECT_EQ(sqrt(D(-1.0, 4.0)).upper(), 2.0);
  EXPECT_TRUE(sqrt(mp(-1.0, 4.0)).has_nan());
  EXPECT_TRUE(sqrt(D(-2.0, -1.0)).has_nan());
  EXPECT_TRUE(sqrt(mp(-2.0, -1.0)).has_nan());
  EXPECT_EQ(mpfr_cmp_d(&sqrt(mp(0.0, 4.0)).get()->right, 2.0), 0);
  // log: NaN for both when the interval reaches below 0; -inf at a lower end 0.
  EXPECT_TRUE(log(D(-1.0, 2.0)).has_nan());
  EXPECT_TRUE(log(mp(-1.0, 2.0)).has_nan());
  EXPECT_EQ(log(D(0.0, 1.0)).lower(), -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(mpfr_inf_p(&log(mp(0.0, 1.0)).get()->left));
}

TEST(IntervalDouble, Pow35EnclosesThe512BitPower) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> U(-40, 40);
  for (int i = 0; i < 5000; ++i) {
    const double a = std::exp(U(rng)), b = a * (1 + std::fabs(U(rng)) / 1000);
    const D r = Tr::pow_3_5(D(a, b));
    for (double x : {a, b}) {
      Mpfr p(512);
      mpfr_set_d(p.get(), x, MPFR_RNDN);
      mpfr_pow_ui(p.get(), p.get(), 3, MPFR_RNDN);
      mpfr_rootn_ui(p.get(), p.get(), 5, MPFR_RNDN);
      EXPECT_GE(mpfr_cmp_d(p.get(), r.lower()), 0) << x;
      EXPECT_LE(mpfr_cmp_d(p.get(), r.upper()), 0) << x;
    }
  }
  const D z = Tr::pow_3_5(D(0.0, 32.0));
  EXPECT_EQ(z.lower(), 0.0);
  EXPECT_GE(z.upper(), 8.0);  // 32^(3/5) = 8
  EXPECT_LE(z.upper(), 8.0 + 1e-13);  // three rounded operations, each widened by a double
}

TEST(IntervalDouble, DecimalsAreEnclosedTightly) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<long> digits(0, 999999999), ex(-30, 30);
  for (int i = 0; i < 5000; ++i) {
    const std::string text = std::to_string(digits(rng)) + "e" + std::to_string(ex(rng));
    const D x = Tr::from_decimal(text, 53);
    mpfr_t lo, hi;
    mpfr_inits2(53, lo, hi, static_cast<mpfr_ptr>(nullptr));
    const int exact = mpfr_strtofr(lo, text.c_str(), nullptr, 10, MPFR_RNDD);
    mpfr_strtofr(hi, text.c_str(), nullptr, 10, MPFR_RNDU);
    EXPECT_EQ(x.lower(), mpfr_get_d(lo, MPFR_RNDN)) << text;
    EXPECT_EQ(x.upper(), mpfr_get_d(hi, MPFR_RNDN)) << text;
    if (exact == 0) EXPECT_EQ(x.lower(), x.upper()) << text << " is a double";
    else EXPECT_EQ(next_up(x.lower()), x.upper()) << text << ": the two neighbouring doubles";
    mpfr_clears(lo, hi, static_cast<mpfr_ptr>(nullptr));
  }
  EXPECT_EQ(Tr::from_decimal("28.82", 53).upper(), next_up(Tr::from_decimal("28.82", 53).lower()));
  EXPECT_THROW(Tr::from_decimal("28.8x", 53), std::invalid_argument);
}

TEST(IntervalDouble, PrintedEndsAreOutwardAndReadBack) {
  const D x = Tr::from_decimal("0.1", 53);
  // The printed lower end is at or below the lower end; reading it back gives it again.
  for (const D& y : {x, D(-1e-310, 3.0), D(1.0 / 3, 2.0 / 3), D(-7.25, -7.25)}) {
    const std::string lo = Tr::lower_string(y), hi = Tr::upper_string(y);
    EXPECT_EQ(std::strtod(lo.c_str(), nullptr), y.lower()) << lo;
    EXPECT_EQ(std::strtod(hi.c_str(), nullptr), y.upper()) << hi;
    Mpfr l(512), h(512);
    mpfr_set_str(l.get(), lo.c_str(), 10, MPFR_RNDN);
    mpfr_set_str(h.get(), hi.c_str(), 10, MPFR_RNDN);
    EXPECT_LE(mpfr_cmp_d(l.get(), y.lower()), 0) << lo;
    EXPECT_GE(mpfr_cmp_d(h.get(), y.upper()), 0) << hi;
  }
  EXPECT_EQ(Tr::to_string(D(-7.25, 2.0)), "[-7.25, 2]");
}

TEST(IntervalDouble, PredicatesAreThreeValued) {
  const D a(1.0, 2.0), b(3.0, 4.0), c(1.5, 3.5), z(0.0, 0.0), nan = D::nan_interval();
  EXPECT_EQ(Tr::lt(a, b), Truth::yes);
  EXPECT_EQ(Tr::lt(b, a), Truth::no);
  EXPECT_EQ(Tr::lt(a, c), Truth::unknown);
  EXPECT_EQ(Tr::lt(D(2.0, 2.0), D(2.0, 2.0)), Truth::no);
  EXPECT_EQ(Tr::le(D(2.0, 2.0), D(2.0, 2.0)), Truth::yes);
  EXPECT_EQ(Tr::le(D(1.0, 2.0), D(2.0, 3.0)), Truth::yes);
  EXPECT_EQ(Tr::lt(D(1.0, 2.0), D(2.0, 3.0)), Truth::unknown);
  EXPECT_EQ(Tr::is_zero(z), Truth::yes);
  EXPECT_EQ(Tr::is_zero(D(-1.0, 1.0)), Truth::unknown);
  EXPECT_EQ(Tr::is_zero(a), Truth::no);
  EXPECT_EQ(Tr::lt(nan, a), Truth::invalid);
  EXPECT_EQ(Tr::is_zero(nan), Truth::invalid);
  D out;
  EXPECT_EQ(Tr::floor_certain(D(2.25, 2.75), out), Truth::yes);
  EXPECT_EQ(out.lower(), 2.0);
  EXPECT_EQ(Tr::floor_certain(D(2.75, 3.25), out), Truth::unknown);
  EXPECT_EQ(Tr::floor_certain(D::entire(), out), Truth::invalid);
  EXPECT_EQ(Tr::nonneg(D(-1.0, 2.0)).lower(), 0.0);
  EXPECT_EQ(Tr::exponent(D(-5.0, 3.0)), 3);  // 4 <= 5 < 8
}

ModelSpec constant(const char* eps, const char* a) {
  ModelSpec m;
  m.law = Law::constant;
  m.eps = *Decimal::parse(eps);
  m.a = *Decimal::parse(a);
  m.wall = parse_wall("wall", "triangle");
  validate(m);
  return m;
}

// A Lohner orbit in DoubleInterval from the exact release state holds the orbit of the same
// exact inputs computed with MPFR at 512 bits (whose own error is far below the widths).
TEST(IntervalDouble, LohnerOrbitHoldsThe512BitOrbit) {
  const ModelSpec spec = constant("0.96", "28.82");
  const InitialCondition start{*Decimal::parse("0.5"), Decimal::from_int(4)};
  OrbitEnclosureOf<D> orbit(interval_model_of<D>(spec, 53), make_state<D>(start, 53), EnclosureMethod::lohner);
  const ImpactMap<Mpfr> truth(make_model<Mpfr>(spec, 512));
  State<Mpfr> s = make_state<Mpfr>(start, 512);
  auto holds = [](const D& x, const Mpfr& p) {
    return mpfr_cmp_d(p.get(), x.lower()) >= 0 && mpfr_cmp_d(p.get(), x.upper()) <= 0;
  };
  const int kSteps = 3000;
  for (int n = 1; n <= kSteps; ++n) {
    const auto e = orbit.step();
    s = truth.step(s).next;
    ASSERT_TRUE(holds(e.next.theta, s.theta)) << "step " << n << ": theta " << Tr::to_string(e.next.theta) << " misses " << s.theta;
    ASSERT_TRUE(holds(e.next.v, s.v)) << "step " << n << ": v " << Tr::to_string(e.next.v) << " misses " << s.v;
  }
  // Lohner keeps the enclosure near the rounding level (a naive box would have blown up).
  EXPECT_LT(box_width(orbit.box()), 1e-9);
}

// The interval:double tier changes how fast a certificate comes, never what it says.
TEST(IntervalDouble, CertifySticking_SameCertificatesWithAndWithoutTheDoubleTier) {
  struct Case {
    const char* eps;
    const char* a;
    long long max_steps;
  };
  int decided_by_double = 0;
  for (const Case& c : {Case{"0.5", "25", 1000}, Case{"0.5", "30", 1000}, Case{"0.5", "10", 1000},
                        Case{"0.96", "28.82", 20000}, Case{"0.8", "12", 2000}}) {
    StickingQuestion fast;
    fast.model = constant(c.eps, c.a);
    fast.max_steps = c.max_steps;
    fast.schedule.max_bits = 512;
    StickingQuestion mpfi = fast;
    mpfi.schedule.double_first = false;
    const StickingCertificate f = certify_sticking(fast), m = certify_sticking(mpfi);
    SCOPED_TRACE(std::string("eps ") + c.eps + ", a " + c.a);
    EXPECT_EQ(f.outcome, m.outcome);
    EXPECT_EQ(f.period, m.period);
    ASSERT_FALSE(f.attempts.empty());
    EXPECT_EQ(f.attempts[0].scalar, "interval:double");
    if (f.certified && f.scalar == "interval:double") ++decided_by_double;
    if (f.certified && f.scalar != "interval:double") {
      EXPECT_GT(f.attempts.size(), 1u);
    }
  }
  EXPECT_GE(decided_by_double, 3) << "the fast tier should settle the easy cases";
}

}  // namespace
}  // namespace bouncer
