// DoubleInterval: an interval of two IEEE doubles, rounded outward: the fast certified
// scalar (--precision interval:double), the first tier of every escalation schedule.
//
// Why it is rigorous (the rounding argument). The program runs in the default rounding mode
// (round to nearest, ties to even; it never changes it) with SSE2 doubles and
// -ffp-contract=off, so each +, -, *, / and sqrt below is ONE correctly rounded IEEE 754
// operation: c = RN(r), the double nearest the exact real result r. For finite c and r the
// directed roundings follow from the sign of the error r - c alone: RD(r) is c when r >= c
// and the double below c otherwise (r, nearer to c than to it, lies between the two), RU(r)
// likewise.
// The sign is found without rounding by error-free transformations (scalar/error_free.hpp;
// std::fma is IEEE fusedMultiplyAdd: a b + z rounded once, no intermediate rounding or
// overflow), each exact only in a range that the fast path tests before using its result:
//   a + b:  TwoSum, e = (a + b) - c exactly for finite a, b unless one of its intermediates
//           overflows (underflow cannot disturb it: a sum of doubles in the subnormal range is
//           exact). It uses + and - only, so an intermediate overflow reaches e as +-inf or
//           NaN, never as a finite value; an infinite or NaN c makes e NaN. Test: e finite.
//           (Issue 21: for a = 0x1.0000000000003p+1022, b = -DBL_MAX, s - a overflowed, e was
//           NaN, and the rounding step read NaN as "exact": the point RN(a + b) came back.)
//   a * b:  l = fma(a, b, -c) = a b - c exactly when c is finite and |c| >= 2^-960: a b - c is
//           a multiple of ulp(a) ulp(b) >= 2^(ea + eb - 104) >= 2^-1066 (ea, eb the exponents,
//           ea + eb >= -962 there) of magnitude <= ulp(c)/2, hence a double. Test: that range.
//   a / b:  r = fma(-c, b, a) = RN(a - c b). For finite a, b, c with |a| >= 2^-960, a - c b is
//           a multiple of ulp(a) or of ulp(c) ulp(b) >= 2^(ec + eb - 104) >= 2^(ea - 105)
//           (ec >= ea - eb - 1 for c != 0; c = 0 leaves r = a), so it is 0 or at least
//           2^-1074 in magnitude, and RN keeps its sign (no overflow either:
//           |a - c b| <= |b| ulp(c)/2, about |a| 2^-53).
//           sign(a/b - c) = sign(a - c b) sign(b). Test: |a| >= 2^-960 and r finite (a
//           non-finite r means an infinite or NaN operand or c).
//   sqrt x: r = fma(-c, c, x) = RN(x - c^2); for finite x >= 2^-960, x - c^2 is a multiple of
//           ulp(x) or ulp(c)^2 >= 2^-1066 and keeps its sign. Test: x >= 2^-960, r finite.
// Everything else takes an out-of-line slow path (rare operands; the fast paths' tests cost
// one comparison or finiteness check on values already computed):
//   * c = +-inf from finite operands: r lies beyond DBL_MAX, so the near bound is +-DBL_MAX
//     and the far one +-inf (one double outward from c): exactly RD / RU. The next operation
//     then meets is_finite = false and the step is undecided, never guessed.
//   * infinite operands (the ends of unbounded intervals): the limits, x +- inf = +-inf,
//     x / +-inf = 0, sqrt(inf) = inf, exact; 0 * inf and inf - inf are NaN (invalid).
//   * TwoSum's intermediate overflow with a finite c: FastTwoSum with the larger magnitude
//     first, whose s - a = b - e cannot overflow: exact.
//   * tiny products, dividends and radicands (below 2^-960, where the error term may
//     underflow): the operands are scaled by powers of two (frexp / ldexp, exact) so that
//     the same FMA sign test runs on numbers far from underflow (each slow path below gives
//     its bounds).
// No NaN or inexact error term ever reaches the rounding step. So for finite operands each
// end is exactly the directed rounding of the exact result to double: MPFR's RNDD / RNDU at
// 53 bits with the double's exponent range (subnormals included; +-DBL_MAX or +-inf on
// overflow). Exact operations stay thin, and no rounding mode is ever switched (no
// -frounding-math, no fesetround, nothing the compiler could reorder).
// Products and quotients take the min / max over the corner results, each rounded in its
// direction.
//
// exp and log are not correctly rounded in libm. Each end is MPFR's directed result at 53 bits
// (MPFR_RNDD for the lower end, MPFR_RNDU for the upper) converted to double in the same
// direction, bit for bit: rigorous and tightest. scalar/interval_elementary.hpp computes it in
// double arithmetic (a table, a short Taylor polynomial and a written a-priori bound of every
// rounding and truncation error, then two directed sums that must agree), and calls MPFR only
// when they disagree or the argument lies outside the proven range (its opening comment).
//
// Invalid intervals. An interval with a NaN end is invalid (has_nan; every caller treats it as
// undecided: ScalarTraits gives Truth::invalid and is_finite = false). Every operation with an
// invalid operand gives an invalid result, and these give one from valid operands: a divisor
// holding 0, a corner product 0 * inf (an unbounded operand times one with an end at 0), the
// square root of an interval entirely below 0, log of an interval reaching below 0, and an
// empty intersection (intersect of disjoint intervals: there is no empty interval value).
// sqrt of an interval reaching below 0 roots its non-negative part, [0, RU(sqrt(hi))] (the
// IEEE 1788 sqrt); the MPFI wrapper (scalar/mpfi.hpp) gives NaN there instead (mpfi_sqrt).
//
// Decimal inputs are enclosed by MPFR's directed conversion (mpfr_strtofr at 53 bits, RNDD
// and RNDU): the tightest double interval containing the exact decimal.
//
// The tests: tests/test_interval_double.cpp checks every operation against MPFR at 512 bits
// on random and adversarial operands (the exact result inside, the ends bit for bit MPFR's
// directed roundings), and the whole step against ImpactMap<Mpfr> at 512 bits in every
// model; tests/test_interval_extremes.cpp checks enclosure and tightness near +-DBL_MAX,
// 2^+-1022 and among the subnormals against MPFR at 2200 bits; tests/test_itf1788.cpp runs
// the IEEE 1788 test suite ITF1788 (tightest expected results) on both interval types.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "bouncer/scalar/error_free.hpp"

