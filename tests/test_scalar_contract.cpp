// One contract test per scalar type (in the style of Boost.Multiprecision's per-backend
// tests): a typed suite over the scalar set of bouncer/scalar/scalar_set.hpp that checks
// every operation of the contract (bouncer/scalar/contract.hpp) against independent truth,
// and a second typed suite over the duals of the set.
//
// Independent truth, never the type under test:
//  * exact rationals (GMP): small integers, dyadic decimals (exact in every type), the
//    exact result of + - * / on exact operands, decimals parsed by hand (exact.hpp);
//  * correct rounding to the type's precision by MPFR's mpfr_set_q (points must equal it);
//  * MPFR at max(512, 2 bits + 64) bits with directed rounding for sqrt, exp, log, x^(3/5)
//    and derivatives: a bracket [lo, hi] of the exact value. A point result must lie
//    within the stated error of the bracket; an interval result must contain it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "bouncer/scalar/contract.hpp"
#include "bouncer/scalar/dual.hpp"
#include "bouncer/scalar/precision.hpp"
#include "bouncer/scalar/scalar_set.hpp"
#include "exact.hpp"
#include "scalar_types.hpp"

namespace bouncer {
namespace {

// ---------------------------------------------------------------------------------------
// Point types are correctly rounded at their precision, except dd (double-word arithmetic,
// scalar/double_double.hpp): its values are not a fixed grid of 106-bit numbers, and its
// operations are accurate to a few units of 2^-106 (proved bounds, JMP 2017), not correctly
// rounded. Its checks: the double-word conversion of a decimal (hi = RN(q), lo = RN(q - hi))
// and a relative error below 2^-(bits - 4) for each operation.
template <class T>
constexpr bool kDoubleWord = std::is_same_v<T, DoubleDouble>;

// Exact ends of a value: lo == hi for a point type.

struct Range {
  mpq_class lo, hi;
};

template <class T>
Range range_of(const T& x) {
  if constexpr (ScalarTraits<T>::is_interval) {
    return {exact(x.lower()), exact(x.upper())};
  } else {
    const mpq_class q = exact(x);
    return {q, q};
  }
}

mpq_class abs_q(const mpq_class& q) { return q < 0 ? mpq_class(-q) : q; }

// Precisions each type is tested at: its own, or (for the types of variable precision)
// one inline, one just above Quad, and one on the heap.
template <class T>
std::vector<long> precisions() {
  if (ScalarTraits<T>::fixed_bits) return {ScalarTraits<T>::fixed_bits};
  return {53, 200, 1100};
}

// ---------------------------------------------------------------------------------------
// Truth brackets at high precision.

struct Bracket {
  Mpfr lo, hi;
  mpq_class qlo() const { return exact(lo); }
  mpq_class qhi() const { return exact(hi); }
};

long truth_bits(long bits) { return std::max(512L, 2 * bits + 64); }

Bracket bracket_of(const mpq_class& q, long p) {
  Bracket b{Mpfr(p), Mpfr(p)};
  mpfr_set_q(b.lo.get(), q.get_mpq_t(), MPFR_RNDD);
  mpfr_set_q(b.hi.get(), q.get_mpq_t(), MPFR_RNDU);
  return b;
}

using MpfrFn = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t);

// An increasing function applied to both ends, rounded outward.
Bracket increasing(MpfrFn f, const Bracket& x) {
  Bracket r{Mpfr(x.lo.bits()), Mpfr(x.hi.bits())};
  f(r.lo.get(), x.lo.get(), MPFR_RNDD);
  f(r.hi.get(), x.hi.get(), MPFR_RNDU);
  return r;
}

int pow35(mpfr_ptr r, mpfr_srcptr x, mpfr_rnd_t rnd) {
  // x^(3/5) = (x^3)^(1/5), both steps rounded the same way (increasing for x >= 0).
  mpfr_pow_ui(r, x, 3, rnd);
  return mpfr_rootn_ui(r, r, 5, rnd);
}

// c * num / den for positive brackets and a positive rational c, rounded outward.
Bracket scaled_ratio(const mpq_class& c, const Bracket& num, const Bracket& den) {
  const long p = num.lo.bits();
  Bracket r{Mpfr(p), Mpfr(p)};
  mpfr_div(r.lo.get(), num.lo.get(), den.hi.get(), MPFR_RNDD);
  mpfr_div(r.hi.get(), num.hi.get(), den.lo.get(), MPFR_RNDU);
  mpfr_mul_q(r.lo.get(), r.lo.get(), c.get_mpq_t(), MPFR_RNDD);
  mpfr_mul_q(r.hi.get(), r.hi.get(), c.get_mpq_t(), MPFR_RNDU);
  return r;
}

// A point result within rel * |truth| of the bracket; an interval result containing the
// bracket, no wider than the bracket plus rel * |truth|.
template <class T>
void expect_near_or_enclosing(const T& r, const Bracket& t, const mpq_class& rel, const std::string& what) {
  SCOPED_TRACE(what);
  const Range got = range_of(r);
  const mpq_class tlo = t.qlo(), thi = t.qhi();
  const mpq_class mag = std::max(abs_q(tlo), abs_q(thi));
  if constexpr (ScalarTraits<T>::is_interval) {
    EXPECT_LE(got.lo, tlo) << "the enclosure misses the exact value (lower end)";
    EXPECT_GE(got.hi, thi) << "the enclosure misses the exact value (upper end)";
    // Two roundings (an ulp each) of the exact value at most, at rel = one rounding.
    EXPECT_LE(mpq_class(got.hi - got.lo), mpq_class(thi - tlo + 2 * rel * mag)) << "enclosure too wide";
  } else {
    const mpq_class q = got.lo;
    const mpq_class dist = q < tlo ? mpq_class(tlo - q) : q > thi ? mpq_class(q - thi) : mpq_class(0);
    EXPECT_LE(dist, rel * mag) << "got " << ScalarTraits<T>::to_string(r);
  }
}

// The exact rational result of an operation on exact operands: a point must be its correct
// rounding (mpfr_set_q, round to nearest), an interval must contain it within one ulp.
template <class T>
void expect_rounded_or_enclosing(const T& r, const mpq_class& q, long bits, const std::string& what) {
  SCOPED_TRACE(what);
  const Range got = range_of(r);
  if constexpr (ScalarTraits<T>::is_interval) {
    EXPECT_LE(got.lo, q);
    EXPECT_GE(got.hi, q);
    EXPECT_LE(mpq_class(got.hi - got.lo), mpq_class(abs_q(q) * inv_pow2(bits - 1)));
  } else if constexpr (kDoubleWord<T>) {
    EXPECT_LE(abs_q(got.lo - q), mpq_class(abs_q(q) * inv_pow2(bits - 4))) << "not accurate to 2^-(bits - 4)";
  } else {
    Mpfr rounded(bits);
    mpfr_set_q(rounded.get(), q.get_mpq_t(), MPFR_RNDN);
    EXPECT_EQ(got.lo, exact(rounded)) << "not correctly rounded";
  }
}

// Dyadic decimals: exact in every type of the set (at most 21 significant bits).
const std::vector<const char*> kDyadic = {"0.375", "28.8125", "3", "0.5", "1048576.0625", "7.25",
                                          "0.0009765625", "-2.5", "-0.375", "1"};
// Decimals that no binary type holds exactly.
const std::vector<const char*> kInexact = {"0.1", "28.82", "1e-9", "0.96", "-7.3", "123456.789"};

template <class T>
class ScalarContract : public ::testing::Test {};
TYPED_TEST_SUITE(ScalarContract, GTestTypes<Scalars>);

TYPED_TEST(ScalarContract, MeetsTheConcept) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  static_assert(Scalar<T>);
  static_assert(Tr::is_interval ? IntervalScalar<T> : PointScalar<T>);
  static_assert(PointScalar<T> != IntervalScalar<T>, "exactly one of the two kinds");
  // The family is the --precision name (scalar/precision.hpp), unique within the set.
  int same = 0;
  for_each_scalar<Scalars>([&](auto tag) {
    same += std::string(ScalarTraits<typename decltype(tag)::type>::family) == Tr::family;
  });
  EXPECT_EQ(same, 1);
  for (long bits : precisions<T>()) {
    const Precision p = parse_precision("p", Tr::fixed_bits ? std::string(Tr::family)
                                                            : std::string(Tr::family) + ":" + std::to_string(bits));
    EXPECT_EQ(p.bits, bits);
    EXPECT_EQ(p.is_interval(), Tr::is_interval);
    EXPECT_TRUE(with_scalar(p, [](auto tag) { return std::is_same_v<typename decltype(tag)::type, T>; }));
  }
}

