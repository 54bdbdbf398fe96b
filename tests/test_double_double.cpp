// DoubleDouble (--precision dd), checked against MPFR at 512 bits:
//  * every operation on random canonical operands (exponents over +-60, random low words,
//    near-cancelling pairs) within its proved relative error bound (Joldes, Muller and
//    Popescu 2017: 3u^2 for +, 7u^2 for *, 15u^2 for /; 4u^2 asserted for sqrt; with a double
//    integer operand 2u^2, 3u^2, 3.5u^2; u = 2^-53), and
//    every result canonical (hi = RN(hi + lo));
//  * exp and log within 32 units of 2^-106, x^(3/5) within 32 (measured below);
//  * decimals: hi = RN(q), lo = RN(q - hi) for random decimals, and to_string reads back to
//    the same pair, in at most 40 digits for random values;
//  * the whole step from random states in every model: dd's image is as close to the 512-bit
//    image as MPFR at 106 bits is (within a factor 64, or 2^-100 of the scale).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"
#include "exact.hpp"

namespace bouncer {
namespace {

using DD = DoubleDouble;
using Tr = ScalarTraits<DD>;
constexpr long kTruth = 512;

Mpfr m512(const DD& x) {
  Mpfr r(kTruth);
  mpfr_set_d(r.get(), x.hi(), MPFR_RNDN);
  mpfr_add_d(r.get(), r.get(), x.lo(), MPFR_RNDN);  // exact at 512 bits for these exponents
  return r;
}

// |got - want| / |want| in units of u^2 = 2^-106.
double rel_u2(const DD& got, const Mpfr& want) {
  if (mpfr_zero_p(want.get())) return got.hi() == 0 && got.lo() == 0 ? 0 : INFINITY;
  Mpfr d(kTruth);
  mpfr_sub(d.get(), m512(got).get(), want.get(), MPFR_RNDN);
  mpfr_div(d.get(), d.get(), want.get(), MPFR_RNDN);
  mpfr_mul_2si(d.get(), d.get(), 106, MPFR_RNDN);
  return std::fabs(mpfr_get_d(d.get(), MPFR_RNDN));
}

bool canonical(const DD& x) { return x.hi() + x.lo() == x.hi(); }

// A random canonical pair: hi with exponent in [-60, 60], lo anywhere in [-ulp(hi)/2,
// ulp(hi)/2] (now and then zero, or a power of two).
DD random_dd(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> ex(-60, 60), kind(0, 7);
  std::uniform_real_distribution<double> U(0.5, 1.0), S(-1.0, 1.0);
  const double hi = (rng() & 1 ? -1 : 1) * std::ldexp(U(rng), ex(rng));
  int e = 0;
  std::frexp(hi, &e);
  const int k = kind(rng);
  const double lo = k == 0 ? 0.0 : k == 1 ? std::ldexp(1.0, e - 54 - static_cast<int>(rng() % 8)) : std::ldexp(S(rng), e - 54);
  return DD::from_pair(hi, lo);
}

TEST(DoubleDouble, ArithmeticWithinItsErrorBoundsAndCanonical) {
  std::mt19937_64 rng(20261124);
  double worst[5] = {0, 0, 0, 0, 0};
  for (int i = 0; i < 20000; ++i) {
    const DD x = random_dd(rng);
    // Every fourth pair nearly cancels: y agrees with x in hi, or in a few leading bits.
    DD y = random_dd(rng);
    if (i % 4 == 0) y = DD::from_pair(-x.hi(), y.lo()) + DD(std::ldexp(x.hi(), -static_cast<int>(rng() % 80)));
    if (y.hi() == 0) continue;  // a cancelling draw that reached 0 exactly
    const Mpfr mx = m512(x), my = m512(y);
    Mpfr want(kTruth);
    SCOPED_TRACE("x = " + Tr::to_string(x) + ", y = " + Tr::to_string(y));
    mpfr_add(want.get(), mx.get(), my.get(), MPFR_RNDN);
    const DD s = x + y, p = x * y, q = x / y;
    worst[0] = std::max(worst[0], rel_u2(s, want));
    EXPECT_LE(rel_u2(s, want), 3.0) << "+";
    mpfr_sub(want.get(), mx.get(), my.get(), MPFR_RNDN);
    EXPECT_LE(rel_u2(x - y, want), 3.0) << "-";
    mpfr_mul(want.get(), mx.get(), my.get(), MPFR_RNDN);
    worst[1] = std::max(worst[1], rel_u2(p, want));
    EXPECT_LE(rel_u2(p, want), 7.0) << "*";
    mpfr_div(want.get(), mx.get(), my.get(), MPFR_RNDN);
    worst[2] = std::max(worst[2], rel_u2(q, want));
    EXPECT_LE(rel_u2(q, want), 15.0) << "/";
    const DD ax = abs(x), r = sqrt(ax);
    mpfr_sqrt(want.get(), m512(ax).get(), MPFR_RNDN);
    worst[3] = std::max(worst[3], rel_u2(r, want));
    EXPECT_LE(rel_u2(r, want), 4.0) << "sqrt";
    EXPECT_TRUE(canonical(s) && canonical(p) && canonical(q) && canonical(r));
    // With an integer operand (the double-word-by-double algorithms): 2, 1.5 and 3.5 u^2
    // in JMP; 4 asserted.
    const long n = static_cast<long>(rng() % 2000001) - 1000000;
    if (n != 0) {
      Mpfr mn(n, kTruth);
      mpfr_add(want.get(), mx.get(), mn.get(), MPFR_RNDN);
      EXPECT_LE(rel_u2(x + n, want), 4.0) << "x + " << n;
      mpfr_sub(want.get(), mn.get(), mx.get(), MPFR_RNDN);
      EXPECT_LE(rel_u2(n - x, want), 4.0) << n << " - x";
      mpfr_mul(want.get(), mx.get(), mn.get(), MPFR_RNDN);
      EXPECT_LE(rel_u2(x * n, want), 4.0) << "x * " << n;
      mpfr_div(want.get(), mx.get(), mn.get(), MPFR_RNDN);
      worst[4] = std::max(worst[4], rel_u2(x / n, want));
      EXPECT_LE(rel_u2(x / n, want), 4.0) << "x / " << n;
    }
    // Comparisons follow the exact values.
    EXPECT_EQ(x < y, mpfr_less_p(mx.get(), my.get()) != 0);
    EXPECT_EQ(x <= y, mpfr_lessequal_p(mx.get(), my.get()) != 0);
    if (::testing::Test::HasFailure()) return;
  }
  std::printf("worst relative errors in units of 2^-106: + %.2f, * %.2f, / %.2f, sqrt %.2f, / integer %.2f\n",
              worst[0], worst[1], worst[2], worst[3], worst[4]);
}

TEST(DoubleDouble, EveryLongIsExactAndLargeIntegerOperandsToo) {
  for (long n : {0L, 1L, -1L, (1L << 53) + 1, -((1L << 53) + 3), (1L << 62) + 12345, std::numeric_limits<long>::max(),
                 std::numeric_limits<long>::min() + 1}) {
    SCOPED_TRACE(n);
    EXPECT_EQ(exact(DD(n)), mpq_class(mpz_class(std::to_string(n))));
    EXPECT_TRUE(canonical(DD(n)));
    // x + n and x * n with n beyond 2^53 (not a double): as exact as with the pair.
    const DD x = Tr::from_decimal("0.375", 106);
    EXPECT_EQ(exact(DD(x + n)), exact(x) + mpq_class(mpz_class(std::to_string(n))));
  }
  const long big = (1L << 60) + 7;
  EXPECT_EQ(exact(DD(DD(3L) * big)), mpq_class(mpz_class(std::to_string(3 * big))));
}

TEST(DoubleDouble, CancellationIsExactWhereTheResultIsRepresentable) {
  // (1 + 2^-60) - 1 = 2^-60 and (x + tiny) - x = tiny: what QD's sloppy add gets wrong.
  const DD one(1L), tiny(std::ldexp(1.0, -60));
  const DD x = one + tiny;
  EXPECT_EQ(x.hi(), 1.0);
  EXPECT_EQ(x.lo(), std::ldexp(1.0, -60));
  EXPECT_EQ(exact(DD(x - one)), exact(tiny));
  const DD a = Tr::from_decimal("28.82", 106), b = DD::from_pair(-28.82, 0);
  EXPECT_EQ(exact(DD(a + b)), exact(a) + exact(b));  // |a + b| < 2^-48: exact in dd
}

TEST(DoubleDouble, TranscendentalsWithinTensOfUnitsOfUSquared) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-30.0, 30.0), P(1e-6, 1e6);
  double worst[3] = {0, 0, 0};
  for (int i = 0; i < 2000; ++i) {
    const DD x = DD::from_pair(U(rng), std::ldexp(U(rng), -60));
    const DD y = DD::from_pair(P(rng), std::ldexp(U(rng), -80));
    SCOPED_TRACE("x = " + Tr::to_string(x) + ", y = " + Tr::to_string(y));
    Mpfr want(kTruth);
    mpfr_exp(want.get(), m512(x).get(), MPFR_RNDN);
    worst[0] = std::max(worst[0], rel_u2(exp(x), want));
    EXPECT_LE(rel_u2(exp(x), want), 32.0) << "exp";
    mpfr_log(want.get(), m512(y).get(), MPFR_RNDN);
    if (std::fabs(y.hi() - 1) > 1e-3) {
      worst[1] = std::max(worst[1], rel_u2(log(y), want));
      EXPECT_LE(rel_u2(log(y), want), 32.0) << "log";
    }
    mpfr_pow_ui(want.get(), m512(y).get(), 3, MPFR_RNDN);
    mpfr_rootn_ui(want.get(), want.get(), 5, MPFR_RNDN);
    worst[2] = std::max(worst[2], rel_u2(Tr::pow_3_5(y), want));
    EXPECT_LE(rel_u2(Tr::pow_3_5(y), want), 32.0) << "x^(3/5)";  // x^3, a root and a Newton step
    if (::testing::Test::HasFailure()) return;
  }
  std::printf("worst relative errors in units of 2^-106: exp %.2f, log %.2f, x^(3/5) %.2f\n", worst[0], worst[1], worst[2]);
  EXPECT_TRUE(log(DD(-1.0)).is_nan());
  EXPECT_EQ(log(DD(0.0)).hi(), -INFINITY);
}

