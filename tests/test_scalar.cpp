// The scalar layer: exact decimals, correctly rounded conversions, round-trip printing,
// interval enclosures, three-valued comparisons, and the value semantics of Mpfr/Mpfi.
//
// Independent truth: GMP rationals. A decimal's exact value is built here by hand
// (digits / 10^k), its correct rounding to p bits is computed here with integer arithmetic
// (round half to even of q * 2^(p - e)), and every floating value is converted back to a
// rational exactly (mpq from double; through MPFR for long double; a three-double split for
// __float128) before comparing.
#include <gtest/gtest.h>
#include <quadmath.h>

#include <cmath>
#include <limits>
#include <cstdlib>
#include <string>
#include <vector>

#include "bouncer/scalar/decimal.hpp"
#include "bouncer/scalar/precision.hpp"
#include "bouncer/scalar/traits.hpp"
#include "bouncer/model/spec.hpp"
#include "exact.hpp"

namespace bouncer {
namespace {

const std::vector<std::string> kDecimals = {
    "0.1", "28.82", "1e-9", "0.3", "0.6", "19", "0.96", "-7.25", "123456789.123456789",
    "3.14159265358979323846264338327950288419716939937510582097494459",
    "2.5e-300", "1e22", "1e23", "6.02214076e23", "0.000000000000000000000000000000001",
    "9007199254740993",  // 2^53 + 1: a tie in double, rounds to even 2^53
    "1.00000000000000011102230246251565404236316680908203125",  // 1 + 2^-53: tie in double
    "4.0000000000000000000000000000000000000000000000000000000000000000000000001",
};

// ---------------------------------------------------------------------------------------
// Decimal

TEST(Decimal, ParsesExactRationals) {
  struct Case { const char* text; const char* value; };
  for (const Case& c : {Case{"0.1", "1/10"}, Case{"28.82", "1441/50"}, Case{"1e-9", "1/1000000000"},
                        Case{"-3.5E+2", "-350"}, Case{".5", "1/2"}, Case{"5.", "5"}, Case{"+7", "7"},
                        Case{"-0", "0"}, Case{"000.0100", "1/100"}, Case{"1.5e3", "1500"},
                        Case{"12e-1", "6/5"},
                        Case{"1.0000000000000000000000001", "10000000000000000000000001/10000000000000000000000000"}}) {
    SCOPED_TRACE(c.text);
    auto d = Decimal::parse(c.text);
    ASSERT_TRUE(d.has_value());
    EXPECT_EQ(d->value(), mpq_class(c.value));
    EXPECT_EQ(d->value(), rational_of(c.text));
    EXPECT_EQ(d->text(), c.text);  // the original text is kept for per-type conversion
  }
  EXPECT_EQ(Decimal::from_int(-12).value(), -12);
  // approx() is a display value: within one ulp of the exact rational (faithful).
  EXPECT_LE(abs(mpq_class(exact(Decimal::parse("0.1")->approx()) - mpq_class(1, 10))), inv_pow2(56));
  EXPECT_TRUE(*Decimal::parse("0.1") < *Decimal::parse("0.10000000000000000000001"));
  EXPECT_TRUE(*Decimal::parse("0.5") == *Decimal::parse("5e-1"));
}

TEST(Decimal, RejectsNonDecimals) {
  for (const char* bad : {"", " ", "inf", "-inf", "Infinity", "nan", "NaN", "0x1p3", "0x10", "1 ",
                          " 1", "1 0", "1e", "e5", ".", "-", "+", "1.2.3", "--1", "+-1", "1e+",
                          "1e1.5", "1,5", "1_000", "\t1", "1\n", "1e1234567", "1f", "0b1"}) {
    SCOPED_TRACE(std::string("'") + bad + "'");
    EXPECT_FALSE(Decimal::parse(bad).has_value());
  }
}

// ---------------------------------------------------------------------------------------
// from_decimal: correct rounding

template <class T>
void expect_correctly_rounded(const std::string& text, long p, long bits_arg) {
  SCOPED_TRACE(text + " at " + std::to_string(p) + " bits");
  const T x = ScalarTraits<T>::from_decimal(text, bits_arg);
  EXPECT_EQ(exact(x), round_to_bits(rational_of(text), p));
}

TEST(ScalarTraits, DoubleFromDecimalIsCorrectlyRounded) {
  for (const std::string& s : kDecimals) {
    const double x = ScalarTraits<double>::from_decimal(s, 53);
    EXPECT_EQ(x, std::strtod(s.c_str(), nullptr)) << s;
    expect_correctly_rounded<double>(s, 53, 53);
  }
  EXPECT_EQ(ScalarTraits<double>::from_decimal("9007199254740993", 53), 9007199254740992.0);
  EXPECT_EQ(ScalarTraits<double>::from_decimal("1.00000000000000011102230246251565404236316680908203125", 53), 1.0);
  EXPECT_EQ(ScalarTraits<double>::from_decimal("1.00000000000000011102230246251565404236316680908203126", 53),
            std::nextafter(1.0, 2.0));
}

TEST(ScalarTraits, LongDoubleAndQuadFromDecimalAreCorrectlyRounded) {
  ASSERT_EQ(std::numeric_limits<long double>::digits, 64);
  for (const std::string& s : kDecimals) {
    expect_correctly_rounded<long double>(s, 64, 64);
    expect_correctly_rounded<Quad>(s, 113, 113);
  }
}

TEST(ScalarTraits, MpfrFromDecimalIsCorrectlyRounded) {
  for (long p : {16L, 53L, 113L, 256L, 1000L, 4096L}) {
    for (const std::string& s : kDecimals) {
      expect_correctly_rounded<Mpfr>(s, p, p);
      EXPECT_EQ(ScalarTraits<Mpfr>::from_decimal(s, p).bits(), p);
    }
  }
}

TEST(ScalarTraits, FromDecimalRejectsGarbage) {
  for (const char* bad : {"", "abc", "1.5x", "1e", "0.1 "}) {
    SCOPED_TRACE(std::string("'") + bad + "'");
    EXPECT_THROW(ScalarTraits<double>::from_decimal(bad, 53), std::invalid_argument);
    EXPECT_THROW(ScalarTraits<long double>::from_decimal(bad, 64), std::invalid_argument);
    EXPECT_THROW(ScalarTraits<Quad>::from_decimal(bad, 113), std::invalid_argument);
    EXPECT_THROW(ScalarTraits<Mpfr>::from_decimal(bad, 256), std::invalid_argument);
    EXPECT_THROW(ScalarTraits<Mpfi>::from_decimal(bad, 256), std::invalid_argument);
  }
}

// ---------------------------------------------------------------------------------------
// to_string round trips

// Values that need every bit: 1/3, sqrt 2, pi-ish, tiny and huge, negative, integers.
template <class T>
std::vector<T> sample_values(long bits) {
  using Tr = ScalarTraits<T>;
  using std::sqrt;
  const T one = Tr::from_int(1, bits), three = Tr::from_int(3, bits);
  std::vector<T> v = {one / three, sqrt(Tr::from_int(2, bits)), -one / Tr::from_int(7, bits),
                      Tr::from_decimal("28.82", bits), Tr::from_decimal("1e-300", bits),
                      Tr::from_decimal("1.234567890123456789012345678901234567890123e250", bits),
                      Tr::from_int(4, bits), Tr::from_int(-4, bits), Tr::from_decimal("0.5", bits),
                      Tr::from_int(0, bits), Tr::from_decimal("1e-9", bits) / three};
  // A value just below 1/2 (one ulp), as the map produces near corners.
  v.push_back(Tr::below(Tr::from_decimal("0.5", bits)));
  return v;
}

template <class T>
void expect_round_trip(long bits) {
  using Tr = ScalarTraits<T>;
  for (const T& x : sample_values<T>(bits)) {
    const std::string s = Tr::to_string(x);
    SCOPED_TRACE(s);
    ASSERT_TRUE(Decimal::parse(s).has_value()) << "printed text is not a plain decimal";
    const T y = Tr::from_decimal(s, bits);
    EXPECT_EQ(exact(y), exact(x));
    EXPECT_EQ(Tr::bits(y), Tr::bits(x));
  }
}

TEST(ScalarTraits, ToStringRoundTripsDouble) { expect_round_trip<double>(53); }
TEST(ScalarTraits, ToStringRoundTripsLongDouble) { expect_round_trip<long double>(64); }
TEST(ScalarTraits, ToStringRoundTripsQuad) { expect_round_trip<Quad>(113); }
TEST(ScalarTraits, ToStringRoundTripsMpfr) {
  for (long bits : {53L, 113L, 256L, 1000L}) {
    SCOPED_TRACE(bits);
    expect_round_trip<Mpfr>(bits);
  }
}

TEST(ScalarTraits, MpfiEndStringsEncloseTheInterval) {
  // The printed ends, read back as rationals, must enclose the interval (rounded outward).
  for (long bits : {53L, 128L, 512L}) {
    Mpfi x = Mpfi(1, bits) / Mpfi(3, bits);
    const mpq_class lo = rational_of(ScalarTraits<Mpfi>::lower_string(x));
    const mpq_class hi = rational_of(ScalarTraits<Mpfi>::upper_string(x));
    EXPECT_LE(lo, exact(x.lower()));
    EXPECT_GE(hi, exact(x.upper()));
    EXPECT_LT(lo, mpq_class(1, 3));
    EXPECT_GT(hi, mpq_class(1, 3));
  }
}

// ---------------------------------------------------------------------------------------
// Mpfi enclosures of decimals

TEST(Mpfi, FromDecimalEnclosesTheExactDecimalTightly) {
  for (long bits : {53L, 128L, 512L}) {
    for (const char* s : {"0.1", "28.82", "1e-9", "0.96", "-7.3"}) {
      SCOPED_TRACE(std::string(s) + " at " + std::to_string(bits));
      const Mpfi x = ScalarTraits<Mpfi>::from_decimal(s, bits);
      const mpq_class q = rational_of(s);
      EXPECT_EQ(x.bits(), bits);
      EXPECT_LE(exact(x.lower()), q);
      EXPECT_GE(exact(x.upper()), q);
      EXPECT_LT(exact(x.lower()), q);  // not representable in binary
      // Tightest: the ends are neighbours.
      Mpfr next = x.lower();
      mpfr_nextabove(next.get());
      EXPECT_TRUE(next == x.upper());
      // Width below 2^-(bits-6) relative.
      const mpq_class w = exact(x.width());
      EXPECT_LT(w, abs(q) * inv_pow2(bits - 6));
      // Contains the correctly rounded point value.
      EXPECT_TRUE(x.contains(ScalarTraits<Mpfr>::from_decimal(s, bits)));
    }
  }
  const Mpfi half = ScalarTraits<Mpfi>::from_decimal("0.5", 128);
  EXPECT_TRUE(half.lower() == half.upper());
  EXPECT_EQ(exact(half.lower()), mpq_class(1, 2));
}

// ---------------------------------------------------------------------------------------
// Three-valued predicates

Mpfi iv(const char* lo, const char* hi, long bits = 64) {
  return Mpfi(ScalarTraits<Mpfr>::from_decimal(lo, bits), ScalarTraits<Mpfr>::from_decimal(hi, bits));
}

TEST(Truth, IntervalPredicates) {
  using Tr = ScalarTraits<Mpfi>;
  // Disjoint.
  EXPECT_EQ(Tr::lt(iv("1", "2"), iv("3", "4")), Truth::yes);
  EXPECT_EQ(Tr::le(iv("1", "2"), iv("3", "4")), Truth::yes);
  EXPECT_EQ(Tr::lt(iv("3", "4"), iv("1", "2")), Truth::no);
  EXPECT_EQ(Tr::le(iv("3", "4"), iv("1", "2")), Truth::no);
  // Overlapping: some pairs satisfy, some do not.
  EXPECT_EQ(Tr::lt(iv("1", "3"), iv("2", "4")), Truth::unknown);
  EXPECT_EQ(Tr::le(iv("1", "3"), iv("2", "4")), Truth::unknown);
  EXPECT_EQ(Tr::lt(iv("2", "4"), iv("1", "3")), Truth::unknown);
  // Touching at one point: [1,2] <= [2,3] always; [1,2] < [2,3] not at (2, 2).
  EXPECT_EQ(Tr::le(iv("1", "2"), iv("2", "3")), Truth::yes);
  EXPECT_EQ(Tr::lt(iv("1", "2"), iv("2", "3")), Truth::unknown);
  EXPECT_EQ(Tr::lt(iv("2", "3"), iv("1", "2")), Truth::no);
  EXPECT_EQ(Tr::le(iv("2", "3"), iv("1", "2")), Truth::unknown);
  // Equal points.
  EXPECT_EQ(Tr::lt(iv("2", "2"), iv("2", "2")), Truth::no);
  EXPECT_EQ(Tr::le(iv("2", "2"), iv("2", "2")), Truth::yes);
  // Zero.
  EXPECT_EQ(Tr::is_zero(iv("0", "0")), Truth::yes);
  EXPECT_EQ(Tr::is_zero(iv("-1", "1")), Truth::unknown);
  EXPECT_EQ(Tr::is_zero(iv("0", "1")), Truth::unknown);
  EXPECT_EQ(Tr::is_zero(iv("1e-30", "1")), Truth::no);
  EXPECT_EQ(Tr::is_zero(iv("-2", "-1e-30")), Truth::no);
  // NaN.
  Mpfi nan(64);  // default value is NaN
  EXPECT_EQ(Tr::lt(nan, iv("1", "2")), Truth::invalid);
  EXPECT_EQ(Tr::le(iv("1", "2"), nan), Truth::invalid);
  EXPECT_EQ(Tr::is_zero(nan), Truth::invalid);
  // An enclosure of 0.1 is not certainly equal to 0.1's other enclosure's neighbour...
  const Mpfi tenth = Tr::from_decimal("0.1", 128);
  EXPECT_EQ(Tr::lt(tenth, tenth), Truth::unknown);
  EXPECT_EQ(Tr::le(tenth, tenth), Truth::unknown);
  EXPECT_EQ(Tr::is_zero(tenth - tenth), Truth::unknown);
}

template <class T>
void point_predicates(long bits) {
  using Tr = ScalarTraits<T>;
  const T one = Tr::from_int(1, bits), two = Tr::from_int(2, bits), zero = Tr::from_int(0, bits);
  EXPECT_EQ(Tr::lt(one, two), Truth::yes);
  EXPECT_EQ(Tr::lt(two, one), Truth::no);
  EXPECT_EQ(Tr::lt(one, one), Truth::no);
  EXPECT_EQ(Tr::le(one, one), Truth::yes);
  EXPECT_EQ(Tr::le(two, one), Truth::no);
  EXPECT_EQ(Tr::is_zero(zero), Truth::yes);
  EXPECT_EQ(Tr::is_zero(-zero), Truth::yes);
  EXPECT_EQ(Tr::is_zero(one), Truth::no);
  EXPECT_EQ(Tr::is_zero(Tr::from_decimal("1e-300", bits)), Truth::no);
  const T nan = zero / zero;
  EXPECT_EQ(Tr::lt(nan, one), Truth::invalid);
  EXPECT_EQ(Tr::le(one, nan), Truth::invalid);
  EXPECT_EQ(Tr::is_zero(nan), Truth::invalid);
}

TEST(Truth, PointPredicates) {
  point_predicates<double>(53);
  point_predicates<long double>(64);
  point_predicates<Quad>(113);
  point_predicates<Mpfr>(256);
}

TEST(Truth, DecideAndCertainly) {
  EXPECT_TRUE(decide(Truth::yes, Reason::riding));
  EXPECT_FALSE(decide(Truth::no, Reason::riding));
  try {
    decide(Truth::unknown, Reason::sticking_threshold);
    ADD_FAILURE() << "unknown must throw";
  } catch (const Undecided& u) {
    EXPECT_EQ(u.reason, Reason::sticking_threshold);
  }
  try {
    decide(Truth::invalid, Reason::sticking_threshold);
    ADD_FAILURE() << "invalid must throw";
  } catch (const Undecided& u) {
    EXPECT_EQ(u.reason, Reason::nonfinite);
  }
  EXPECT_TRUE(certainly(Truth::yes));
  EXPECT_FALSE(certainly(Truth::unknown));
  EXPECT_FALSE(certainly(Truth::invalid));
  EXPECT_FALSE(certainly(Truth::no));
  EXPECT_EQ(!Truth::yes, Truth::no);
  EXPECT_EQ(!Truth::unknown, Truth::unknown);
}

// ---------------------------------------------------------------------------------------
// Mpfr / Mpfi value semantics across inline and heap precisions

Mpfr third(long bits) { Mpfr r(bits); mpfr_set_ui(r.get(), 1, MPFR_RNDN); mpfr_div_ui(r.get(), r.get(), 3, MPFR_RNDN); return r; }

// The exact rational of 1/3 rounded to `bits` (independent of Mpfr).
mpq_class third_exact(long bits) { return round_to_bits(mpq_class(1, 3), bits); }

TEST(Mpfr, InlineLimitIsAsDocumented) {
  EXPECT_EQ(Mpfr::kInlineBits, 1024);
}

TEST(Mpfr, CopyMoveAssignKeepValueAndPrecision) {
  const std::vector<long> precs = {2, 53, 256, 1024, 1025, 4096};  // inline up to 1024
  for (long pa : precs) {
    for (long pb : precs) {
      SCOPED_TRACE("from " + std::to_string(pa) + " to " + std::to_string(pb));
      // Copy construction; the copy is independent of the original.
      {
        Mpfr src = third(pa);
        Mpfr cp(src);
        src += Mpfr(1, pa);
        EXPECT_EQ(cp.bits(), pa);
        EXPECT_EQ(exact(cp), third_exact(pa));
        EXPECT_EQ(exact(src), round_to_bits(third_exact(pa) + 1, pa));
      }
      // Copy assignment onto a value of another precision.
      {
        Mpfr dst = third(pb);
        const Mpfr src = third(pa);
        dst = src;
        EXPECT_EQ(dst.bits(), pa);
        EXPECT_EQ(exact(dst), third_exact(pa));
        dst *= Mpfr(3, 64);  // modifying the copy leaves the source alone
        EXPECT_EQ(exact(src), third_exact(pa));
      }
      // Move assignment; the source dies before the target is read.
      {
        Mpfr dst = third(pb);
        {
          Mpfr src = third(pa);
          dst = std::move(src);
          src = third(pb);  // a moved-from value can be reassigned
          EXPECT_EQ(exact(src), third_exact(pb));
        }
        EXPECT_EQ(dst.bits(), pa);
        EXPECT_EQ(exact(dst), third_exact(pa));
        Mpfr again = dst + dst;  // still usable in arithmetic
        EXPECT_EQ(exact(again), 2 * third_exact(pa));
      }
    }
    SCOPED_TRACE("prec " + std::to_string(pa));
    // Move construction, outliving the source.
    Mpfr* heap_src = new Mpfr(third(pa));
    Mpfr moved(std::move(*heap_src));
    delete heap_src;
    EXPECT_EQ(moved.bits(), pa);
    EXPECT_EQ(exact(moved), third_exact(pa));
    // Self-assignment.
    Mpfr self = third(pa);
    Mpfr& alias = self;
    self = alias;
    EXPECT_EQ(exact(self), third_exact(pa));
    self = std::move(alias);
    EXPECT_EQ(exact(self), third_exact(pa));
    EXPECT_EQ(self.bits(), pa);
  }
}

TEST(Mpfr, VectorReallocationKeepsValues) {
  // std::vector moves elements on growth: mixed inline and heap precisions.
  std::vector<Mpfr> v;
  const std::vector<long> precs = {53, 4096, 1024, 1025, 256};
  for (int i = 0; i < 200; ++i) {
    const long p = precs[i % precs.size()];
    v.push_back(third(p) * static_cast<long>(i));
  }
  for (int i = 0; i < 200; ++i) {
    const long p = precs[i % precs.size()];
    ASSERT_EQ(v[i].bits(), p);
    EXPECT_EQ(exact(v[i]), round_to_bits(third_exact(p) * i, p)) << i;
  }
  std::vector<Mpfr> w = v;  // copy of the whole vector
  v.clear();
  for (int i = 0; i < 200; ++i) EXPECT_EQ(w[i].bits(), precs[i % precs.size()]);
}

TEST(Mpfr, PrecisionRules) {
  const Mpfr a = third(64), b = third(300);
  EXPECT_EQ(Mpfr(a + b).bits(), 300);
  EXPECT_EQ(Mpfr(b * a).bits(), 300);
  Mpfr c = a;
  c += b;  // compound assignment keeps the left precision
  EXPECT_EQ(c.bits(), 64);
  EXPECT_EQ(exact(c), round_to_bits(third_exact(64) + third_exact(300), 64));
  EXPECT_EQ(Mpfr(a * 3L).bits(), 64);
  // Integer operands are exact: (1/3 rounded) * 3 at the operand's precision.
  EXPECT_EQ(exact(a * 3L), round_to_bits(third_exact(64) * 3, 64));
  EXPECT_EQ(exact(1L - a), round_to_bits(1 - third_exact(64), 64));
}

// ---------------------------------------------------------------------------------------
// Mpfr expressions: evaluated in place, they must round exactly as one correctly rounded
// temporary per operation would (truth: exact rationals rounded with integers).

Mpfr from_q(const mpq_class& q, long bits) {
  Mpfr r(bits);
  mpfr_set_q(r.get(), q.get_mpq_t(), MPFR_RNDN);
  return r;
}
mpq_class rnd(const mpq_class& q, long bits) { return round_to_bits(q, bits); }
Mpfr by_value(const Mpfr& x) { return x; }  // a temporary operand

// Integer operands are exact; a floating operand would be rounded somewhere unseen (it used to
// convert silently to long: x * 0.5 was x * 0), so it does not compile.
template <class X, class N>
concept multiplies = requires(const X& x, N n) { Mpfr(x * n); };
template <class X, class N>
concept adds_to = requires(const X& x, N n) { Mpfr(n + x); };
static_assert(multiplies<Mpfr, int> && multiplies<Mpfr, long> && adds_to<Mpfr, unsigned>);
static_assert(!multiplies<Mpfr, double> && !adds_to<Mpfr, double> && !multiplies<Mpfr, float>);
static_assert(!multiplies<Mpfr, unsigned long>);  // would not fit MPFR's long

TEST(MpfrExpression, NestedExpressionsRoundLikeOneTemporaryPerOperation) {
  for (long p : {53L, 113L, 1024L, 1100L}) {  // 1100: limbs on the heap
    SCOPED_TRACE("bits " + std::to_string(p));
    const Mpfr x = from_q(mpq_class(1, 3), p), y = from_q(mpq_class(2, 7), p);
    const Mpfr z = from_q(mpq_class(5, 11), p), w = from_q(mpq_class(-1, 13), p);
    const mpq_class X = exact(x), Y = exact(y), Z = exact(z), W = exact(w);
    auto R = [p](const mpq_class& q) { return rnd(q, p); };
    // left-deep, right-deep, both sides nodes, integers on either side, negation
    EXPECT_EQ(exact(Mpfr((x + y) * z - w)), R(R(R(X + Y) * Z) - W));
    EXPECT_EQ(exact(Mpfr(x / (y - z * w))), R(X / R(Y - R(Z * W))));
    EXPECT_EQ(exact(Mpfr((x + y) * (z - w))), R(R(X + Y) * R(Z - W)));
    EXPECT_EQ(exact(Mpfr(2 * x * y / 3 - 1)), R(R(R(R(2 * X) * Y) / 3) - 1));
    EXPECT_EQ(exact(Mpfr(1 - x / (2 - y))), R(1 - R(X / R(2 - Y))));
    EXPECT_EQ(exact(Mpfr(-(x - y) * -z)), R(R(-(X - Y)) * -Z));
    EXPECT_EQ(exact(Mpfr(3 / (x + 5) + 7 / z)), R(R(3 / R(X + 5)) + R(7 / Z)));
    Mpfr d(p);
    d = (w - x) / (y + z) * (x - y);  // assignment evaluates into d as well
    EXPECT_EQ(exact(d), R(R(R(W - X) / R(Y + Z)) * R(X - Y)));
    EXPECT_EQ(d.bits(), p);
  }
}

TEST(MpfrExpression, SubexpressionsOfSmallerPrecisionRoundToTheirOwnPrecision) {
  const Mpfr x = from_q(mpq_class(1, 3), 64), z = from_q(mpq_class(2, 7), 64);
  const Mpfr y = from_q(mpq_class(5, 11), 300);
  const mpq_class X = exact(x), Y = exact(y), Z = exact(z);
  const mpq_class own = rnd(rnd(X * Z, 64) + Y, 300);  // x*z is a 64-bit temporary
  ASSERT_NE(own, rnd(X * Z + Y, 300));  // the test can tell the two apart
  const Mpfr d = x * z + y;
  EXPECT_EQ(d.bits(), 300);
  EXPECT_EQ(exact(d), own);
  EXPECT_EQ(exact(Mpfr(y + x * z)), rnd(Y + rnd(X * Z, 64), 300));
  EXPECT_EQ(exact(Mpfr((x - z) * (y + y))), rnd(rnd(X - Z, 64) * rnd(Y + Y, 300), 300));
  EXPECT_EQ(exact(Mpfr(-(x * z) + y)), rnd(-rnd(X * Z, 64) + Y, 300));
}

TEST(MpfrExpression, DestinationMayBeAnOperand) {
  for (long p : {53L, 1100L}) {
    SCOPED_TRACE("bits " + std::to_string(p));
    const Mpfr x = from_q(mpq_class(1, 3), p), y = from_q(mpq_class(2, 7), p);
    const mpq_class X = exact(x), Y = exact(y), D = exact(from_q(mpq_class(-4, 9), p));
    auto R = [p](const mpq_class& q) { return rnd(q, p); };
    auto fresh = [p] { return from_q(mpq_class(-4, 9), p); };
    Mpfr d = fresh();
    d = (d + y) * d;  // d read after the left side is evaluated into d
    EXPECT_EQ(exact(d), R(R(D + Y) * D));
    d = fresh();
    d = y * (x - d);
    EXPECT_EQ(exact(d), R(Y * R(X - D)));
    d = fresh();
    d = d - 2 * d * y;  // d on the left, the right side a node containing d
    EXPECT_EQ(exact(d), R(D - R(R(2 * D) * Y)));
    d = fresh();
    d = (y - d) / d;
    EXPECT_EQ(exact(d), R(R(Y - D) / D));
    d = fresh();
    d = (x + d) * (d - y) - d;
    EXPECT_EQ(exact(d), R(R(R(X + D) * R(D - Y)) - D));
    d = fresh();
    d = sqrt(d * d) + d;
    Mpfr t = fresh();  // the same operations as raw MPFR calls on the old value
    const Mpfr old = fresh();
    mpfr_mul(t.get(), old.get(), old.get(), MPFR_RNDN);
    mpfr_sqrt(t.get(), t.get(), MPFR_RNDN);
    mpfr_add(t.get(), t.get(), old.get(), MPFR_RNDN);
    EXPECT_EQ(exact(d), exact(t));
  }
}

TEST(MpfrExpression, AssignmentTakesThePrecisionCompoundKeepsIt) {
  const Mpfr x = from_q(mpq_class(1, 3), 300), y = from_q(mpq_class(2, 7), 300);
  const mpq_class X = exact(x), Y = exact(y);
  Mpfr d(53);
  d = x * y + x;
  EXPECT_EQ(d.bits(), 300);
  EXPECT_EQ(exact(d), rnd(rnd(X * Y, 300) + X, 300));
  Mpfr c = from_q(mpq_class(1, 5), 64);
  const mpq_class C = exact(c);
  c += x * y;  // the product is rounded at its own 300 bits, then the sum at c's 64
  EXPECT_EQ(c.bits(), 64);
  EXPECT_EQ(exact(c), rnd(C + rnd(X * Y, 300), 64));
  c = from_q(mpq_class(1, 5), 64);
  c /= x - y;
  EXPECT_EQ(exact(c), rnd(C / rnd(X - Y, 300), 64));
}

TEST(MpfrExpression, TemporaryOperandsAndFunctions) {
  const long p = 113;
  const Mpfr x = from_q(mpq_class(1, 3), p), y = from_q(mpq_class(2, 7), p);
  const mpq_class X = exact(x), Y = exact(y);
  EXPECT_EQ(exact(Mpfr(by_value(x) + by_value(y) * 2)), rnd(X + rnd(Y * 2, p), p));
  EXPECT_EQ(exact(Mpfr(2 - by_value(x))), rnd(2 - X, p));
  // The functions against the same MPFR calls on explicit temporaries.
  auto ref = [p](int (*f)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t), const Mpfr& arg) {
    Mpfr r(p);
    f(r.get(), arg.get(), MPFR_RNDN);
    return exact(r);
  };
  const Mpfr xy = x * y, negx = -x, x1 = x + 1, xm1 = x - 1;
  EXPECT_EQ(exact(Mpfr(sqrt(x * y))), ref(mpfr_sqrt, xy));
  EXPECT_EQ(exact(Mpfr(exp(-x))), ref(mpfr_exp, negx));
  EXPECT_EQ(exact(Mpfr(log(x + 1))), ref(mpfr_log, x1));
  EXPECT_EQ(exact(Mpfr(abs(x - 1))), ref(mpfr_abs, xm1));
  EXPECT_EQ(exact(Mpfr(floor(x * 7))), mpq_class(2));
  EXPECT_EQ(exact(Mpfr(floor(-x))), mpq_class(-1));
  Mpfr d = x;
  d = sqrt(d);  // in place
  EXPECT_EQ(exact(d), ref(mpfr_sqrt, x));
  // NaN propagates through a tree and is visible to the comparisons.
  const Mpfr nan(p);
  EXPECT_TRUE(mpfr_nan_p(Mpfr((nan + x) * 2 - y).get()));
  EXPECT_FALSE(nan * 1 < x);
  EXPECT_FALSE(x <= nan - 1);
}

TEST(Mpfi, CopyMoveAssignKeepEndsAndPrecision) {
  const std::vector<long> precs = {53, 1024, 1025, 4096};
  for (long pa : precs) {
    for (long pb : precs) {
      SCOPED_TRACE("from " + std::to_string(pa) + " to " + std::to_string(pb));
      const Mpfi ref = Mpfi(1, pa) / Mpfi(3, pa);
      Mpfi dst = Mpfi(2, pb) / Mpfi(7, pb);
      dst = ref;
      EXPECT_EQ(dst.bits(), pa);
      EXPECT_TRUE(dst.lower() == ref.lower() && dst.upper() == ref.upper());
      Mpfi dst2 = Mpfi(2, pb) / Mpfi(7, pb);
      {
        Mpfi src = ref;
        dst2 = std::move(src);
      }
      EXPECT_EQ(dst2.bits(), pa);
      EXPECT_TRUE(dst2.lower() == ref.lower() && dst2.upper() == ref.upper());
      Mpfi moved(std::move(dst2));
      EXPECT_TRUE(moved.lower() == ref.lower() && moved.upper() == ref.upper());
      EXPECT_LT(exact(moved.lower()), mpq_class(1, 3));
      EXPECT_GT(exact(moved.upper()), mpq_class(1, 3));
    }
  }
}

// ---------------------------------------------------------------------------------------
// Mpfi arithmetic encloses the exact result and the Mpfr result at the same precision

TEST(Mpfi, ArithmeticEnclosesExactAndMpfrResults) {
  const std::vector<std::pair<const char*, const char*>> pairs = {
      {"0.1", "28.82"}, {"-7.3", "0.96"}, {"1e-9", "3"}, {"19", "-0.0001"}, {"2.5", "2.5"}};
  for (long bits : {53L, 128L, 512L}) {
    for (auto [xs, ys] : pairs) {
      SCOPED_TRACE(std::string(xs) + ", " + ys + " at " + std::to_string(bits));
      using TI = ScalarTraits<Mpfi>;
      using TR = ScalarTraits<Mpfr>;
      const Mpfi X = TI::from_decimal(xs, bits), Y = TI::from_decimal(ys, bits);
      const Mpfr x = TR::from_decimal(xs, bits), y = TR::from_decimal(ys, bits);
      const mpq_class qx = rational_of(xs), qy = rational_of(ys);
      auto encloses = [](const Mpfi& I, const mpq_class& q) {
        return exact(I.lower()) <= q && q <= exact(I.upper());
      };
      EXPECT_TRUE(encloses(X + Y, qx + qy));
      EXPECT_TRUE(encloses(X - Y, qx - qy));
      EXPECT_TRUE(encloses(X * Y, qx * qy));
      EXPECT_TRUE(encloses(X / Y, qx / qy));
      EXPECT_TRUE(encloses(X * 7L - 3L, qx * 7 - 3));
      EXPECT_TRUE(encloses(5L / Y, 5 / qy));
      EXPECT_TRUE(encloses(2L - X, 2 - qx));
      EXPECT_TRUE((X + Y).contains(x + y));
      EXPECT_TRUE((X - Y).contains(x - y));
      EXPECT_TRUE((X * Y).contains(x * y));
      EXPECT_TRUE((X / Y).contains(x / y));
      EXPECT_TRUE((-X).contains(-x));
      EXPECT_TRUE(abs(X).contains(abs(x)));
      EXPECT_TRUE(exp(X / 10L).contains(exp(x / 10L)));
      EXPECT_TRUE(sqrt(abs(Y)).contains(sqrt(abs(y))));
      EXPECT_TRUE(log(abs(X)).contains(log(abs(x))));
      EXPECT_TRUE(TI::pow_3_5(abs(X)).contains(TR::pow_3_5(abs(x))));
      // Widths stay small: a few ulps of the result.
      const Mpfi P = X * Y;
      EXPECT_LT(exact(P.width()), abs(mpq_class(qx * qy)) * inv_pow2(bits - 8));
    }
  }
}

TEST(ScalarTraits, PowThreeFifthsMatchesHighPrecision) {
  // x^(3/5) against a 2000-bit exp(0.6 log x). The fixed-size types call pow(x, 0.6) with a
  // rounded exponent 0.6(1 + d), |d| <= 2^-p, which costs a relative |0.6 d ln x| on top of
  // the pow's own error: bound (2 + |ln x|) ulps. Mpfr (x^3 then 5th root) and Mpfi must do
  // better: a few ulps, and an enclosure.
  for (const char* s : {"0.001", "0.5", "2", "8.5", "1000", "1e-12"}) {
    SCOPED_TRACE(s);
    Mpfr ref = ScalarTraits<Mpfr>::from_decimal(s, 2000);
    const double ln = std::fabs(std::log(std::strtod(s, nullptr)));
    ref = exp(log(ref) * Mpfr(3, 2000) / Mpfr(5, 2000));
    const mpq_class r = exact(ref);
    auto rel = [&](const mpq_class& q) -> mpq_class { return abs(q - r) / r; };
    const mpq_class allow = mpq_class(2 + ln);
    EXPECT_LT(rel(exact(ScalarTraits<double>::pow_3_5(ScalarTraits<double>::from_decimal(s, 53)))), allow * inv_pow2(53));
    EXPECT_LT(rel(exact(ScalarTraits<long double>::pow_3_5(ScalarTraits<long double>::from_decimal(s, 64)))), allow * inv_pow2(64));
    EXPECT_LT(rel(exact(ScalarTraits<Quad>::pow_3_5(ScalarTraits<Quad>::from_decimal(s, 113)))), allow * inv_pow2(113));
    // Mpfr: input rounding (3/5 ulp) + two correctly rounded operations.
    EXPECT_LT(rel(exact(ScalarTraits<Mpfr>::pow_3_5(ScalarTraits<Mpfr>::from_decimal(s, 256)))), inv_pow2(254));
    const Mpfi I = ScalarTraits<Mpfi>::pow_3_5(ScalarTraits<Mpfi>::from_decimal(s, 256));
    EXPECT_LE(exact(I.lower()), r);
    EXPECT_GE(exact(I.upper()), r);
    EXPECT_LT(exact(I.width()) / r, mpq_class(16 + 4 * ln) * inv_pow2(256));
  }
}

TEST(ScalarTraits, BelowExponentFloor) {
  EXPECT_EQ(ScalarTraits<double>::below(0.5), std::nextafter(0.5, 0.0));
  EXPECT_EQ(exact(ScalarTraits<Mpfr>::below(Mpfr(1, 10))), mpq_class(1023, 1024));
  EXPECT_EQ(exact(ScalarTraits<Quad>::below(Quad(1))), 1 - inv_pow2(113));
  EXPECT_EQ(exact(ScalarTraits<long double>::below(1.0L)), 1 - inv_pow2(64));
  // exponent e: 2^(e-1) <= |x| < 2^e.
  EXPECT_EQ(ScalarTraits<double>::exponent(1.0), 1);
  EXPECT_EQ(ScalarTraits<double>::exponent(1e12), 40);
  EXPECT_EQ(ScalarTraits<Quad>::exponent(Quad(1e12)), 40);
  EXPECT_EQ(ScalarTraits<Mpfr>::exponent(Mpfr(1000000000000L, 128)), 40);
  EXPECT_EQ(ScalarTraits<long double>::exponent(0.75L), 0);
  EXPECT_EQ(exact(ScalarTraits<Mpfr>::floor(ScalarTraits<Mpfr>::from_decimal("-2.5", 100))), -3);
  EXPECT_EQ(exact(ScalarTraits<Quad>::floor(ScalarTraits<Quad>::from_decimal("7.999", 113))), 7);
}

TEST(ScalarTraits, DoubleExponentIsFrexps) {
  // double's exponent reads the bits of a normal number; frexp is its truth, at the ends of
  // every binade, for subnormals, zeros, infinities and NaN.
  auto frexp_e = [](double x) {
    int e;
    std::frexp(x, &e);
    return e;
  };
  std::vector<double> xs = {0.0, -0.0, std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::min(),
                            std::numeric_limits<double>::max(), std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()};
  for (int e = -1074; e <= 1023; ++e)
    for (double m : {1.0, 1.5, 2 - std::ldexp(1.0, -52)}) {
      xs.push_back(std::ldexp(m, e));
      xs.push_back(-std::ldexp(m, e));
    }
  for (double x : xs) EXPECT_EQ(ScalarTraits<double>::exponent(x), frexp_e(x)) << x;
}

// ---------------------------------------------------------------------------------------
// Precision strings

TEST(Precision, ParsesAndRejects) {
  EXPECT_EQ(parse_precision("precision", "double").kind, Precision::Kind::double_);
  EXPECT_EQ(parse_precision("precision", "double").bits, 53);
  EXPECT_EQ(parse_precision("precision", "long").bits, 64);
  EXPECT_EQ(parse_precision("precision", "quad").bits, 113);
  const Precision m = parse_precision("precision", "mpfr:256");
  EXPECT_EQ(m.kind, Precision::Kind::mpfr);
  EXPECT_EQ(m.bits, 256);
  const Precision i = parse_precision("precision", "interval:128");
  EXPECT_TRUE(i.is_interval());
  EXPECT_EQ(i.bits, 128);
  for (const char* bad : {"float", "mpfr:", "mpfr:8", "mpfr:abc", "mpfr:1e3", "mpfr:-64",
                          "interval:2000000", "mpfr:64.5", "Double"}) {
    SCOPED_TRACE(bad);
    try {
      parse_precision("--precision", bad);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field, "--precision");
    }
  }
  // with_scalar dispatches to the named type.
  EXPECT_EQ(with_scalar(m, [](auto tag) { using T = typename decltype(tag)::type; return std::string(ScalarTraits<T>::family); }), "mpfr");
  EXPECT_EQ(with_scalar(i, [](auto tag) { using T = typename decltype(tag)::type; return std::string(ScalarTraits<T>::family); }), "interval");
  EXPECT_EQ(with_scalar(parse_precision("p", "quad"), [](auto tag) { using T = typename decltype(tag)::type; return std::string(ScalarTraits<T>::family); }), "quad");
}

}  // namespace
}  // namespace bouncer