TYPED_TEST(ScalarContract, FromIntIsExactAndBitsAreKept) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  for (long bits : precisions<T>()) {
    SCOPED_TRACE(bits);
    for (long n : {0L, 1L, -1L, 7L, -123456L, 2147483649L, (1L << 50) + 1, -((1L << 52) - 1)}) {
      const T x = Tr::from_int(n, bits);
      const Range r = range_of(x);
      EXPECT_EQ(r.lo, n);
      EXPECT_EQ(r.hi, n);
      EXPECT_EQ(Tr::bits(x), bits);
    }
  }
}

TYPED_TEST(ScalarContract, FromDecimalRoundsCorrectlyOrEncloses) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  for (long bits : precisions<T>()) {
    for (const char* s : kDyadic) {
      SCOPED_TRACE(std::string(s) + " at " + std::to_string(bits));
      const Range r = range_of(Tr::from_decimal(s, bits));
      EXPECT_EQ(r.lo, rational_of(s));
      EXPECT_EQ(r.hi, rational_of(s));
    }
    for (const char* s : kInexact) {
      SCOPED_TRACE(std::string(s) + " at " + std::to_string(bits));
      const T x = Tr::from_decimal(s, bits);
      const Range r = range_of(x);
      const mpq_class q = rational_of(s);
      if constexpr (Tr::is_interval) {
        // The tightest enclosure: the two neighbours of q at this precision.
        EXPECT_LT(r.lo, q);
        EXPECT_GT(r.hi, q);
        EXPECT_EQ(r.lo, round_to_bits(r.lo, bits));
        EXPECT_LE(mpq_class(r.hi - r.lo), mpq_class(abs_q(q) * inv_pow2(bits - 1)));
      } else if constexpr (kDoubleWord<T>) {
        // hi = RN(q), lo = RN(q - hi), both doubles: within 2^-106 of q, relative.
        const mpq_class hi = round_to_bits(q, 53);
        EXPECT_EQ(r.lo, hi + round_to_bits(mpq_class(q - hi), 53));
        EXPECT_LE(abs_q(r.lo - q), mpq_class(abs_q(q) * inv_pow2(bits - 1)));
      } else {
        EXPECT_EQ(r.lo, round_to_bits(q, bits));
      }
      EXPECT_EQ(Tr::bits(x), bits);
    }
    for (const char* bad : {"", "abc", "1.5x", "1e", "0.1 "}) {
      SCOPED_TRACE(std::string("'") + bad + "'");
      EXPECT_THROW(Tr::from_decimal(bad, bits), std::invalid_argument);
    }
  }
}

