// Randomized soundness of both interval types (DoubleInterval and Mpfi at 53 bits) at the
// ends of the double range and among the subnormals, against MPFR at high precision.
//
// Operands: doubles at and just below DBL_MAX, in [2^1022, 2^1024) and [2^995, 2^1024),
// around 2^1022 and 2^-1022 (DBL_MIN), subnormals (random and a few denorm_min), around
// 2^-960, powers of two over the whole range, any normal double, moderate numbers and zeros,
// with random signs; the second operand is now and then -x, x or -x moved by a few ulps
// (exact and near cancellations). Intervals are thin three times in four, else wide.
//
// Truth: for + - * the exact result of the corner operands in MPFR at 2200 bits (any sum,
// difference or product of two doubles is exact there: 2^1024 down to 2^-1074 spans 2098
// bits; the test asserts MPFR's ternary value 0); for / and sqrt the results rounded down
// and up at 2200 bits, for exp and log at 256 bits. A directed bracket at any precision
// >= 53 decides both checks exactly: every double (subnormals included) is a 53-bit MPFR
// number, so no double lies strictly between the bracket and the exact value, and
// RD_double(RNDD_p(x)) = RD_double(x).
//
// Checks, for every case: the result is not NaN and not inverted, and encloses the exact
// result; DoubleInterval's ends equal the tightest doubles (MPFR's value rounded down /
// up to double by mpfr_get_d: RNDD / RNDU at 53 bits with the double's exponent range,
// +-inf beyond it), as its header claims for + - * / sqrt exp log; Mpfi's ends equal MPFR's
// RNDD / RNDU at 53 bits (its own exponent range, so no overflow to infinity). Divisors
// holding 0 and roots and logs of negative numbers take the types' documented answers.
// The fixed-seed run must meet each regime (the TwoSum intermediate overflow of issue 21,
// subnormal results, overflowing results) a minimum number of times, so that a changed
// generator cannot silently stop covering them. BOUNCER_TEST_SEED=N runs another seed;
// every failure names the seed and the case.
#include <gtest/gtest.h>
#include <mpfi.h>
#include <mpfr.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "bouncer/scalar/traits.hpp"

namespace bouncer {
namespace {

using D = DoubleInterval;
constexpr unsigned long kDefaultSeed = 20261125;
constexpr mpfr_prec_t kExactBits = 2200;
constexpr mpfr_prec_t kFunctionBits = 256;

unsigned long seed() {
  const char* s = std::getenv("BOUNCER_TEST_SEED");
  return s ? std::strtoul(s, nullptr, 10) : kDefaultSeed;
}

std::string hex(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%a", x);
  return buf;
}
std::string hex(const D& x) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%a, %a]", x.lower(), x.upper());
  return buf;
}
std::string text(mpfr_srcptr x) {
  char buf[80];
  mpfr_snprintf(buf, sizeof buf, "%.20Rg", x);
  return buf;
}
std::string text(const Mpfi& x) {
  char buf[160];
  mpfr_snprintf(buf, sizeof buf, "[%.20Rg, %.20Rg]", &x.get()->left, &x.get()->right);
  return buf;
}

// ---------------------------------------------------------------------------------------
// Operands.

constexpr std::uint64_t kMaxBits = 0x7FEFFFFFFFFFFFFFULL;  // DBL_MAX
constexpr std::uint64_t kMantissa = (1ULL << 52) - 1;
constexpr std::uint64_t exponent_bits(int e) { return static_cast<std::uint64_t>(e + 1023) << 52; }  // normal 2^e

