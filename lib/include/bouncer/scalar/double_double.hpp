// DoubleDouble: a value hi + lo held as two IEEE doubles (double-word arithmetic), about 106
// significant bits at a few times the cost of a double: --precision dd, a point type of the
// scalar set between long double (64 bits) and quad (113 bits, in software: 35-58x double).
//
// Representation. Every value is canonical: hi = RN(hi + lo) (the double nearest the exact
// sum), so |lo| <= ulp(hi)/2, hi alone is the value rounded to double, and comparisons are
// lexicographic on (hi, lo). Every operation ends with a FastTwoSum renormalisation, which
// makes it so.
//
// Arithmetic. The program runs in round-to-nearest with SSE2 doubles and -ffp-contract=off
// (no FMA contraction), so the error-free transformations are exact (scalar/error_free.hpp).
// The algorithms are the accurate ones of Joldes, Muller and Popescu, "Tight and rigorous
// error bounds for basic building blocks of double-word arithmetic" (ACM TOMS 44, 2017), with
// their proved relative error bounds (u = 2^-53):
//   dd + dd      AccurateDWPlusDW (Alg. 6)        3u^2 + 13u^3 ~ 2^-104.4
//   dd * dd      DWTimesDW1 (Alg. 10, no FMA)     7u^2           ~ 2^-103.2
//   dd / dd      long division with two corrections (QD's accurate_div: q1 = xh/yh, the
//                remainder computed in dd, twice), tested against MPFR at 106 bits
//   sqrt         one Newton correction of sqrt(hi) with the dd remainder (as QD), tested
// Integer operands are converted exactly (|n| < 2^106). exp and log are QD's dd_real
// functions (libqd, Hida, Li and Bailey; relative error a few 2^-104, tested against MPFR).
// QD's own + and / are not used: Debian builds it with QD_SLOPPY_ADD (no IEEE add), whose
// error is unbounded under cancellation, which the impact map meets at every impact.
//
// Decimal input: hi = RN(d), lo = RN(d - hi) for the exact rational d (GMP and MPFR, both
// correctly rounded), then renormalised. Decimal output: the shortest decimal (>= 32 digits)
// that reads back to the same pair, checked by reading it back; at worst the exact value.
//
// Overflow: values beyond about 2^996 overflow the Veltkamp splitting of the product; the
// map's values are many orders of magnitude below, and a NaN or infinity is caught as
// "non-finite" like in double.
#pragma once

#include <cmath>
#include <limits>

#include "bouncer/scalar/error_free.hpp"

namespace bouncer {

class DoubleDouble {
 public:
  DoubleDouble() = default;  // 0
  // The exact integer n.
  explicit DoubleDouble(long n) {
    const double h = static_cast<double>(n);
    const double l = static_cast<double>(n - static_cast<long>(h));  // exact: |n - h| < 2^11
    set_fast(h, l);
  }
  // The double x exactly.
  explicit DoubleDouble(double x) : hi_(x), lo_(0) {}
  // A pair that is already canonical (hi = RN(hi + lo)), or made so.
  static DoubleDouble from_pair(double hi, double lo) {
    DoubleDouble r;
    r.set_sum(hi, lo);
    return r;
  }

  double hi() const { return hi_; }
  double lo() const { return lo_; }

  DoubleDouble& operator+=(const DoubleDouble& o) { return *this = *this + o; }
  DoubleDouble& operator-=(const DoubleDouble& o) { return *this = *this - o; }
  DoubleDouble& operator*=(const DoubleDouble& o) { return *this = *this * o; }
  DoubleDouble& operator/=(const DoubleDouble& o) { return *this = *this / o; }
  DoubleDouble& operator*=(long n) { return *this = *this * n; }
  DoubleDouble& operator/=(long n) { return *this = *this / n; }