TYPED_TEST(ScalarContract, ArithmeticOnExactOperands) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  for (long bits : precisions<T>()) {
    for (const char* xs : kDyadic) {
      for (const char* ys : {"0.375", "-3", "28.8125", "7"}) {
        const std::string what = std::string(xs) + " and " + ys + " at " + std::to_string(bits);
        const T x = Tr::from_decimal(xs, bits), y = Tr::from_decimal(ys, bits);
        const mpq_class qx = rational_of(xs), qy = rational_of(ys);
        const long n = 3;
        expect_rounded_or_enclosing<T>(x + y, qx + qy, bits, what + " +");
        expect_rounded_or_enclosing<T>(x - y, qx - qy, bits, what + " -");
        expect_rounded_or_enclosing<T>(x * y, qx * qy, bits, what + " *");
        expect_rounded_or_enclosing<T>(x / y, qx / qy, bits, what + " /");
        expect_rounded_or_enclosing<T>(-x, -qx, bits, what + " unary -");
        expect_rounded_or_enclosing<T>(x + n, qx + n, bits, what + " x + n");
        expect_rounded_or_enclosing<T>(x - n, qx - n, bits, what + " x - n");
        expect_rounded_or_enclosing<T>(n - x, n - qx, bits, what + " n - x");
        expect_rounded_or_enclosing<T>(x * n, qx * n, bits, what + " x * n");
        expect_rounded_or_enclosing<T>(n * x, qx * n, bits, what + " n * x");
        expect_rounded_or_enclosing<T>(x / n, qx / n, bits, what + " x / n");
        expect_rounded_or_enclosing<T>(n / x, n / qx, bits, what + " n / x");
        T m = x;
        m += y;
        expect_rounded_or_enclosing<T>(m, qx + qy, bits, what + " +=");
        m = x;
        m -= y;
        expect_rounded_or_enclosing<T>(m, qx - qy, bits, what + " -=");
        m = x;
        m *= y;
        expect_rounded_or_enclosing<T>(m, qx * qy, bits, what + " *=");
        m = x;
        m /= y;
        expect_rounded_or_enclosing<T>(m, qx / qy, bits, what + " /=");
        m = x;
        m *= n;
        expect_rounded_or_enclosing<T>(m, qx * n, bits, what + " *= n");
        m = x;
        m /= n;
        expect_rounded_or_enclosing<T>(m, qx / n, bits, what + " /= n");
      }
    }
  }
}

