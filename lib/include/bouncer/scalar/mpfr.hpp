// Mpfr: a correctly rounded (round-to-nearest) MPFR number whose precision travels with
// the value, not with a process-wide default.
//
// Why not Boost's mpfr_float: in Boost 1.74 the default precision of variable-precision
// numbers is one process-wide static (unsafe for threads with different precisions), and
// every temporary costs a heap allocation (about 2.5x raw MPFR per step at 53-128 bits).
// Here a value of up to kInlineBits bits keeps its limbs inside the object (MPFR's
// "custom" interface), so temporaries cost no allocation and the impact map can be
// written with ordinary operators. Larger precisions fall back to mpfr_init2.
//
// Precision rules: the result of a binary operation has the larger precision of its
// operands; compound assignment keeps the precision of the left side; assignment copies
// value and precision.
#pragma once

#include <mpfr.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

namespace bouncer {

class Mpfr {
 public:
  static constexpr int kInlineLimbs = 16;
  static constexpr long kInlineBits = kInlineLimbs * GMP_NUMB_BITS;

  Mpfr() { init(53); }
  explicit Mpfr(mpfr_prec_t bits) { init(bits); }
  Mpfr(long n, mpfr_prec_t bits) { init(bits); mpfr_set_si(v_, n, MPFR_RNDN); }
  Mpfr(const Mpfr& o) { init(o.bits()); copy_value(o); }
  Mpfr(Mpfr&& o) noexcept {
    if (o.is_inline()) {
      init(o.bits());
      copy_limbs(o);
    } else {
      v_[0] = o.v_[0];  // steal the heap limbs
      o.init(MPFR_PREC_MIN);
    }
  }
  Mpfr& operator=(const Mpfr& o) {
    if (this != &o) {
      if (bits() != o.bits()) { release(); init(o.bits()); }
      copy_value(o);
    }
    return *this;
  }
  Mpfr& operator=(Mpfr&& o) noexcept {
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
  ~Mpfr() { release(); }

  mpfr_prec_t bits() const { return mpfr_get_prec(v_); }
  mpfr_ptr get() { return v_; }
  mpfr_srcptr get() const { return v_; }

  // Correctly rounded value of a decimal (or any MPFR-syntax) string; false on bad syntax.
  bool set_decimal(std::string_view text) {
    std::string s(text);
    char* end = nullptr;
    mpfr_strtofr(v_, s.c_str(), &end, 10, MPFR_RNDN);
    return !s.empty() && end && *end == '\0';
  }

  Mpfr& operator+=(const Mpfr& o) { mpfr_add(v_, v_, o.v_, MPFR_RNDN); return *this; }
  Mpfr& operator-=(const Mpfr& o) { mpfr_sub(v_, v_, o.v_, MPFR_RNDN); return *this; }
  Mpfr& operator*=(const Mpfr& o) { mpfr_mul(v_, v_, o.v_, MPFR_RNDN); return *this; }
  Mpfr& operator/=(const Mpfr& o) { mpfr_div(v_, v_, o.v_, MPFR_RNDN); return *this; }
  Mpfr& operator*=(long n) { mpfr_mul_si(v_, v_, n, MPFR_RNDN); return *this; }
  Mpfr& operator/=(long n) { mpfr_div_si(v_, v_, n, MPFR_RNDN); return *this; }

  friend Mpfr operator+(const Mpfr& x, const Mpfr& y) { Mpfr r(wider(x, y)); mpfr_add(r.v_, x.v_, y.v_, MPFR_RNDN); return r; }
  friend Mpfr operator-(const Mpfr& x, const Mpfr& y) { Mpfr r(wider(x, y)); mpfr_sub(r.v_, x.v_, y.v_, MPFR_RNDN); return r; }
  friend Mpfr operator*(const Mpfr& x, const Mpfr& y) { Mpfr r(wider(x, y)); mpfr_mul(r.v_, x.v_, y.v_, MPFR_RNDN); return r; }
  friend Mpfr operator/(const Mpfr& x, const Mpfr& y) { Mpfr r(wider(x, y)); mpfr_div(r.v_, x.v_, y.v_, MPFR_RNDN); return r; }
  friend Mpfr operator-(const Mpfr& x) { Mpfr r(x.bits()); mpfr_neg(r.v_, x.v_, MPFR_RNDN); return r; }

  // Exact small-integer operands (no conversion of the integer to a rounded Mpfr).
  friend Mpfr operator+(const Mpfr& x, long n) { Mpfr r(x.bits()); mpfr_add_si(r.v_, x.v_, n, MPFR_RNDN); return r; }
  friend Mpfr operator-(const Mpfr& x, long n) { Mpfr r(x.bits()); mpfr_sub_si(r.v_, x.v_, n, MPFR_RNDN); return r; }
  friend Mpfr operator-(long n, const Mpfr& x) { Mpfr r(x.bits()); mpfr_si_sub(r.v_, n, x.v_, MPFR_RNDN); return r; }
  friend Mpfr operator*(const Mpfr& x, long n) { Mpfr r(x.bits()); mpfr_mul_si(r.v_, x.v_, n, MPFR_RNDN); return r; }
  friend Mpfr operator*(long n, const Mpfr& x) { return x * n; }
  friend Mpfr operator/(const Mpfr& x, long n) { Mpfr r(x.bits()); mpfr_div_si(r.v_, x.v_, n, MPFR_RNDN); return r; }
  friend Mpfr operator/(long n, const Mpfr& x) { Mpfr r(x.bits()); mpfr_si_div(r.v_, n, x.v_, MPFR_RNDN); return r; }

  // Point comparisons are exact, so plain bools are honest here (NaN compares false).
  friend bool operator<(const Mpfr& x, const Mpfr& y) { return mpfr_less_p(x.v_, y.v_); }
  friend bool operator<=(const Mpfr& x, const Mpfr& y) { return mpfr_lessequal_p(x.v_, y.v_); }
  friend bool operator>(const Mpfr& x, const Mpfr& y) { return mpfr_greater_p(x.v_, y.v_); }
  friend bool operator>=(const Mpfr& x, const Mpfr& y) { return mpfr_greaterequal_p(x.v_, y.v_); }
  friend bool operator==(const Mpfr& x, const Mpfr& y) { return mpfr_equal_p(x.v_, y.v_); }

  friend Mpfr sqrt(const Mpfr& x) { Mpfr r(x.bits()); mpfr_sqrt(r.v_, x.v_, MPFR_RNDN); return r; }
  friend Mpfr exp(const Mpfr& x) { Mpfr r(x.bits()); mpfr_exp(r.v_, x.v_, MPFR_RNDN); return r; }
  friend Mpfr log(const Mpfr& x) { Mpfr r(x.bits()); mpfr_log(r.v_, x.v_, MPFR_RNDN); return r; }
  friend Mpfr abs(const Mpfr& x) { Mpfr r(x.bits()); mpfr_abs(r.v_, x.v_, MPFR_RNDN); return r; }
  friend Mpfr floor(const Mpfr& x) { Mpfr r(x.bits()); mpfr_floor(r.v_, x.v_); return r; }
  friend Mpfr pow(const Mpfr& x, const Mpfr& y) { Mpfr r(wider(x, y)); mpfr_pow(r.v_, x.v_, y.v_, MPFR_RNDN); return r; }

  double to_double() const { return mpfr_get_d(v_, MPFR_RNDN); }

 private:
  mpfr_t v_;
  mp_limb_t limbs_[kInlineLimbs];

  static mpfr_prec_t wider(const Mpfr& x, const Mpfr& y) { return std::max(x.bits(), y.bits()); }
  bool is_inline() const { return mpfr_custom_get_significand(v_) == static_cast<const void*>(limbs_); }
  void init(mpfr_prec_t bits) {
    if (mpfr_custom_get_size(bits) <= sizeof(limbs_)) {
      mpfr_custom_init(limbs_, bits);
      mpfr_custom_init_set(v_, MPFR_NAN_KIND, 0, bits, limbs_);
    } else {
      mpfr_init2(v_, bits);
    }
  }
  void release() {
    if (!is_inline()) mpfr_clear(v_);
  }
  // Copy an inline value of the same precision: header fields and the used limbs.
  void copy_limbs(const Mpfr& o) {
    v_->_mpfr_sign = o.v_->_mpfr_sign;
    v_->_mpfr_exp = o.v_->_mpfr_exp;
    // NaN, infinities and zeros live in the exponent field; their limbs are never read.
    if (mpfr_regular_p(o.v_)) copy_limb_array(limbs_, o.limbs_, mpfr_custom_get_size(o.bits()) / sizeof(mp_limb_t));
  }
  // Copy a value of the same precision wherever its limbs live: what mpfr_set does for
  // equal precisions (special values live in the exponent field), without the call.
  void copy_value(const Mpfr& o) {
    v_->_mpfr_sign = o.v_->_mpfr_sign;
    v_->_mpfr_exp = o.v_->_mpfr_exp;
    if (!mpfr_regular_p(o.v_)) return;
    copy_limb_array(static_cast<mp_limb_t*>(mpfr_custom_get_significand(v_)),
                    static_cast<const mp_limb_t*>(mpfr_custom_get_significand(o.v_)),
                    mpfr_custom_get_size(o.bits()) / sizeof(mp_limb_t));
  }

 public:
  // Up to 4 limbs (256 bits) by plain assignments: a call to memmove for two limbs cost
  // ~19% of a 113-bit step (measured with perf on tools/bench/bench_step).
  static void copy_limb_array(mp_limb_t* to, const mp_limb_t* from, size_t n) {
    switch (n) {
      case 4: to[3] = from[3]; [[fallthrough]];
      case 3: to[2] = from[2]; [[fallthrough]];
      case 2: to[1] = from[1]; [[fallthrough]];
      case 1: to[0] = from[0]; break;
      default: std::memcpy(to, from, n * sizeof(mp_limb_t));
    }
  }
};

// Namespace-scope declarations of the friends, so that bouncer::floor(x) etc. also work.
Mpfr sqrt(const Mpfr& x);
Mpfr exp(const Mpfr& x);
Mpfr log(const Mpfr& x);
Mpfr abs(const Mpfr& x);
Mpfr floor(const Mpfr& x);
Mpfr pow(const Mpfr& x, const Mpfr& y);

}  // namespace bouncer