double extreme_double(std::mt19937_64& rng) {
  const std::uint64_t sign = (rng() & 1) << 63;
  const std::uint64_t mant = rng() & kMantissa;
  std::uint64_t mag = 0;
  switch (rng() % 13) {
    case 0: mag = kMaxBits - rng() % 4; break;                                        // DBL_MAX and just below
    case 1: mag = kMaxBits - rng() % (1ULL << 20); break;
    case 2: mag = exponent_bits(1022 + static_cast<int>(rng() % 2)) | mant; break;    // [2^1022, 2^1024)
    case 3: mag = exponent_bits(1022) + rng() % 16 - 8; break;                        // around 2^1022
    case 4: mag = exponent_bits(995 + static_cast<int>(rng() % 29)) | mant; break;    // [2^995, 2^1024)
    case 5: mag = exponent_bits(-1022) + rng() % 16 - 8; break;                       // around DBL_MIN
    case 6: mag = 1 + rng() % kMantissa; break;                                       // subnormal
    case 7: mag = 1 + rng() % 16; break;                                              // a few denorm_min
    case 8: mag = exponent_bits(-1022 + static_cast<int>(rng() % 140)) | mant; break; // [2^-1022, 2^-882)
    case 9: {                                                                         // 2^e, e in [-1074, 1023]
      const int e = -1074 + static_cast<int>(rng() % 2098);
      mag = e < -1022 ? 1ULL << (e + 1074) : exponent_bits(e);
      break;
    }
    case 10: mag = (static_cast<std::uint64_t>(1 + rng() % 2046) << 52) | mant; break;  // any normal
    case 11: mag = exponent_bits(-60 + static_cast<int>(rng() % 121)) | mant; break;    // moderate
    default: mag = 0; break;                                                           // +-0
  }
  return std::bit_cast<double>(sign | mag);
}

// x moved by k ulps away from or towards 0 (staying finite and of the same sign).
double nudge(double x, std::int64_t k) {
  const auto b = std::bit_cast<std::uint64_t>(x);
  const std::uint64_t mag = b & ~(1ULL << 63);
  const std::int64_t m = static_cast<std::int64_t>(mag) + k;
  if (m < 0 || m > static_cast<std::int64_t>(kMaxBits)) return x;
  return std::bit_cast<double>((b & (1ULL << 63)) | static_cast<std::uint64_t>(m));
}

// A second operand: now and then tied to the first (cancellations), else independent.
double partner(double x, std::mt19937_64& rng) {
  switch (rng() % 8) {
    case 0: return -x;
    case 1: return x;
    case 2: return -nudge(x, static_cast<std::int64_t>(rng() % 9) - 4);
    default: return extreme_double(rng);
  }
}

struct Pair {
  double lo, hi;
};
Pair make_interval(double x, std::mt19937_64& rng) {
  if (rng() % 4 != 0) return {x, x};
  const double y = rng() % 2 ? nudge(x, static_cast<std::int64_t>(rng() % 64)) : extreme_double(rng);
  return {std::min(x, y), std::max(x, y)};
}

D to_d(const Pair& p) { return D(p.lo, p.hi); }
Mpfi to_mpfi(const Pair& p) {
  Mpfr lo(53), hi(53);
  mpfr_set_d(lo.get(), p.lo, MPFR_RNDN);  // exact
  mpfr_set_d(hi.get(), p.hi, MPFR_RNDN);
  return Mpfi(lo, hi);
}

// ---------------------------------------------------------------------------------------
// Truth: [lo, hi] in MPFR bracketing the exact range of the operation over the operands.

struct Bracket {
  mpfr_t lo, hi, t;
  explicit Bracket(mpfr_prec_t bits) { mpfr_inits2(bits, lo, hi, t, static_cast<mpfr_ptr>(nullptr)); }
  ~Bracket() { mpfr_clears(lo, hi, t, static_cast<mpfr_ptr>(nullptr)); }
  Bracket(const Bracket&) = delete;
  Bracket& operator=(const Bracket&) = delete;
};

enum class Op { add, sub, mul, div, sqrt, exp, log };
const char* name(Op op) {
  switch (op) {
    case Op::add: return "+";
    case Op::sub: return "-";
    case Op::mul: return "*";
    case Op::div: return "/";
    case Op::sqrt: return "sqrt";
    case Op::exp: return "exp";
    default: return "log";
  }
}