TYPED_TEST(ScalarContract, ElementaryFunctionsAgainstMpfrBrackets) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  using std::exp;
  using std::log;
  using std::sqrt;
  for (long bits : precisions<T>()) {
    const long p = truth_bits(bits);
    for (const char* s : {"0.375", "28.8125", "3", "0.5", "1048576.0625", "7.25", "0.0009765625", "1"}) {
      const std::string what = std::string(s) + " at " + std::to_string(bits);
      const T x = Tr::from_decimal(s, bits);
      const Bracket bx = bracket_of(rational_of(s), p);
      const double ln = std::fabs(std::log(std::strtod(s, nullptr)));
      // sqrt: correctly rounded (half an ulp: 2^-bits relative); dd a few 2^-bits.
      expect_near_or_enclosing<T>(T(sqrt(x)), increasing(mpfr_sqrt, bx), inv_pow2(kDoubleWord<T> ? bits - 3 : bits), what + " sqrt");
      // exp, log: within two ulps (libm, libquadmath) or correctly rounded (MPFR, MPFI);
      // (exp of 2^20 overflows the IEEE types: not a value of the contract.)
      // dd: QD's exp and log, measured at up to 8.5 units of 2^-106: 32 allowed.
      const long fn_bits = kDoubleWord<T> ? bits - 5 : bits - 2;
      if (rational_of(s) < 700) expect_near_or_enclosing<T>(T(exp(x)), increasing(mpfr_exp, bx), inv_pow2(fn_bits), what + " exp");
      if (rational_of(s) != 1) expect_near_or_enclosing<T>(T(log(x)), increasing(mpfr_log, bx), inv_pow2(fn_bits), what + " log");
      // x^(3/5): an inexact exponent 0.6 in the IEEE types costs up to |ln x| ulps.
      expect_near_or_enclosing<T>(Tr::pow_3_5(x), increasing(pow35, bx), mpq_class(16 + 4 * static_cast<long>(ln)) * inv_pow2(bits),
                                  what + " pow_3_5");
    }
    // log 1 = 0 and exp 0 = 1 exactly (in an interval: the enclosure holds the exact value).
    const Range l1 = range_of(T(log(Tr::from_int(1, bits))));
    EXPECT_LE(l1.lo, 0);
    EXPECT_GE(l1.hi, 0);
    const Range e0 = range_of(T(exp(Tr::from_int(0, bits))));
    EXPECT_LE(e0.lo, 1);
    EXPECT_GE(e0.hi, 1);
    EXPECT_EQ(range_of(Tr::pow_3_5(Tr::from_int(0, bits))).hi, 0);
    expect_near_or_enclosing<T>(Tr::pow_3_5(Tr::from_int(32, bits)), bracket_of(8, p), inv_pow2(bits - 4), "32^(3/5) = 8");
  }
}

TYPED_TEST(ScalarContract, ThreeValuedPredicates) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  for (long bits : precisions<T>()) {
    SCOPED_TRACE(bits);
    const T one = Tr::from_int(1, bits), two = Tr::from_int(2, bits), zero = Tr::from_int(0, bits);
    EXPECT_EQ(Tr::lt(one, two), Truth::yes);
    EXPECT_EQ(Tr::lt(two, one), Truth::no);
    EXPECT_EQ(Tr::lt(one, one), Truth::no);
    EXPECT_EQ(Tr::le(one, one), Truth::yes);
    EXPECT_EQ(Tr::le(one, two), Truth::yes);
    EXPECT_EQ(Tr::le(two, one), Truth::no);
    EXPECT_EQ(Tr::is_zero(zero), Truth::yes);
    EXPECT_EQ(Tr::is_zero(T(-zero)), Truth::yes);
    EXPECT_EQ(Tr::is_zero(one), Truth::no);
    EXPECT_EQ(Tr::is_zero(Tr::from_decimal("1e-300", bits)), Truth::no);
    // Values one ulp apart are ordered in every type.
    const T below_one = one - Tr::from_int(1, bits) / Tr::from_int(1L << 40, bits);
    EXPECT_EQ(Tr::lt(below_one, one), Truth::yes);
    // NaN: invalid, never yes or no.
    const T nan = zero / zero;
    EXPECT_EQ(Tr::lt(nan, one), Truth::invalid);
    EXPECT_EQ(Tr::le(one, nan), Truth::invalid);
    EXPECT_EQ(Tr::is_zero(nan), Truth::invalid);
    // An enclosure of a decimal overlaps itself: only an interval cannot decide.
    const T tenth = Tr::from_decimal("0.1", bits);
    const Truth expect_self = Tr::is_interval ? Truth::unknown : Truth::no;
    EXPECT_EQ(Tr::lt(tenth, tenth), expect_self);
    EXPECT_EQ(Tr::is_zero(T(tenth - tenth)), Tr::is_interval ? Truth::unknown : Truth::yes);
  }
}