TEST(DoubleDouble, DecimalsConvertAsDoubleWordsAndPrintedValuesReadBack) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> digits(1, 40), ex(-30, 30);
  size_t longest = 0;
  for (int i = 0; i < 3000; ++i) {
    // A random decimal of up to 40 digits.
    std::string m;
    const int n = digits(rng);
    for (int k = 0; k < n; ++k) m += static_cast<char>('0' + rng() % 10);
    const std::string text = (rng() & 1 ? "-0." : "0.") + m + "e" + std::to_string(ex(rng));
    SCOPED_TRACE(text);
    const DD x = Tr::from_decimal(text, 106);
    const mpq_class q = rational_of(text);
    const mpq_class hi = round_to_bits(q, 53);
    EXPECT_EQ(exact(DD(x.hi())), hi);
    EXPECT_EQ(exact(x), hi + round_to_bits(mpq_class(q - hi), 53));
    const std::string s = Tr::to_string(x);
    EXPECT_EQ(Tr::from_decimal(s, 106), x) << s;
    longest = std::max(longest, s.size());
    // A random pair (not from a decimal) reads back too.
    const DD r = random_dd(rng);
    EXPECT_EQ(Tr::from_decimal(Tr::to_string(r), 106), r) << Tr::to_string(r);
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_LE(longest, 40u + 8u);  // sign, point, exponent: at most 40 significant digits here
  EXPECT_EQ(Tr::to_string(DD(0.0)), "0");
  EXPECT_EQ(Tr::to_string(DD(1L)), "1");
  EXPECT_EQ(Tr::to_string(DD(-0.375)), "-0.375");
}