// Exact x op y (+ - *) at kExactBits; asserts exactness.
void exact2(mpfr_ptr r, Op op, double x, double y) {
  mpfr_t a, b;
  mpfr_inits2(53, a, b, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_d(a, x, MPFR_RNDN);
  mpfr_set_d(b, y, MPFR_RNDN);
  const int inexact = op == Op::add ? mpfr_add(r, a, b, MPFR_RNDN) : op == Op::sub ? mpfr_sub(r, a, b, MPFR_RNDN) : mpfr_mul(r, a, b, MPFR_RNDN);
  mpfr_clears(a, b, static_cast<mpfr_ptr>(nullptr));
  ASSERT_EQ(inexact, 0) << "the 2200-bit result must be exact";
}

// The bracket of a binary operation over the corners of X and Y (+ - * are monotone in each
// argument and * / bilinear on sign-definite boxes: the extremes lie at corners).
void bracket2(Bracket& b, Op op, const Pair& X, const Pair& Y) {
  const double xs[2] = {X.lo, X.hi}, ys[2] = {Y.lo, Y.hi};
  bool first = true;
  for (double x : xs)
    for (double y : ys) {
      for (int dir = 0; dir < 2; ++dir) {
        const mpfr_rnd_t rnd = dir == 0 ? MPFR_RNDD : MPFR_RNDU;
        if (op == Op::div) {
          mpfr_t a, c;
          mpfr_inits2(53, a, c, static_cast<mpfr_ptr>(nullptr));
          mpfr_set_d(a, x, MPFR_RNDN);
          mpfr_set_d(c, y, MPFR_RNDN);
          mpfr_div(b.t, a, c, rnd);
          mpfr_clears(a, c, static_cast<mpfr_ptr>(nullptr));
        } else {
          exact2(b.t, op, x, y);
        }
        if (dir == 0 && (first || mpfr_less_p(b.t, b.lo))) mpfr_set(b.lo, b.t, MPFR_RNDN);
        if (dir == 1 && (first || mpfr_greater_p(b.t, b.hi))) mpfr_set(b.hi, b.t, MPFR_RNDN);
      }
      first = false;
    }
}

// The bracket of an increasing function over X.
void bracket1(Bracket& b, Op op, const Pair& X) {
  for (int dir = 0; dir < 2; ++dir) {
    const mpfr_rnd_t rnd = dir == 0 ? MPFR_RNDD : MPFR_RNDU;
    mpfr_ptr r = dir == 0 ? b.lo : b.hi;
    mpfr_set_d(b.t, dir == 0 ? X.lo : X.hi, MPFR_RNDN);
    if (op == Op::sqrt) mpfr_sqrt(r, b.t, rnd);
    else if (op == Op::exp) mpfr_exp(r, b.t, rnd);
    else mpfr_log(r, b.t, rnd);
  }
}

// ---------------------------------------------------------------------------------------
// Checks.

struct Coverage {
  long cases = 0;
  long two_sum_overflow = 0;  // TwoSum's s - a overflows while s is finite (issue 21)
  long subnormal_result = 0;  // an end of the exact result below DBL_MIN, not 0
  long overflow_result = 0;   // an end of the exact result beyond DBL_MAX
  long cancellation = 0;      // an exact zero end from nonzero operands
};

void note(Coverage& cov, const Bracket& b) {
  for (mpfr_srcptr e : {static_cast<mpfr_srcptr>(b.lo), static_cast<mpfr_srcptr>(b.hi)}) {
    if (mpfr_regular_p(e) && mpfr_get_exp(e) <= -1022) ++cov.subnormal_result;  // 0 < |e| < 2^-1022
    if (mpfr_number_p(e) && mpfr_cmp_d(e, DBL_MAX) > 0) ++cov.overflow_result;
    if (mpfr_number_p(e) && mpfr_cmp_d(e, -DBL_MAX) < 0) ++cov.overflow_result;
  }
}

// DoubleInterval: no NaN, encloses [lo, hi], and its ends are the tightest doubles.
::testing::AssertionResult double_ok(const D& r, const Bracket& b) {
  if (r.has_nan()) return ::testing::AssertionFailure() << "NaN result " << hex(r);
  if (!(r.lower() <= r.upper())) return ::testing::AssertionFailure() << "inverted result " << hex(r);
  if (mpfr_cmp_d(b.lo, r.lower()) < 0 || mpfr_cmp_d(b.hi, r.upper()) > 0)
    return ::testing::AssertionFailure() << "UNSOUND: " << hex(r) << " misses [" << text(b.lo) << ", " << text(b.hi) << "]";
  const double down = mpfr_get_d(b.lo, MPFR_RNDD), up = mpfr_get_d(b.hi, MPFR_RNDU);
  if (r.lower() != down || r.upper() != up)
    return ::testing::AssertionFailure() << "not tight: " << hex(r) << ", the tightest is [" << hex(down) << ", " << hex(up) << "]";
  return ::testing::AssertionSuccess();
}

// Mpfi at 53 bits: no NaN, not inverted, encloses [lo, hi], ends = RNDD / RNDU at 53 bits.
::testing::AssertionResult mpfi_ok(const Mpfi& r, const Bracket& b) {
  if (r.has_nan()) return ::testing::AssertionFailure() << "NaN result " << text(r);
  if (mpfr_greater_p(&r.get()->left, &r.get()->right)) return ::testing::AssertionFailure() << "inverted result " << text(r);
  if (mpfr_greater_p(&r.get()->left, b.lo) || mpfr_less_p(&r.get()->right, b.hi))
    return ::testing::AssertionFailure() << "UNSOUND: " << text(r) << " misses [" << text(b.lo) << ", " << text(b.hi) << "]";
  mpfr_t down, up;
  mpfr_inits2(53, down, up, static_cast<mpfr_ptr>(nullptr));
  mpfr_set(down, b.lo, MPFR_RNDD);
  mpfr_set(up, b.hi, MPFR_RNDU);
  const bool tight = mpfr_equal_p(down, &r.get()->left) && mpfr_equal_p(up, &r.get()->right);
  mpfr_clears(down, up, static_cast<mpfr_ptr>(nullptr));
  if (!tight) return ::testing::AssertionFailure() << "not tight at 53 bits: " << text(r);
  return ::testing::AssertionSuccess();
}

std::string where(unsigned long s, long i, Op op, const Pair& X, const Pair* Y) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "seed %lu case %ld: %s [%a, %a]", s, i, name(op), X.lo, X.hi);
  std::string w = buf;
  if (Y) {
    std::snprintf(buf, sizeof buf, " [%a, %a]", Y->lo, Y->hi);
    w += buf;
  }
  return w;
}