TYPED_TEST(ScalarContract, SignHelpersNonnegAndClamp) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  for (long bits : precisions<T>()) {
    SCOPED_TRACE(bits);
    const T zero = Tr::from_int(0, bits), one = Tr::from_int(1, bits);
    const T x = Tr::from_decimal("0.375", bits), mx = Tr::from_decimal("-0.375", bits);
    EXPECT_TRUE(Tr::likely_negative(mx));
    EXPECT_FALSE(Tr::likely_negative(x));
    EXPECT_FALSE(Tr::likely_negative(zero));
    // nonneg: max(x, 0) for points, the enclosure cut to [0, inf) for intervals.
    EXPECT_EQ(range_of(Tr::nonneg(x)).lo, mpq_class(3, 8));
    EXPECT_EQ(range_of(Tr::nonneg(mx)).lo, 0);
    EXPECT_EQ(range_of(Tr::nonneg(mx)).hi, 0);
    // clamp to [0, 1): inside stays, below goes to 0, at or above 1 to the number below 1
    // (the largest value of the type under 1: 1 - 2^-bits).
    EXPECT_EQ(range_of(Tr::clamp(x, zero, one)).lo, mpq_class(3, 8));
    EXPECT_EQ(range_of(Tr::clamp(x, zero, one)).hi, mpq_class(3, 8));
    if constexpr (Tr::is_interval) {
      // x - x encloses 0 with both signs: nonneg and clamp keep exactly its non-negative part.
      const T t = Tr::from_decimal("0.1", bits);
      const T d = t - t;
      const Range rd = range_of(d);
      ASSERT_LT(rd.lo, 0);
      ASSERT_GT(rd.hi, 0);
      EXPECT_EQ(range_of(Tr::nonneg(d)).lo, 0);
      EXPECT_EQ(range_of(Tr::nonneg(d)).hi, rd.hi);
      EXPECT_EQ(range_of(Tr::clamp(d, zero, one)).lo, 0);
      EXPECT_EQ(range_of(Tr::clamp(d, zero, one)).hi, rd.hi);
      // An enclosure reaching past 1 is cut at 1.
      const T w = one + d;
      EXPECT_EQ(range_of(Tr::clamp(w, zero, one)).hi, 1);
      EXPECT_EQ(range_of(Tr::clamp(w, zero, one)).lo, range_of(w).lo);
    } else if constexpr (kDoubleWord<T>) {
      // dd: the value below x is hi + (the double below lo): 2^-1074 below 1 and 0.375,
      // strictly below, and what clamp gives at and above hi.
      EXPECT_EQ(range_of(Tr::clamp(mx, zero, one)).lo, 0);
      EXPECT_EQ(range_of(Tr::below(one)).lo, 1 - inv_pow2(1074));
      EXPECT_EQ(range_of(Tr::below(x)).lo, mpq_class(3, 8) - inv_pow2(1074));
      EXPECT_EQ(range_of(Tr::clamp(one, zero, one)).lo, 1 - inv_pow2(1074));
      EXPECT_EQ(range_of(Tr::clamp(Tr::from_int(2, bits), zero, one)).lo, 1 - inv_pow2(1074));
      const T tenth = Tr::from_decimal("0.1", bits);
      EXPECT_LT(Tr::below(tenth), tenth);
      EXPECT_LE(mpq_class(range_of(tenth).lo - range_of(Tr::below(tenth)).lo), inv_pow2(bits + 1));
    } else {
      EXPECT_EQ(range_of(Tr::clamp(mx, zero, one)).lo, 0);
      EXPECT_EQ(range_of(Tr::clamp(one, zero, one)).lo, 1 - inv_pow2(bits));
      EXPECT_EQ(range_of(Tr::clamp(Tr::from_int(2, bits), zero, one)).lo, 1 - inv_pow2(bits));
      // below: the next value down (the ulp below 0.375 and below 1/2 is 2^(-1-bits)).
      EXPECT_EQ(range_of(Tr::below(one)).lo, 1 - inv_pow2(bits));
      EXPECT_EQ(range_of(Tr::below(x)).lo, mpq_class(3, 8) - inv_pow2(bits + 1));
      EXPECT_EQ(range_of(Tr::below(Tr::from_decimal("0.5", bits))).lo, mpq_class(1, 2) - inv_pow2(bits + 1));
      EXPECT_EQ(range_of(Tr::below(mx)).lo, mpq_class(-3, 8) - inv_pow2(bits + 1));
    }
  }
}