namespace bouncer {

namespace interval_double_detail {

// The next double above / below x (x itself for +inf / -inf, NaN for NaN).
inline double next_up(double x) {
  if (!(x < std::numeric_limits<double>::infinity())) return x;  // +inf or NaN
  if (x == 0) return std::numeric_limits<double>::denorm_min();
  const auto b = std::bit_cast<std::uint64_t>(x);
  return std::bit_cast<double>(x > 0 ? b + 1 : b - 1);
}
inline double next_down(double x) { return -next_up(-x); }

// Both directed roundings of one operation.
struct Rounded {
  double down, up;
};

// Where the error terms below are exact (the rounding argument at the top of this file):
// products and radicands of magnitude >= kSmall, dividends >= kSmall. Below, a scaled
// slow path.
constexpr double kSmall = 0x1p-960;

// Each end of an interval operation is one operation rounded in one direction: c = RN(r), and
// the exact error's sign (error-free transformations) says whether r lies above or below c.
// Up = false: rounded down; true: rounded up. (One direction per call: computing both ends
// of every operation cost the Lohner step a fifth of its time.)
//
// Branch-free: the error's sign is as good as random, so in the Lohner step's dual arithmetic a
// branch on it is mispredicted about half the time. For a finite c, the next double above is
// an integer step of its bit pattern: +1 for c >= +0 (+0 -> the smallest subnormal), -1 for
// c < 0 (-denorm_min -> -0, which equals 0); c + 0.0 turns -0 into +0 first (exact, round to
// nearest). Down is Up mirrored: next_down(c) = -next_up(-c). The callers pass only finite c
// and a finite, exact error term (anything else takes a slow path first: a NaN error would
// read as "exact").
// The trade, measured (bench_certify --quick, with Dual's constant operands): the Lohner step
// went from 62x to 39x a double step, the plain interval step from 6.5x to 9.3x (there the
// branch was mostly predicted, and the detour through integer registers lengthens a chain of
// dependent operations). Certified runs take Lohner steps, so the Lohner step decides.
template <bool Up>
inline double round_to(double c, double sign_of_error) {
  constexpr std::uint64_t kSign = Up ? 0 : 0x8000000000000000ULL;  // down: step -c up, negate back
  const auto b = std::bit_cast<std::uint64_t>((Up ? c : -c) + 0.0);
  const std::uint64_t moved = (b + 1 - ((b >> 63) << 1)) ^ kSign;
  const bool step = Up ? sign_of_error > 0 : sign_of_error < 0;
  const std::uint64_t mask = 0 - static_cast<std::uint64_t>(step);
  return std::bit_cast<double>((moved & mask) | (std::bit_cast<std::uint64_t>(c) & ~mask));
}
// An infinite c: the exact result lies beyond DBL_MAX (an overflow) or is itself infinite (an
// infinite operand); one double outward gives +-DBL_MAX as the near bound, +-inf as the far
// one. NaN stays NaN.
template <bool Up>
inline double outward(double c) {
  if (std::isnan(c)) return c;
  return Up ? next_up(c) : next_down(c);
}

// The slow paths (rare operands: kept out of line so the fast paths stay small).
template <bool Up>
[[gnu::noinline, gnu::cold]] double add_slow(double a, double b, double c) {
  if (!std::isfinite(c)) return outward<Up>(c);
  // c finite, but an intermediate of TwoSum overflowed (s - a near the top of the range:
  // issue 21). FastTwoSum with the larger magnitude first computes s - a = b - e exactly,
  // and |b - e| <= |b| + ulp(c)/2 stays below the overflow threshold (|b| = DBL_MAX would
  // need |a| = DBL_MAX, whose sum with b overflows or cancels exactly): exact.
  double s, e;
  if (std::fabs(a) >= std::fabs(b)) error_free::fast_two_sum(a, b, s, e);
  else error_free::fast_two_sum(b, a, s, e);
  return round_to<Up>(c, e);
}
template <bool Up>
[[gnu::noinline, gnu::cold]] double mul_slow(double a, double b, double c) {
  if (!std::isfinite(c)) return outward<Up>(c);
  // 0 < |c| < kSmall or c = 0 from nonzero a, b (the error term may underflow). With
  // a = ma 2^ea, b = mb 2^eb (frexp: 1/2 <= |ma|, |mb| < 1, exact, subnormals included),
  // a b - c = 2^(ea + eb) (ma mb - cs), cs = c 2^-(ea + eb) exact (|cs| <= 1 and, c being a
  // multiple of 2^-1074 with -1075 < ea + eb <= -958 when c != 0, cs is 0 or a multiple of
  // 2^-116), and ma mb - cs, a multiple of 2^-116, is 0 or far from underflow: its RN has
  // its sign.
  int ea = 0, eb = 0;
  const double ma = std::frexp(a, &ea), mb = std::frexp(b, &eb);
  return round_to<Up>(c, std::fma(ma, mb, -std::ldexp(c, -(ea + eb))));
}
template <bool Up>
[[gnu::noinline, gnu::cold]] double div_slow(double a, double b, double c) {
  if (std::isnan(c)) return c;
  if (std::isinf(b)) return c;  // finite / +-inf = +-0: the limit at an unbounded divisor's end
  if (!std::isfinite(c)) return outward<Up>(c);
  // 0 < |a| < kSmall (the remainder may underflow). With a = ma 2^ea, b = mb 2^eb as above,
  // a - c b = 2^ea (ma - cs mb), cs = c 2^(eb - ea) exact (c near a / b, so |cs| < 4; a
  // subnormal c is scaled up), and ma - cs mb, a multiple of 2^-108, is 0 or far from
  // underflow. sign(a / b - c) = sign(a - c b) sign(b).
  int ea = 0, eb = 0;
  const double ma = std::frexp(a, &ea), mb = std::frexp(b, &eb);
  const double r = std::fma(-std::ldexp(c, eb - ea), mb, ma);
  return round_to<Up>(c, b > 0 ? r : -r);
}
template <bool Up>
[[gnu::noinline, gnu::cold]] double root_slow(double x, double c) {
  if (x == 0 || !std::isfinite(c)) return c;  // sqrt(+-0) = +-0, sqrt(inf) = inf; NaN below 0
  // 0 < x < kSmall: x = m 2^(2k) with 1/2 <= m < 2 (frexp, exponent made even), and
  // x - c^2 = 2^(2k) (m - cs^2) with cs = c 2^-k exact (c = RN(sqrt x) >= 2^-537 is normal,
  // cs near sqrt(m)); m - cs^2, a multiple of 2^-106, is 0 or far from underflow.
  int e = 0;
  double m = std::frexp(x, &e);
  if (e % 2 != 0) {
    m = std::ldexp(m, 1);
    e -= 1;
  }
  const double cs = std::ldexp(c, -e / 2);
  return round_to<Up>(c, std::fma(-cs, cs, m));
}

// The fast paths. Each test below costs one comparison or finiteness check on values already
// computed, and sends everything outside the ranges where the error term is exact to the
// slow path.
template <bool Up>
inline double add_to(double a, double b) {
  double c, e;
  error_free::two_sum(a, b, c, e);
  // e finite: no intermediate of TwoSum overflowed (an overflow makes e +-inf or NaN, and an
  // infinite or NaN c makes e NaN), so c is finite and e = (a + b) - c exactly.
  if (std::isfinite(e)) [[likely]] return round_to<Up>(c, e);
  return add_slow<Up>(a, b, c);
}
template <bool Up>
inline double mul_to(double a, double b) {
  const double c = a * b;
  if (a == 0 || b == 0) return c;  // exact (NaN for 0 * inf: the caller's interval is then invalid)
  // c finite and |c| >= kSmall: l = a b - c exactly (TwoProduct by one FMA).
  if (std::fabs(c) >= kSmall && std::fabs(c) <= std::numeric_limits<double>::max()) [[likely]]
    return round_to<Up>(c, std::fma(a, b, -c));
  return mul_slow<Up>(a, b, c);
}
template <bool Up>
inline double div_to(double a, double b) {
  const double c = a / b;
  if (a == 0 && b != 0) return c;
  // r = RN(a - c b) (one FMA): for finite a, b, c and |a| >= kSmall its sign is that of
  // a - c b. A non-finite r means an infinite or NaN operand or c.
  const double r = std::fma(-c, b, a);
  if (std::fabs(a) >= kSmall && std::isfinite(r)) [[likely]] return round_to<Up>(c, b > 0 ? r : -r);
  return div_slow<Up>(a, b, c);
}
template <bool Up>
inline double root_to(double x) {
  const double c = std::sqrt(x);
  // r = RN(x - c^2) (one FMA): for finite x >= kSmall its sign is that of x - c^2.
  const double r = std::fma(-c, c, x);
  if (x >= kSmall && std::isfinite(r)) [[likely]] return round_to<Up>(c, r);
  return root_slow<Up>(x, c);
}
inline double add_down(double a, double b) { return add_to<false>(a, b); }
inline double add_up(double a, double b) { return add_to<true>(a, b); }
inline double mul_down(double a, double b) { return mul_to<false>(a, b); }
inline double mul_up(double a, double b) { return mul_to<true>(a, b); }
inline double div_down(double a, double b) { return div_to<false>(a, b); }
inline double div_up(double a, double b) { return div_to<true>(a, b); }
// Both ends of one product (the four-corner case of an interval product).
inline Rounded mul(double a, double b) { return {mul_to<false>(a, b), mul_to<true>(a, b)}; }

}  // namespace interval_double_detail

class DoubleInterval {
 public:
  DoubleInterval() = default;  // [0, 0]
  DoubleInterval(double lo, double hi) : lo_(lo), hi_(hi) {}
  // The exact integer n (|n| < 2^53: every long the map uses).
  explicit DoubleInterval(long n) : lo_(static_cast<double>(n)), hi_(static_cast<double>(n)) {}

