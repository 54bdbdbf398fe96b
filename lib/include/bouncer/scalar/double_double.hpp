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
//   dd + dd      AccurateDWPlusDW                 3u^2 (+ O(u^3))
//   dd * dd      DWTimesDW1 (no FMA)              7u^2
//   dd / dd      DWDivDW2                         15u^2 (+ O(u^3))
//   sqrt         one Newton correction of sqrt(hi) with the remainder x - s^2 from
//                TwoProduct (as QD's sqrt); tested against MPFR
// Integer operands (exact as doubles: |n| <= 2^53; larger ones become pairs) take the double-word-by-double
// algorithms DWPlusFP, DWTimesFP1 and DWDivFP1 (bounds of 2u^2, 1.5u^2 and 3.5u^2 in JMP).
// The tests measure the largest errors on random operands (tests/test_double_double.cpp):
// 1.5, 3.0, 4.9 and 2.5 u^2 for +, *, / and sqrt. exp and log are QD's dd_real functions
// (libqd, Hida, Li and Bailey; measured up to 18 u^2), x^(3/5) is QD's fifth root of x^3
// corrected by one Newton step in dd (QD's alone: 125 u^2). QD's own + and / are not used:
// Debian builds it without QD_IEEE_ADD (the sloppy add), whose relative error is unbounded
// under cancellation, which the impact map meets at every impact.
//
// Decimal input: hi = RN(d), lo = RN(d - hi) for the exact rational d (GMP and MPFR, both
// correctly rounded), then renormalised. Decimal output: a decimal that reads back to the
// same pair, checked by reading it back: about as many digits as the bits hi and lo span
// (33 when lo fills the bits below hi, more when lo is much smaller: 0.25 - 4.7e-33 needs
// 49), at worst the exact value.
//
// Overflow: products beyond about 2^1023 overflow (and the error term of products below about
// 2^-969 underflows, losing the low word's accuracy); the map's values are many orders of
// magnitude inside, and a NaN or infinity is caught as "non-finite" like in double.
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
    // n = (n >> 32) 2^32 + (n & (2^32 - 1)): both parts exact doubles, their sum exact in dd.
    const double h = std::ldexp(static_cast<double>(n >> 32), 32);
    const double l = static_cast<double>(n & 0xffffffffL);
    set_sum(h, l);
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

  // AccurateDWPlusDW (JMP 2017).
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
  // DWTimesDW1 (JMP 2017) with TwoProduct (one FMA: scalar/error_free.hpp).
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
  // DWDivDW2 (JMP 2017): th = xh / yh, the remainder x - th y in dd, one correction.
  friend DoubleDouble operator/(const DoubleDouble& x, const DoubleDouble& y) {
    const double th = x.hi_ / y.hi_;
    const DoubleDouble r = y.times(th);
    const double pi_h = x.hi_ - r.hi_;
    const double d_l = x.lo_ - r.lo_;
    const double d = pi_h + d_l;
    const double tl = d / y.hi_;
    DoubleDouble q;
    q.set_fast(th, tl);
    return q;
  }
  // With an integer: when it is exact as a double (|n| <= 2^53: every integer the map uses)
  // the double-word-by-double algorithms, cheaper than converting n to a pair; else the pair.
  static bool small(long n) { return n >= -(1L << 53) && n <= (1L << 53); }
  friend DoubleDouble operator+(const DoubleDouble& x, long n) { return small(n) ? x.plus(static_cast<double>(n)) : x + DoubleDouble(n); }
  friend DoubleDouble operator+(long n, const DoubleDouble& x) { return x + n; }
  friend DoubleDouble operator-(const DoubleDouble& x, long n) { return small(n) ? x.plus(-static_cast<double>(n)) : x - DoubleDouble(n); }
  friend DoubleDouble operator-(long n, const DoubleDouble& x) { return (-x) + n; }
  friend DoubleDouble operator*(const DoubleDouble& x, long n) { return small(n) ? x.times(static_cast<double>(n)) : x * DoubleDouble(n); }
  friend DoubleDouble operator*(long n, const DoubleDouble& x) { return x * n; }
  friend DoubleDouble operator/(const DoubleDouble& x, long n) { return small(n) ? x.divided_by(static_cast<double>(n)) : x / DoubleDouble(n); }
  friend DoubleDouble operator/(long n, const DoubleDouble& x) { return DoubleDouble(n) / x; }

  // sqrt(x) = s + (x - s^2) / (2 s) with s = sqrt(xh) in double, the remainder in dd. 0 for
  // x = 0, NaN for x < 0.
  friend DoubleDouble sqrt(const DoubleDouble& x) {
    if (x.hi_ <= 0) return x.hi_ == 0 ? DoubleDouble() : nan_value();
    const double s = std::sqrt(x.hi_);
    double ph, pl;
    error_free::two_product(s, s, ph, pl);
    // x - s^2: xh - ph is exact (Sterbenz: ph is within an ulp of xh).
    const double rem = ((x.hi_ - ph) - pl) + x.lo_;
    const double corr = rem / (2 * s);
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
  // DWPlusFP (JMP 2017): x + y for a double y.
  DoubleDouble plus(double y) const {
    double sh, sl;
    error_free::two_sum(hi_, y, sh, sl);
    DoubleDouble r;
    r.set_fast(sh, lo_ + sl);
    return r;
  }
  // DWTimesFP1 (JMP 2017, without FMA): x y for a double y.
  DoubleDouble times(double y) const {
    double ch, cl1;
    error_free::two_product(hi_, y, ch, cl1);
    const double cl2 = lo_ * y;
    double th, tl1;
    error_free::fast_two_sum(ch, cl2, th, tl1);
    DoubleDouble r;
    r.set_fast(th, tl1 + cl1);
    return r;
  }
  // DWDivFP1 (JMP 2017, without FMA): x / y for a double y.
  DoubleDouble divided_by(double y) const {
    const double th = hi_ / y;
    double ph, pl;
    error_free::two_product(th, y, ph, pl);
    const double dh = hi_ - ph;
    const double dt = dh - pl;
    const double d = dt + lo_;
    DoubleDouble r;
    r.set_fast(th, d / y);
    return r;
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