TYPED_TEST(ScalarContract, IntegerParts) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  for (long bits : precisions<T>()) {
    for (const char* s : {"2.5", "-2.5", "7.25", "3", "0.1", "-0.1", "28.82", "1048576.0625"}) {
      SCOPED_TRACE(std::string(s) + " at " + std::to_string(bits));
      const T x = Tr::from_decimal(s, bits);
      const Range r = range_of(x);
      // Independent floor of the exact ends.
      auto floor_q = [](const mpq_class& q) {
        mpz_class f;
        mpz_fdiv_q(f.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
        return f;
      };
      T out = Tr::from_int(99, bits);
      const Truth t = Tr::floor_certain(x, out);
      if (floor_q(r.lo) == floor_q(r.hi)) {
        ASSERT_EQ(t, Truth::yes);
        EXPECT_EQ(range_of(out).lo, mpq_class(floor_q(r.lo)));
        EXPECT_EQ(range_of(out).hi, mpq_class(floor_q(r.lo)));
      } else {
        EXPECT_EQ(t, Truth::unknown);
      }
      if constexpr (!Tr::is_interval) {
        EXPECT_EQ(range_of(Tr::floor(x)).lo, mpq_class(floor_q(r.lo)));
      }
    }
    // An enclosure straddling an integer: 0.1 * 10 holds 1 strictly inside for intervals.
    if constexpr (Tr::is_interval) {
      T out = Tr::from_int(0, bits);
      EXPECT_EQ(Tr::floor_certain(T(Tr::from_decimal("0.1", bits) * 10L), out), Truth::unknown);
    }
    // Not finite: never a certain integer part.
    const T zero = Tr::from_int(0, bits);
    T out = zero;
    EXPECT_NE(Tr::floor_certain(T(Tr::from_int(1, bits) / zero), out), Truth::yes);
    EXPECT_NE(Tr::floor_certain(T(zero / zero), out), Truth::yes);
    if constexpr (!Tr::is_interval) {
      EXPECT_EQ(Tr::floor_certain(T(zero / zero), out), Truth::invalid);
    }
  }
}

TYPED_TEST(ScalarContract, FinitenessDoubleAndExponent) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  for (long bits : precisions<T>()) {
    SCOPED_TRACE(bits);
    const T zero = Tr::from_int(0, bits), one = Tr::from_int(1, bits);
    EXPECT_TRUE(Tr::is_finite(one));
    EXPECT_TRUE(Tr::is_finite(Tr::from_decimal("1e300", bits)));
    EXPECT_FALSE(Tr::is_finite(T(one / zero)));
    EXPECT_FALSE(Tr::is_finite(T(zero / zero)));
    // to_double: exact for values double holds, nearest (an interval: its midpoint) else.
    EXPECT_EQ(Tr::to_double(Tr::from_decimal("28.8125", bits)), 28.8125);
    EXPECT_EQ(Tr::to_double(Tr::from_int(-7, bits)), -7.0);
    EXPECT_LE(std::fabs(Tr::to_double(Tr::from_decimal("0.1", bits)) - 0.1), 0.1 * 0x1p-52);
    // exponent e: 2^(e-1) <= |x| < 2^e, checked on exact values; 0 for 0.
    for (const char* s : {"1", "0.75", "0.5", "1000000000000", "-3", "0.0009765625", "1048576.0625"}) {
      const mpq_class q = abs_q(rational_of(s));
      int e = static_cast<int>(mpz_sizeinbase(q.get_num_mpz_t(), 2)) - static_cast<int>(mpz_sizeinbase(q.get_den_mpz_t(), 2));
      while (q >= (e >= 0 ? mpq_class(mpz_class(1) << e) : inv_pow2(-e))) ++e;
      while (q < (e - 1 >= 0 ? mpq_class(mpz_class(1) << (e - 1)) : inv_pow2(1 - e))) --e;
      EXPECT_EQ(Tr::exponent(Tr::from_decimal(s, bits)), e) << s;
    }
    EXPECT_EQ(Tr::exponent(zero), 0);
  }
}

TYPED_TEST(ScalarContract, ToStringReadsBack) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  using std::sqrt;
  for (long bits : precisions<T>()) {
    const T one = Tr::from_int(1, bits);
    const std::vector<T> values = {one / Tr::from_int(3, bits), T(sqrt(Tr::from_int(2, bits))), -one / Tr::from_int(7, bits),
                                   Tr::from_decimal("28.82", bits), Tr::from_decimal("1e-300", bits),
                                   Tr::from_decimal("1.234567890123456789e250", bits), Tr::from_int(-4, bits),
                                   Tr::from_int(0, bits), Tr::from_decimal("0.375", bits)};
    for (const T& x : values) {
      const std::string s = Tr::to_string(x);
      SCOPED_TRACE(s + " at " + std::to_string(bits));
      const Range r = range_of(x);
      if constexpr (Tr::is_interval) {
        // "[lo, hi]" with the ends rounded outward, and tight (within an ulp at bits).
        EXPECT_EQ(s, "[" + Tr::lower_string(x) + ", " + Tr::upper_string(x) + "]");
        const mpq_class lo = rational_of(Tr::lower_string(x)), hi = rational_of(Tr::upper_string(x));
        EXPECT_LE(lo, r.lo);
        EXPECT_GE(hi, r.hi);
        EXPECT_LE(mpq_class(r.lo - lo), mpq_class(abs_q(r.lo) * inv_pow2(bits - 1)));
        EXPECT_LE(mpq_class(hi - r.hi), mpq_class(abs_q(r.hi) * inv_pow2(bits - 1)));
        // Read back, the ends enclose the original enclosure.
        const Range back = range_of(Tr::from_decimal(Tr::lower_string(x), bits));
        EXPECT_LE(back.lo, r.lo);
      } else {
        const Range back = range_of(Tr::from_decimal(s, bits));
        EXPECT_EQ(back.lo, r.lo);
      }
    }
  }
}