bool two_sum_overflows(double a, double b) {
  const double s = a + b;
  return std::isfinite(s) && !std::isfinite(s - a);
}

// Runs `n` random cases of each binary operation in `ops`.
void run_binary(std::initializer_list<Op> ops, long n, Coverage& cov) {
  const unsigned long s = seed();
  std::mt19937_64 rng(s);
  Bracket b(kExactBits);
  for (long i = 0; i < n; ++i) {
    for (Op op : ops) {
      const double x = extreme_double(rng), y = partner(x, rng);
      const Pair X = make_interval(x, rng), Y = make_interval(y, rng);
      ++cov.cases;
      const D dx = to_d(X), dy = to_d(Y);
      const Mpfi mx = to_mpfi(X), my = to_mpfi(Y);
      if (op == Op::div && Y.lo <= 0 && Y.hi >= 0) {
        // A divisor holding 0: no finite enclosure (DoubleInterval: NaN; MPFI: unbounded or NaN).
        EXPECT_TRUE((dx / dy).has_nan()) << where(s, i, op, X, &Y);
        EXPECT_FALSE(ScalarTraits<Mpfi>::is_finite(mx / my)) << where(s, i, op, X, &Y);
        continue;
      }
      bracket2(b, op, X, Y);
      if (::testing::Test::HasFatalFailure()) return;
      note(cov, b);
      if (op == Op::add && (two_sum_overflows(X.lo, Y.lo) || two_sum_overflows(X.hi, Y.hi))) ++cov.two_sum_overflow;
      if (op == Op::sub && (two_sum_overflows(X.lo, -Y.hi) || two_sum_overflows(X.hi, -Y.lo))) ++cov.two_sum_overflow;
      if ((op == Op::add || op == Op::sub) && (mpfr_zero_p(b.lo) || mpfr_zero_p(b.hi)) && x != 0) ++cov.cancellation;
      const D rd = op == Op::add ? dx + dy : op == Op::sub ? dx - dy : op == Op::mul ? dx * dy : dx / dy;
      const Mpfi rm = op == Op::add ? mx + my : op == Op::sub ? mx - my : op == Op::mul ? mx * my : mx / my;
      EXPECT_TRUE(double_ok(rd, b)) << "interval:double " << where(s, i, op, X, &Y);
      EXPECT_TRUE(mpfi_ok(rm, b)) << "mpfi:53 " << where(s, i, op, X, &Y);
      if (::testing::Test::HasFailure()) return;
    }
  }
}

