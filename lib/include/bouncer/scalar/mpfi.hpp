// Mpfi: an MPFI interval (outward rounding) whose precision travels with the value.
//
// Why not Boost's mpfi_float: its comparisons of overlapping intervals, and floor of an
// interval containing an integer, throw from noexcept functions, which terminates the
// program. Mpfi has no bool comparisons at all: the only way to branch on it is through
// the three-valued predicates in scalar/traits.hpp (certainly true / certainly false /
// unknown). Endpoints of up to kInlineBits bits live inside the object, as in Mpfr.
//
// Each end of +, -, *, /, sqrt, exp and log is the correctly rounded RNDD / RNDU result at the
// precision (MPFI's contract; tested at 53 bits against MPFR at 2200 bits near the ends of
// the double range, tests/test_interval_extremes.cpp, and with ITF1788, the IEEE 1788 test
// suite, tests/test_itf1788.cpp). Where IEEE 1788 has an empty or bounded result these give none
// that is finite: a divisor holding 0 gives an unbounded interval (mpfi_div: [-inf, inf] for
// [0, 0]; 0 / [0, 3] is [0, inf]) where DoubleInterval gives NaN; sqrt and log of an interval
// reaching below 0 give NaN; an empty intersection gives NaN (below). A NaN interval is
// invalid: the predicates of scalar/traits.hpp answer Truth::invalid, is_finite is false.
#pragma once

#include <mpfi.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <string_view>

#include "bouncer/scalar/mpfr.hpp"

namespace bouncer {

class Mpfi {
 public:
  static constexpr int kInlineLimbs = 16;

  Mpfi() { init(53); }
  explicit Mpfi(mpfr_prec_t bits) { init(bits); }
  Mpfi(long n, mpfr_prec_t bits) { init(bits); mpfi_set_si(v_, n); }
  Mpfi(const Mpfr& lo, const Mpfr& hi) { init(std::max(lo.bits(), hi.bits())); mpfi_interv_fr(v_, lo.get(), hi.get()); }
  Mpfi(const Mpfi& o) { init(o.bits()); mpfi_set(v_, o.v_); }
  Mpfi(Mpfi&& o) noexcept {
    if (o.is_inline()) {
      init(o.bits());
      copy_limbs(o);
    } else {
      v_[0] = o.v_[0];
      o.init(MPFR_PREC_MIN);
    }
  }
  Mpfi& operator=(const Mpfi& o) {
    if (this != &o) {
      if (bits() != o.bits()) { release(); init(o.bits()); }
      mpfi_set(v_, o.v_);
    }
    return *this;
  }
  Mpfi& operator=(Mpfi&& o) noexcept {
    if (this == &o) return *this;
    if (!o.is_inline()) {
      release();
      v_[0] = o.v_[0];
      o.init(MPFR_PREC_MIN);
    } else {
      if (bits() != o.bits()) { release(); init(o.bits()); }
      copy_limbs(o);
    }
    return *this;
  }
  ~Mpfi() { release(); }

  mpfr_prec_t bits() const { return mpfr_get_prec(&v_->left); }  // inline, unlike mpfi_get_prec
  mpfi_ptr get() { return v_; }
  mpfi_srcptr get() const { return v_; }

  // The tightest interval at this precision containing the exact value of the decimal
  // string (lower end rounded down, upper end rounded up); false on bad syntax.
  bool set_decimal(std::string_view text) {
    std::string s(text);
    if (s.empty()) return false;
    Mpfr lo(bits()), hi(bits());
    char* end = nullptr;
    mpfr_strtofr(lo.get(), s.c_str(), &end, 10, MPFR_RNDD);
    if (!end || *end != '\0') return false;
    mpfr_strtofr(hi.get(), s.c_str(), &end, 10, MPFR_RNDU);
    mpfi_interv_fr(v_, lo.get(), hi.get());
    return true;
  }

  Mpfr lower() const { Mpfr r(bits()); mpfi_get_left(r.get(), v_); return r; }
  Mpfr upper() const { Mpfr r(bits()); mpfi_get_right(r.get(), v_); return r; }
  Mpfr mid() const { Mpfr r(bits()); mpfi_mid(r.get(), v_); return r; }
  Mpfr width() const { Mpfr r(bits()); mpfi_diam_abs(r.get(), v_); return r; }
  bool contains(const Mpfr& x) const { return mpfi_is_inside_fr(x.get(), v_) > 0; }
  bool contains(const Mpfi& x) const { return mpfi_is_inside(x.v_, v_) > 0; }
  bool has_nan() const { return mpfi_nan_p(v_) != 0; }
  bool bounded() const { return mpfi_bounded_p(v_) != 0; }

  Mpfi& operator+=(const Mpfi& o) { mpfi_add(v_, v_, o.v_); return *this; }
  Mpfi& operator-=(const Mpfi& o) { mpfi_sub(v_, v_, o.v_); return *this; }
  Mpfi& operator*=(const Mpfi& o) { mpfi_mul(v_, v_, o.v_); return *this; }
  Mpfi& operator/=(const Mpfi& o) { mpfi_div(v_, v_, o.v_); return *this; }
  Mpfi& operator*=(long n) { mpfi_mul_si(v_, v_, n); return *this; }
  Mpfi& operator/=(long n) { mpfi_div_si(v_, v_, n); return *this; }