// Widths: for the interval types of the set.
template <class T>
class IntervalContract : public ::testing::Test {};
TYPED_TEST_SUITE(IntervalContract, GTestTypes<IntervalScalars>);

TYPED_TEST(IntervalContract, Widths) {
  using T = TypeParam;
  using Tr = ScalarTraits<T>;
  mpq_class previous = 1;
  for (long bits : precisions<T>()) {
    SCOPED_TRACE(bits);
    // Exact values are thin; arithmetic on them that is exact stays thin.
    const T x = Tr::from_decimal("0.375", bits);
    EXPECT_EQ(range_of(x).lo, range_of(x).hi);
    EXPECT_EQ(range_of(T(x * 8L)).hi, range_of(T(x * 8L)).lo);
    // A decimal's enclosure is one ulp wide; it shrinks with the precision.
    const T t = Tr::from_decimal("0.1", bits);
    const mpq_class w = range_of(t).hi - range_of(t).lo;
    EXPECT_GT(w, 0);
    EXPECT_EQ(w, inv_pow2(bits + 3));  // ulp of [1/16, 1/8) at `bits` bits
    EXPECT_LT(w, previous);
    previous = w;
    // Ten of them: contains 1, width at least 10 w (widths add), at most 10 w plus
    // the outward roundings of the nine sums (an ulp of each end, the ends at most ~1).
    T sum = t;
    for (int i = 1; i < 10; ++i) sum += t;
    const Range rs = range_of(sum);
    EXPECT_LE(rs.lo, 1);
    EXPECT_GE(rs.hi, 1);
    EXPECT_GE(mpq_class(rs.hi - rs.lo), mpq_class(10 * w));
    EXPECT_LE(mpq_class(rs.hi - rs.lo), mpq_class(10 * w + 18 * inv_pow2(bits)));
    // Dependency: x - x is not 0 but [-w, w].
    const Range rd = range_of(T(t - t));
    EXPECT_EQ(rd.lo, -w);
    EXPECT_EQ(rd.hi, w);
  }
}

// ---------------------------------------------------------------------------------------
// Duals over the set: the value part is S's own computation, the derivative parts are the
// analytic derivatives (enclosed, for an interval S).

template <class D>
class DualContract : public ::testing::Test {};
TYPED_TEST_SUITE(DualContract, GTestTypes<DualsOf<Scalars>>);

template <class S>
void expect_same(const S& x, const S& y, const std::string& what) {
  const Range a = range_of(x), b = range_of(y);
  EXPECT_EQ(a.lo, b.lo) << what;
  EXPECT_EQ(a.hi, b.hi) << what;
}

TYPED_TEST(DualContract, ValuesAreTheBaseComputationAndDerivativesAnalytic) {
  using D = TypeParam;
  using S = decltype(D{}.v);
  using Tr = ScalarTraits<D>;
  using B = ScalarTraits<S>;
  using std::exp;
  using std::log;
  using std::sqrt;
  static_assert(Tr::is_interval == B::is_interval);
  static_assert(B::is_interval ? IntervalScalar<D> : PointScalar<D>);
  for (long bits : precisions<S>()) {
    const long p = truth_bits(bits);
    for (const char* s : {"0.375", "3", "28.8125", "7.25"}) {
      const std::string what = std::string(s) + " at " + std::to_string(bits);
      const S xs = B::from_decimal(s, bits);
      const D x = D::variable(xs, 0);
      const Bracket bx = bracket_of(rational_of(s), p);
      // The value part is the base type's own result, bit for bit.
      expect_same<S>(D(sqrt(x)).v, S(sqrt(xs)), what + " sqrt value");
      expect_same<S>(D(exp(x)).v, S(exp(xs)), what + " exp value");
      expect_same<S>(D(log(x)).v, S(log(xs)), what + " log value");
      expect_same<S>(Tr::pow_3_5(x).v, B::pow_3_5(xs), what + " pow_3_5 value");
      expect_same<S>(D(x * x / 3L).v, S(xs * xs / 3L), what + " x*x/3 value");
      // Derivatives: (sqrt x)' = 1/(2 sqrt x), (exp x)' = exp x, (log x)' = 1/x,
      // (x^(3/5))' = (3/5) x^(3/5) / x, (x^2/3)' = 2x/3, (5/x)' = -5/x^2.
      const mpq_class rel = inv_pow2(bits - 6);  // a few roundings of the chain rule
      const Bracket sq = increasing(mpfr_sqrt, bx);
      const Bracket one = bracket_of(1, p);
      expect_near_or_enclosing<S>(D(sqrt(x)).d[0], scaled_ratio(mpq_class(1, 2), one, sq), rel, what + " sqrt'");
      expect_near_or_enclosing<S>(D(exp(x)).d[0], increasing(mpfr_exp, bx), rel, what + " exp'");
      expect_near_or_enclosing<S>(D(log(x)).d[0], scaled_ratio(1, one, bx), rel, what + " log'");
      expect_near_or_enclosing<S>(Tr::pow_3_5(x).d[0], scaled_ratio(mpq_class(3, 5), increasing(pow35, bx), bx),
                                  mpq_class(16) * rel, what + " pow_3_5'");
      expect_rounded_or_enclosing<S>(D(x * x / 3L).d[0], 2 * rational_of(s) / 3, bits, what + " (x^2/3)'");
      const mpq_class q = rational_of(s);
      const Range dinv = range_of(D(5L / x).d[0]);
      const mpq_class tinv = -5 / (q * q);
      EXPECT_LE(abs_q(mpq_class((dinv.lo + dinv.hi) / 2 - tinv)), abs_q(tinv) * inv_pow2(bits - 3)) << what << " (5/x)'";
      // The other seed direction stays exactly zero.
      EXPECT_EQ(range_of(D(exp(x)).d[1]).lo, 0);
      EXPECT_EQ(range_of(D(exp(x)).d[1]).hi, 0);
    }
  }
}