  // AccurateDWPlusDW (JMP 2017, Alg. 6).
  friend DoubleDouble operator+(const DoubleDouble& x, const DoubleDouble& y) {
    double sh, sl, th, tl;
    error_free::two_sum(x.hi_, y.hi_, sh, sl);
    error_free::two_sum(x.lo_, y.lo_, th, tl);
    sl += th;
    error_free::fast_two_sum(sh, sl, sh, sl);
    sl += tl;
    DoubleDouble r;
    r.set_fast(sh, sl);
    return r;
  }
  friend DoubleDouble operator-(const DoubleDouble& x) {
    DoubleDouble r;
    r.hi_ = -x.hi_;
    r.lo_ = -x.lo_;
    return r;
  }
  friend DoubleDouble operator-(const DoubleDouble& x, const DoubleDouble& y) { return x + (-y); }
  // DWTimesDW1 (JMP 2017, Alg. 10) with Dekker's TwoProduct.
  friend DoubleDouble operator*(const DoubleDouble& x, const DoubleDouble& y) {
    double ch, cl1;
    error_free::two_product(x.hi_, y.hi_, ch, cl1);
    const double tl1 = x.hi_ * y.lo_;
    const double tl2 = x.lo_ * y.hi_;
    const double cl2 = tl1 + tl2;
    const double cl3 = cl1 + cl2;
    DoubleDouble r;
    r.set_fast(ch, cl3);
    return r;
  }
  // Long division: q1 = xh / yh, r = x - q1 y in dd; q2 = rh / yh, r -= q2 y; q3 = rh / yh.
  friend DoubleDouble operator/(const DoubleDouble& x, const DoubleDouble& y) {
    const double q1 = x.hi_ / y.hi_;
    DoubleDouble r = x - y * DoubleDouble(q1);
    const double q2 = r.hi_ / y.hi_;
    r -= y * DoubleDouble(q2);
    const double q3 = r.hi_ / y.hi_;
    DoubleDouble q;
    q.set_fast(q1, q2);
    return q + DoubleDouble(q3);
  }
  friend DoubleDouble operator+(const DoubleDouble& x, long n) { return x + DoubleDouble(n); }
  friend DoubleDouble operator+(long n, const DoubleDouble& x) { return x + DoubleDouble(n); }
  friend DoubleDouble operator-(const DoubleDouble& x, long n) { return x - DoubleDouble(n); }
  friend DoubleDouble operator-(long n, const DoubleDouble& x) { return DoubleDouble(n) - x; }
  friend DoubleDouble operator*(const DoubleDouble& x, long n) { return x * DoubleDouble(n); }
  friend DoubleDouble operator*(long n, const DoubleDouble& x) { return x * DoubleDouble(n); }
  friend DoubleDouble operator/(const DoubleDouble& x, long n) { return x / DoubleDouble(n); }
  friend DoubleDouble operator/(long n, const DoubleDouble& x) { return DoubleDouble(n) / x; }

  // sqrt(x) = s + (x - s^2) / (2 s) with s = sqrt(xh) in double, the remainder in dd. 0 for
  // x = 0, NaN for x < 0.
  friend DoubleDouble sqrt(const DoubleDouble& x) {
    if (x.hi_ <= 0) return x.hi_ == 0 ? DoubleDouble() : nan_value();
    const double s = std::sqrt(x.hi_);
    const DoubleDouble rem = x - DoubleDouble(s) * DoubleDouble(s);
    const double corr = rem.hi_ / (2 * s);
    DoubleDouble r;
    r.set_sum(s, corr);
    return r;
  }
  friend DoubleDouble exp(const DoubleDouble& x);  // QD (libqd)
  friend DoubleDouble log(const DoubleDouble& x);  // QD (libqd); NaN for x < 0, -inf at 0
  friend DoubleDouble abs(const DoubleDouble& x) { return x.hi_ < 0 ? -x : x; }
  friend DoubleDouble floor(const DoubleDouble& x) {
    // hi not an integer: no integer lies within |lo| <= ulp(hi)/2 of it, so floor(hi).
    const double fh = std::floor(x.hi_);
    if (fh != x.hi_) return DoubleDouble(fh);
    DoubleDouble r;
    r.set_fast(fh, std::floor(x.lo_));
    return r;
  }

  // Canonical pairs compare lexicographically.
  friend bool operator<(const DoubleDouble& x, const DoubleDouble& y) { return x.hi_ < y.hi_ || (x.hi_ == y.hi_ && x.lo_ < y.lo_); }
  friend bool operator>(const DoubleDouble& x, const DoubleDouble& y) { return y < x; }
  friend bool operator<=(const DoubleDouble& x, const DoubleDouble& y) { return x.hi_ < y.hi_ || (x.hi_ == y.hi_ && x.lo_ <= y.lo_); }
  friend bool operator>=(const DoubleDouble& x, const DoubleDouble& y) { return y <= x; }
  friend bool operator==(const DoubleDouble& x, const DoubleDouble& y) { return x.hi_ == y.hi_ && x.lo_ == y.lo_; }
  friend bool operator!=(const DoubleDouble& x, const DoubleDouble& y) { return !(x == y); }

  bool is_nan() const { return std::isnan(hi_) || std::isnan(lo_); }
  bool is_finite() const { return std::isfinite(hi_) && std::isfinite(lo_); }

  static DoubleDouble nan_value() {
    DoubleDouble r;
    r.hi_ = r.lo_ = std::numeric_limits<double>::quiet_NaN();
    return r;
  }

 private:
  double hi_ = 0, lo_ = 0;

  // FastTwoSum (|h| >= |l| or h == 0): the canonical pair of h + l. A non-finite sum keeps
  // lo NaN-free only when finite; inf - inf in the error term gives NaN, which is_finite
  // reports.
  void set_fast(double h, double l) {
    const double s = h + l;
    if (!std::isfinite(s)) {
      hi_ = s;
      lo_ = 0;
      return;
    }
    lo_ = l - (s - h);
    hi_ = s;
  }
  // TwoSum: any order of magnitude.
  void set_sum(double h, double l) {
    double s, e;
    error_free::two_sum(h, l, s, e);
    if (!std::isfinite(s)) e = 0;
    hi_ = s;
    lo_ = e;
  }
};

// Visible by name as well as by argument-dependent lookup.
DoubleDouble exp(const DoubleDouble& x);
DoubleDouble log(const DoubleDouble& x);
DoubleDouble sqrt(const DoubleDouble& x);
DoubleDouble abs(const DoubleDouble& x);
DoubleDouble floor(const DoubleDouble& x);

}  // namespace bouncer