TEST(DoubleDouble, StepIsAsAccurateAsMpfrAt106Bits) {
  // Random states in every model; the image in dd against the 512-bit image, next to MPFR's
  // at 106 bits. The states are doubles (exact in every type).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int compared = 0;
  for (int i = 0; i < 600; ++i) {
    ModelSpec m;
    const int law = i % 3;
    m.law = law == 0 ? Law::elastic : law == 1 ? Law::constant : Law::veldep;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.5g", 5 + 40 * U(rng));
    m.a = parse_decimal("a", buf);
    std::snprintf(buf, sizeof buf, "%.3g", 0.3 + 0.69 * U(rng));
    m.eps = law == 1 ? parse_decimal("eps", buf) : Decimal::from_int(1);
    m.c = parse_decimal("c", law == 2 ? "1000" : "1");
    m.wall = parse_wall("wall", i % 2 ? "triangle" : "asymmetric:0.3");
    validate(m);
    const ImpactMap<DD> map_dd(make_model<DD>(m, 106));
    const ImpactMap<Mpfr> map_106(make_model<Mpfr>(m, 106));
    const ImpactMap<Mpfr> map_512(make_model<Mpfr>(m, kTruth));
    const double th = U(rng), v = 4 + 30 * U(rng);
    auto start = [&](auto tag, long bits) {
      using T = typename decltype(tag)::type;
      return State<T>{ScalarTraits<T>::from_decimal(std::to_string(th), bits),
                      ScalarTraits<T>::from_decimal(std::to_string(v), bits)};
    };
    SCOPED_TRACE(std::string(name(m.law)) + " a=" + m.a.text() + " eps=" + m.eps.text() + " theta=" + std::to_string(th) +
                 " v=" + std::to_string(v));
    try {
      const auto r512 = map_512.step(start(Tag<Mpfr>{}, kTruth));
      const auto r106 = map_106.step(start(Tag<Mpfr>{}, 106));
      const auto rdd = map_dd.step(start(Tag<DD>{}, 106));
      if (r106.kind != r512.kind || r106.segment != r512.segment) continue;  // a borderline decision
      ASSERT_EQ(rdd.kind, r512.kind);
      ASSERT_EQ(rdd.segment, r512.segment);
      const double scale = std::max(1.0, std::fabs(mpfr_get_d(r512.next.v.get(), MPFR_RNDN)));
      auto err = [&](const Mpfr& got, const Mpfr& want) {  // exact difference at 512 bits
        Mpfr d(kTruth);
        mpfr_sub(d.get(), got.get(), want.get(), MPFR_RNDN);
        return std::fabs(mpfr_get_d(d.get(), MPFR_RNDN)) / scale;
      };
      const double floor_err = std::ldexp(1.0, -100);
      const double e106_th = err(r106.next.theta, r512.next.theta);
      const double e106_v = err(r106.next.v, r512.next.v);
      EXPECT_LE(err(m512(rdd.next.theta), r512.next.theta), std::max(64 * e106_th, floor_err));
      EXPECT_LE(err(m512(rdd.next.v), r512.next.v), std::max(64 * e106_v, floor_err));
      ++compared;
    } catch (const Undecided&) {
    }
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GE(compared, 500);
}

}  // namespace
}  // namespace bouncer