TYPED_TEST(DualContract, TraitsForwardToTheValueAndKeepTheConventions) {
  using D = TypeParam;
  using S = decltype(D{}.v);
  using Tr = ScalarTraits<D>;
  using B = ScalarTraits<S>;
  for (long bits : precisions<S>()) {
    SCOPED_TRACE(bits);
    const D one = Tr::from_int(1, bits), zero = Tr::from_int(0, bits);
    const D x = D::variable(B::from_decimal("0.375", bits), 0);
    const D mx = D::variable(B::from_decimal("-0.375", bits), 1);
    EXPECT_EQ(Tr::lt(x, one), B::lt(x.v, one.v));
    EXPECT_EQ(Tr::le(one, x), B::le(one.v, x.v));
    EXPECT_EQ(Tr::is_zero(zero), Truth::yes);
    EXPECT_EQ(Tr::bits(x), bits);
    EXPECT_EQ(Tr::fixed_bits, B::fixed_bits);
    EXPECT_EQ(Tr::to_string(x), B::to_string(x.v));
    EXPECT_EQ(Tr::exponent(x), B::exponent(x.v));
    EXPECT_TRUE(Tr::likely_negative(mx));
    EXPECT_TRUE(Tr::derivatives_finite(x));
    // clamp moves only the value: the derivative is that of x. (Above 1 for a point; an
    // enclosure reaching above 1 for an interval.)
    const S tenth = B::from_decimal("0.1", bits);
    const S above = B::is_interval ? S(one.v + S(tenth - tenth)) : B::from_int(2, bits);
    const D c = Tr::clamp(D::variable(above, 0), zero, one);
    expect_same<S>(c.v, B::clamp(above, zero.v, one.v), "clamp value");
    if constexpr (B::is_interval) {
      EXPECT_EQ(range_of(c.v).hi, 1);
    } else {
      EXPECT_EQ(range_of(c.v).hi, range_of(B::below(one.v)).hi);  // 1 - 2^-bits; dd: 1 - 2^-1074
      EXPECT_LT(range_of(c.v).hi, 1);
    }
    EXPECT_EQ(range_of(c.d[0]).lo, 1);
    // The integer part is locally constant: zero derivative.
    D whole = zero;
    ASSERT_EQ(Tr::floor_certain(D::variable(B::from_decimal("2.5", bits), 0), whole), Truth::yes);
    EXPECT_EQ(range_of(whole.v).lo, 2);
    EXPECT_EQ(range_of(whole.d[0]).hi, 0);
    // nonneg of a negative value: a point dual becomes an exact zero with zero derivative;
    // an interval dual cuts only the value enclosure and keeps the derivatives.
    const D nn = Tr::nonneg(mx);
    EXPECT_EQ(range_of(nn.v).hi, 0);
    EXPECT_EQ(range_of(nn.d[1]).lo, B::is_interval ? 1 : 0);
    if constexpr (B::is_interval) {
      EXPECT_EQ(Tr::lower_string(x), B::lower_string(x.v));
      EXPECT_EQ(Tr::upper_string(x), B::upper_string(x.v));
    } else {
      const D b = Tr::below(x);
      expect_same<S>(b.v, B::below(x.v), "below value");
      EXPECT_EQ(range_of(b.d[0]).lo, 1);
      EXPECT_EQ(range_of(Tr::floor(x).d[0]).lo, 0);
    }
  }
}

}  // namespace
}  // namespace bouncer
