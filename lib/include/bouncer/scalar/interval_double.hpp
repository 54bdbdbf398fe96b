// DoubleInterval: an interval of two IEEE doubles, rounded outward: the fast certified
// scalar (--precision interval:double), the first tier of every escalation schedule.
//
// Why it is rigorous (the rounding argument). The program runs in the default rounding mode
// (round to nearest, ties to even; it never changes it) with SSE2 doubles and
// -ffp-contract=off, so each +, -, *, / and sqrt below is ONE correctly rounded IEEE 754
// operation: c = RN(r), the double nearest the exact real result r. The exact error r - c is
// then found without rounding by the classical error-free transformations:
//   a + b:  Knuth's TwoSum gives e = (a + b) - c exactly (any finite a, b without overflow);
//   a * b:  TwoProduct, e = fma(a, b, -c) (std::fma: IEEE fusedMultiplyAdd, one correctly
//           rounded operation), gives e = a b - c exactly when c does not overflow and e does
//           not underflow;
//   a / b:  c b = h + l exactly (TwoProduct), and (a - h) - l has the sign of a - c b
//           (a - h is exact by Sterbenz's lemma, h being within a factor 2 of a, and
//           rounding never changes a sign), so sign(a/b - c) = sign((a - h) - l) sign(b);
//   sqrt x: likewise with c c = h + l: sign(sqrt(x) - c) = sign((x - h) - l).
// The rounded-down result is c when r >= c and the double below c otherwise; rounded up
// likewise. So each end is exactly MPFR's RNDD / RNDU result at 53 bits (the tests check this
// bit for bit), exact operations stay thin, and no rounding mode is ever switched (no
// -frounding-math, no fesetround, nothing the compiler could reorder).
// Outside the ranges where the transformations are exact (magnitudes near overflow or
// underflow: an operand or result of magnitude >= 2^995, or a product, dividend, quotient or
// root below 2^-960)
// the operation falls back to moving both ends of c one double outward, which is an enclosure
// because |r - c| <= ulp(c)/2 (at overflow c = +-inf and the far bound is +-inf; the next
// operation then meets is_finite = false and the step is undecided, never guessed).
// Products and quotients take the min / max over the four corner results, each rounded in its
// direction.
//
// exp and log are not correctly rounded in libm. They are computed by MPFR at 53 bits with
// directed rounding (MPFR_RNDD for the lower end, MPFR_RNDU for the upper end; MPFR's results
// are correctly rounded in the requested direction, and a 53-bit MPFR number converts to a
// double exactly), which is rigorous and still far cheaper than an MPFI step.
//
// Decimal inputs are enclosed by MPFR's directed conversion (mpfr_strtofr at 53 bits, RNDD
// and RNDU): the tightest double interval containing the exact decimal.
//
// The tests (tests/test_interval_double.cpp) check every operation against MPFR at 512 bits
// on random and adversarial operands (the exact result inside, the ends one ulp from RN), and
// the whole step against ImpactMap<Mpfr> at 512 bits in every model.
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

constexpr double kBig = 0x1p995;     // operands below this: products and quotients far from overflow
constexpr double kSmall = 0x1p-960;  // results above this: the error terms do not underflow

// TwoProduct (scalar/error_free.hpp), exact for |a|, |b| < kBig and |h| > kSmall (or h == 0
// with a or b zero).
using error_free::two_product;

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
// (infinite results take `outward`).
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
// Outside the exact ranges: one double outward (NaN stays NaN).
template <bool Up>
inline double outward(double c) {
  if (std::isnan(c)) return c;
  return Up ? next_up(c) : next_down(c);
}
template <bool Up>
inline double add_to(double a, double b) {
  double c, e;
  error_free::two_sum(a, b, c, e);
  return std::isfinite(c) ? round_to<Up>(c, e) : outward<Up>(c);
}
template <bool Up>
inline double mul_to(double a, double b) {
  const double c = a * b;
  if (a == 0 || b == 0) return c;
  if (!(std::fabs(a) < kBig && std::fabs(b) < kBig && std::fabs(c) > kSmall && std::fabs(c) < kBig)) return outward<Up>(c);
  double h, l;
  two_product(a, b, h, l);
  return round_to<Up>(c, l);
}
template <bool Up>
inline double div_to(double a, double b) {
  const double c = a / b;
  if (a == 0 && b != 0) return c;
  if (!(std::fabs(a) < kBig && std::fabs(b) < kBig && std::fabs(a) > kSmall && std::fabs(c) > kSmall && std::fabs(c) < kBig))
    return outward<Up>(c);
  double h, l;
  two_product(c, b, h, l);
  const double r = (a - h) - l;  // the sign of a - c b
  return round_to<Up>(c, b > 0 ? r : -r);
}
template <bool Up>
inline double root_to(double x) {
  const double c = std::sqrt(x);
  if (x == 0) return c;
  if (!(x < kBig && x > kSmall)) return outward<Up>(c);
  double h, l;
  two_product(c, c, h, l);
  return round_to<Up>(c, (x - h) - l);  // the sign of x - c c
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

  // sqrt of the part of x in [0, inf) (as mpfi_sqrt: negative parts have no real root; an
  // interval entirely below 0 gives NaN).
  friend DoubleInterval sqrt(const DoubleInterval& x) {
    if (x.hi_ < 0 || x.has_nan()) return nan_interval();
    const double lo = x.lo_ <= 0 ? 0.0 : interval_double_detail::root_to<false>(x.lo_);
    return {std::max(lo, 0.0), interval_double_detail::root_to<true>(x.hi_)};
  }
  friend DoubleInterval exp(const DoubleInterval& x);  // MPFR, directed rounding
  friend DoubleInterval log(const DoubleInterval& x);  // MPFR, directed rounding; NaN for x <= 0
  friend DoubleInterval abs(const DoubleInterval& x) {
    if (x.lo_ >= 0) return x;
    if (x.hi_ <= 0) return -x;
    return {0.0, std::max(-x.lo_, x.hi_)};
  }
  friend DoubleInterval hull(const DoubleInterval& x, const DoubleInterval& y) {
    return {std::min(x.lo_, y.lo_), std::max(x.hi_, y.hi_)};
  }
  // Intersection (never formed empty here: callers intersect enclosures of one value).
  friend DoubleInterval intersect(const DoubleInterval& x, const DoubleInterval& y) {
    return {std::max(x.lo_, y.lo_), std::min(x.hi_, y.hi_)};
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