  double lower() const { return lo_; }
  double upper() const { return hi_; }
  // Midpoint (a point inside, used to centre frames; not itself an enclosure).
  double mid() const {
    const double m = lo_ / 2 + hi_ / 2;
    return std::isfinite(m) ? std::clamp(m, lo_, hi_) : m;
  }
  // Width, rounded up.
  double width() const { return interval_double_detail::next_up(hi_ - lo_); }
  bool contains(double x) const { return lo_ <= x && x <= hi_; }
  bool contains(const DoubleInterval& x) const { return lo_ <= x.lo_ && x.hi_ <= hi_; }
  bool has_nan() const { return std::isnan(lo_) || std::isnan(hi_); }
  bool bounded() const { return std::isfinite(lo_) && std::isfinite(hi_); }

  DoubleInterval& operator+=(const DoubleInterval& o) { return *this = *this + o; }
  DoubleInterval& operator-=(const DoubleInterval& o) { return *this = *this - o; }
  DoubleInterval& operator*=(const DoubleInterval& o) { return *this = *this * o; }
  DoubleInterval& operator/=(const DoubleInterval& o) { return *this = *this / o; }
  DoubleInterval& operator*=(long n) { return *this = *this * n; }
  DoubleInterval& operator/=(long n) { return *this = *this / n; }