void run_unary(Op op, long n, Coverage& cov) {
  const unsigned long s = seed() + static_cast<unsigned long>(op);
  std::mt19937_64 rng(s);
  Bracket b(op == Op::sqrt ? kExactBits : kFunctionBits);
  for (long i = 0; i < n; ++i) {
    double x = extreme_double(rng);
    // exp: half the arguments scaled to 1 <= |x| < 2^12, where exp overflows, underflows
    // and has subnormal values.
    if (op == Op::exp && x != 0 && rng() % 2) x = std::ldexp(x, -std::ilogb(x) + static_cast<int>(rng() % 12));
    Pair X = make_interval(x, rng);
    // sqrt, log: seven in eight made non-negative (the ends' magnitudes, sorted).
    if (op != Op::exp && rng() % 8 != 0) {
      const double a = std::fabs(X.lo), c = std::fabs(X.hi);
      X = {std::min(a, c), std::max(a, c)};
    }
    ++cov.cases;
    const D dx = to_d(X);
    const Mpfi mx = to_mpfi(X);
    const D rd = op == Op::sqrt ? sqrt(dx) : op == Op::exp ? exp(dx) : log(dx);
    const Mpfi rm = op == Op::sqrt ? sqrt(mx) : op == Op::exp ? exp(mx) : log(mx);
    if (op != Op::exp && X.lo < 0) {
      // Outside the domain. sqrt: DoubleInterval roots the non-negative part (IEEE 1788),
      // [0, RU(sqrt(hi))], NaN when nothing is left; mpfi_sqrt gives NaN. log: NaN for both.
      EXPECT_TRUE(rm.has_nan()) << "mpfi:53 " << where(s, i, op, X, nullptr) << ": " << text(rm);
      if (op == Op::log || X.hi < 0) {
        EXPECT_TRUE(rd.has_nan()) << "interval:double " << where(s, i, op, X, nullptr) << ": " << hex(rd);
      } else {
        bracket1(b, op, {0.0, X.hi});
        EXPECT_TRUE(double_ok(rd, b)) << "interval:double " << where(s, i, op, X, nullptr);
      }
      if (::testing::Test::HasFailure()) return;
      continue;
    }
    bracket1(b, op, X);
    note(cov, b);
    EXPECT_TRUE(double_ok(rd, b)) << "interval:double " << where(s, i, op, X, nullptr);
    EXPECT_TRUE(mpfi_ok(rm, b)) << "mpfi:53 " << where(s, i, op, X, nullptr);
    if (::testing::Test::HasFailure()) return;
  }
}

// ---------------------------------------------------------------------------------------