  friend Mpfi operator+(const Mpfi& x, const Mpfi& y) { Mpfi r(wider(x, y)); mpfi_add(r.v_, x.v_, y.v_); return r; }
  friend Mpfi operator-(const Mpfi& x, const Mpfi& y) { Mpfi r(wider(x, y)); mpfi_sub(r.v_, x.v_, y.v_); return r; }
  friend Mpfi operator*(const Mpfi& x, const Mpfi& y) { Mpfi r(wider(x, y)); mpfi_mul(r.v_, x.v_, y.v_); return r; }
  friend Mpfi operator/(const Mpfi& x, const Mpfi& y) { Mpfi r(wider(x, y)); mpfi_div(r.v_, x.v_, y.v_); return r; }
  friend Mpfi operator-(const Mpfi& x) { Mpfi r(x.bits()); mpfi_neg(r.v_, x.v_); return r; }

  friend Mpfi operator+(const Mpfi& x, long n) { Mpfi r(x.bits()); mpfi_add_si(r.v_, x.v_, n); return r; }
  friend Mpfi operator-(const Mpfi& x, long n) { Mpfi r(x.bits()); mpfi_sub_si(r.v_, x.v_, n); return r; }
  friend Mpfi operator-(long n, const Mpfi& x) { Mpfi r(x.bits()); mpfi_si_sub(r.v_, n, x.v_); return r; }
  friend Mpfi operator*(const Mpfi& x, long n) { Mpfi r(x.bits()); mpfi_mul_si(r.v_, x.v_, n); return r; }
  friend Mpfi operator*(long n, const Mpfi& x) { return x * n; }
  friend Mpfi operator/(const Mpfi& x, long n) { Mpfi r(x.bits()); mpfi_div_si(r.v_, x.v_, n); return r; }
  friend Mpfi operator/(long n, const Mpfi& x) { Mpfi r(x.bits()); mpfi_si_div(r.v_, n, x.v_); return r; }

  // mpfi_sqrt: NaN (invalid) for an x reaching below 0, unlike DoubleInterval's sqrt, which
  // roots the non-negative part ([0, sqrt(hi)], IEEE 1788); NaN for x entirely below 0 in both.
  friend Mpfi sqrt(const Mpfi& x) { Mpfi r(x.bits()); mpfi_sqrt(r.v_, x.v_); return r; }
  friend Mpfi exp(const Mpfi& x) { Mpfi r(x.bits()); mpfi_exp(r.v_, x.v_); return r; }
  // mpfi_log: NaN for an x reaching below 0; a lower end 0 gives -inf (as DoubleInterval).
  friend Mpfi log(const Mpfi& x) { Mpfi r(x.bits()); mpfi_log(r.v_, x.v_); return r; }
  friend Mpfi abs(const Mpfi& x) { Mpfi r(x.bits()); mpfi_abs(r.v_, x.v_); return r; }
  // Hull of two intervals (NaN if either is NaN, as mpfi_union).
  friend Mpfi hull(const Mpfi& x, const Mpfi& y) { Mpfi r(wider(x, y)); mpfi_union(r.v_, x.v_, y.v_); return r; }
  // Intersection. mpfi_intersect leaves disjoint intervals as an inverted pair (left > right:
  // MPFI's "empty"), which has_nan() and bounded() do not flag and which later operations
  // compute with ([3, 2] + [1, 2] = [4, 4]); here it becomes the NaN interval, which every
  // caller treats as invalid (as DoubleInterval's intersect). A NaN operand gives NaN.
  friend Mpfi intersect(const Mpfi& x, const Mpfi& y) {
    Mpfi r(wider(x, y));
    mpfi_intersect(r.v_, x.v_, y.v_);
    if (mpfi_is_empty(r.v_)) {
      mpfr_set_nan(&r.v_->left);
      mpfr_set_nan(&r.v_->right);
    }
    return r;
  }

 private:
  mpfi_t v_;
  mp_limb_t left_[kInlineLimbs];
  mp_limb_t right_[kInlineLimbs];

  static mpfr_prec_t wider(const Mpfi& x, const Mpfi& y) { return std::max(x.bits(), y.bits()); }
  bool is_inline() const { return mpfr_custom_get_significand(&v_->left) == static_cast<const void*>(left_); }
  void init(mpfr_prec_t bits) {
    if (mpfr_custom_get_size(bits) <= sizeof(left_)) {
      mpfr_custom_init(left_, bits);
      mpfr_custom_init(right_, bits);
      mpfr_custom_init_set(&v_->left, MPFR_NAN_KIND, 0, bits, left_);
      mpfr_custom_init_set(&v_->right, MPFR_NAN_KIND, 0, bits, right_);
    } else {
      mpfi_init2(v_, bits);
    }
  }
  void release() {
    if (!is_inline()) mpfi_clear(v_);
  }
  void copy_limbs(const Mpfi& o) {
    v_->left._mpfr_sign = o.v_->left._mpfr_sign;
    v_->left._mpfr_exp = o.v_->left._mpfr_exp;
    v_->right._mpfr_sign = o.v_->right._mpfr_sign;
    v_->right._mpfr_exp = o.v_->right._mpfr_exp;
    const size_t n = mpfr_custom_get_size(o.bits()) / sizeof(mp_limb_t);
    // Limbs of NaN, infinite or zero ends are never read: copy only regular ends.
    if (mpfr_regular_p(&o.v_->left)) Mpfr::copy_limb_array(left_, o.left_, n);
    if (mpfr_regular_p(&o.v_->right)) Mpfr::copy_limb_array(right_, o.right_, n);
  }
};

Mpfi sqrt(const Mpfi& x);
Mpfi exp(const Mpfi& x);
Mpfi log(const Mpfi& x);
Mpfi abs(const Mpfi& x);
Mpfi hull(const Mpfi& x, const Mpfi& y);
Mpfi intersect(const Mpfi& x, const Mpfi& y);

}  // namespace bouncer