  friend DoubleInterval operator+(const DoubleInterval& x, const DoubleInterval& y) {
    return {interval_double_detail::add_down(x.lo_, y.lo_), interval_double_detail::add_up(x.hi_, y.hi_)};
  }
  friend DoubleInterval operator-(const DoubleInterval& x, const DoubleInterval& y) {
    return {interval_double_detail::add_down(x.lo_, -y.hi_), interval_double_detail::add_up(x.hi_, -y.lo_)};
  }
  // Products and quotients by the signs of the ends: which corner gives each end is known
  // from the signs, so two rounded operations suffice (four only for a product of two
  // intervals that both hold 0). NaN ends propagate (has_nan: invalid).
  friend DoubleInterval operator*(const DoubleInterval& x, const DoubleInterval& y) {
    using interval_double_detail::mul;
    using interval_double_detail::mul_down;
    using interval_double_detail::mul_up;
    const double xl = x.lo_, xh = x.hi_, yl = y.lo_, yh = y.hi_;
    if (x.has_nan() || y.has_nan()) return nan_interval();
    if (xl >= 0) {
      if (yl >= 0) return {mul_down(xl, yl), mul_up(xh, yh)};
      if (yh <= 0) return {mul_down(xh, yl), mul_up(xl, yh)};
      return {mul_down(xh, yl), mul_up(xh, yh)};
    }
    if (xh <= 0) {
      if (yl >= 0) return {mul_down(xl, yh), mul_up(xh, yl)};
      if (yh <= 0) return {mul_down(xh, yh), mul_up(xl, yl)};
      return {mul_down(xl, yh), mul_up(xl, yl)};
    }
    if (yl >= 0) return {mul_down(xl, yh), mul_up(xh, yh)};
    if (yh <= 0) return {mul_down(xh, yl), mul_up(xl, yl)};
    return corners(mul(xl, yl), mul(xl, yh), mul(xh, yl), mul(xh, yh));
  }
  friend DoubleInterval operator/(const DoubleInterval& x, const DoubleInterval& y) {
    using interval_double_detail::div_down;
    using interval_double_detail::div_up;
    const double xl = x.lo_, xh = x.hi_, yl = y.lo_, yh = y.hi_;
    if (x.has_nan() || y.has_nan()) return nan_interval();
    // A divisor that may be 0: NaN (as an undefined quotient; the step is then undecided).
    if (yl > 0) {
      if (xl >= 0) return {div_down(xl, yh), div_up(xh, yl)};
      if (xh <= 0) return {div_down(xl, yl), div_up(xh, yh)};
      return {div_down(xl, yl), div_up(xh, yl)};
    }
    if (yh < 0) {
      if (xl >= 0) return {div_down(xh, yh), div_up(xl, yl)};
      if (xh <= 0) return {div_down(xh, yl), div_up(xl, yh)};
      return {div_down(xh, yh), div_up(xl, yh)};
    }
    return nan_interval();
  }
  // Negation and exact-integer conversions are exact: no widening.
  friend DoubleInterval operator-(const DoubleInterval& x) { return {-x.hi_, -x.lo_}; }
  friend DoubleInterval operator+(const DoubleInterval& x, long n) { return x + DoubleInterval(n); }
  friend DoubleInterval operator+(long n, const DoubleInterval& x) { return x + DoubleInterval(n); }
  friend DoubleInterval operator-(const DoubleInterval& x, long n) { return x - DoubleInterval(n); }
  friend DoubleInterval operator-(long n, const DoubleInterval& x) { return DoubleInterval(n) - x; }
  friend DoubleInterval operator*(const DoubleInterval& x, long n) { return x * DoubleInterval(n); }
  friend DoubleInterval operator*(long n, const DoubleInterval& x) { return x * DoubleInterval(n); }
  friend DoubleInterval operator/(const DoubleInterval& x, long n) { return x / DoubleInterval(n); }
  friend DoubleInterval operator/(long n, const DoubleInterval& x) { return DoubleInterval(n) / x; }