// Issue 21: in TwoSum, s - a overflowed to -inf, the error term became NaN, and the rounding
// step read NaN as "exact": the sum came back as the point RN(a + b), half an ulp off.
TEST(IntervalExtremes, TopOfRangeSumIsEnclosed) {
  const double a = 0x1.0000000000003p+1022, b = -DBL_MAX;
  ASSERT_TRUE(two_sum_overflows(a, b)) << "the case must exercise the overflow";
  Bracket br(kExactBits);
  bracket2(br, Op::add, {a, a}, {b, b});
  EXPECT_NE(mpfr_cmp_d(br.lo, a + b), 0) << "the exact sum is not a double";
  const D sum = D(a, a) + D(b, b);
  EXPECT_TRUE(double_ok(sum, br)) << hex(sum);
  EXPECT_LT(sum.lower(), sum.upper()) << "an inexact sum cannot be a point";
  const D diff = D(a, a) - D(-b, -b);
  EXPECT_TRUE(double_ok(diff, br)) << hex(diff);
  const D swapped = D(b, b) + D(a, a);
  EXPECT_TRUE(double_ok(swapped, br)) << hex(swapped);
  Mpfr ma(53), mb(53);
  mpfr_set_d(ma.get(), a, MPFR_RNDN);
  mpfr_set_d(mb.get(), b, MPFR_RNDN);
  EXPECT_TRUE(mpfi_ok(Mpfi(ma, ma) + Mpfi(mb, mb), br));
}

TEST(IntervalExtremes, AddSubtract) {
  Coverage cov;
  run_binary({Op::add, Op::sub}, 150000, cov);
  std::printf("add/sub: %ld cases, %ld TwoSum intermediate overflows, %ld subnormal and %ld overflowing ends, %ld exact cancellations\n",
              cov.cases, cov.two_sum_overflow, cov.subnormal_result, cov.overflow_result, cov.cancellation);
  if (seed() == kDefaultSeed) {
    EXPECT_GE(cov.two_sum_overflow, 20) << "the generator must meet issue 21's overflow";
    EXPECT_GE(cov.subnormal_result, 1000);
    EXPECT_GE(cov.overflow_result, 1000);
    EXPECT_GE(cov.cancellation, 1000);
  }
}

TEST(IntervalExtremes, Multiply) {
  Coverage cov;
  run_binary({Op::mul}, 100000, cov);
  std::printf("mul: %ld cases, %ld subnormal and %ld overflowing ends\n", cov.cases, cov.subnormal_result, cov.overflow_result);
  if (seed() == kDefaultSeed) {
    EXPECT_GE(cov.subnormal_result, 1000);
    EXPECT_GE(cov.overflow_result, 1000);
  }
}

TEST(IntervalExtremes, Divide) {
  Coverage cov;
  run_binary({Op::div}, 60000, cov);
  std::printf("div: %ld cases, %ld subnormal and %ld overflowing ends\n", cov.cases, cov.subnormal_result, cov.overflow_result);
  if (seed() == kDefaultSeed) {
    EXPECT_GE(cov.subnormal_result, 1000);
    EXPECT_GE(cov.overflow_result, 1000);
  }
}

TEST(IntervalExtremes, SquareRoot) {
  Coverage cov;
  run_unary(Op::sqrt, 40000, cov);
  std::printf("sqrt: %ld cases\n", cov.cases);
}

TEST(IntervalExtremes, ExpAndLog) {
  Coverage cov;
  run_unary(Op::exp, 10000, cov);
  run_unary(Op::log, 10000, cov);
  std::printf("exp/log: %ld cases, %ld subnormal and %ld overflowing ends\n", cov.cases, cov.subnormal_result, cov.overflow_result);
  if (seed() == kDefaultSeed) {
    EXPECT_GE(cov.subnormal_result, 50);
    EXPECT_GE(cov.overflow_result, 50);
  }
}

}  // namespace
}  // namespace bouncer