  // sqrt of the part of x in [0, inf): [0, RU(sqrt(hi))] when x reaches below 0 (IEEE 1788's
  // sqrt; not mpfi_sqrt, which gives NaN there), NaN when x lies entirely below 0.
  friend DoubleInterval sqrt(const DoubleInterval& x) {
    if (x.hi_ < 0 || x.has_nan()) return nan_interval();
    const double lo = x.lo_ <= 0 ? 0.0 : interval_double_detail::root_to<false>(x.lo_);
    return {std::max(lo, 0.0), interval_double_detail::root_to<true>(x.hi_)};
  }
  friend DoubleInterval exp(const DoubleInterval& x);  // MPFR's directed roundings (interval_elementary)
  // MPFR's directed roundings; NaN for an x reaching below 0, and a lower end 0 gives -inf.
  friend DoubleInterval log(const DoubleInterval& x);
  friend DoubleInterval abs(const DoubleInterval& x) {
    if (x.lo_ >= 0) return x;
    if (x.hi_ <= 0) return -x;
    return {0.0, std::max(-x.lo_, x.hi_)};
  }
  // The hull of two intervals; invalid (NaN) when either is (std::min / std::max would drop
  // a NaN end silently).
  friend DoubleInterval hull(const DoubleInterval& x, const DoubleInterval& y) {
    if (x.has_nan() || y.has_nan()) return nan_interval();
    return {std::min(x.lo_, y.lo_), std::max(x.hi_, y.hi_)};
  }
  // The intersection. Disjoint intervals (possible only when an enclosure is wrong or two
  // enclosures of different values meet) give the NaN interval: there is no empty interval
  // value, and NaN is the one every caller already treats as invalid (an inverted pair would
  // pass has_nan() and bounded() and then be computed with). A NaN operand gives NaN too.
  friend DoubleInterval intersect(const DoubleInterval& x, const DoubleInterval& y) {
    const double lo = std::max(x.lo_, y.lo_), hi = std::min(x.hi_, y.hi_);
    if (!(lo <= hi) || x.has_nan() || y.has_nan()) return nan_interval();
    return {lo, hi};
  }

  static DoubleInterval entire() {
    return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }
  static DoubleInterval nan_interval() {
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  }

 private:
  double lo_ = 0, hi_ = 0;

  // The hull of four corner results, each end rounded in its direction; a NaN corner
  // (0 times inf) makes the interval NaN: invalid, never guessed.
  static DoubleInterval corners(const interval_double_detail::Rounded& a, const interval_double_detail::Rounded& b,
                                const interval_double_detail::Rounded& c, const interval_double_detail::Rounded& d) {
    if (std::isnan(a.down) || std::isnan(b.down) || std::isnan(c.down) || std::isnan(d.down)) return nan_interval();
    return {std::min(std::min(a.down, b.down), std::min(c.down, d.down)), std::max(std::max(a.up, b.up), std::max(c.up, d.up))};
  }
};

DoubleInterval exp(const DoubleInterval& x);
DoubleInterval log(const DoubleInterval& x);

}  // namespace bouncer
