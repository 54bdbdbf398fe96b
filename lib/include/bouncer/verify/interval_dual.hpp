// Dual<Mpfi>: forward-mode derivatives evaluated in interval arithmetic. Evaluated on a box
// X, the derivative components enclose the Jacobian of the branch over all of X (every
// branch is decided for the whole box through the three-valued predicates, so the step is
// one smooth formula on X). Used by the Lohner enclosure (verify/enclosure.hpp).
//
// scalar/dual.hpp's generic ScalarTraits<Dual<S>> is for point scalars (bool comparisons,
// nonneg by the midpoint's sign); this full specialization replaces it for S = Mpfi, and
// the overloads below replace the rounding guards of traits.hpp / dual.hpp. Include this
// header (not dual.hpp alone) wherever Dual<Mpfi> is used.
#pragma once

#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/dual.hpp"

namespace bouncer {

using IDual = Dual<Mpfi>;

template <>
struct ScalarTraits<Dual<Mpfi>> {
  using D = Dual<Mpfi>;
  using B = ScalarTraits<Mpfi>;
  static constexpr bool is_interval = true;
  static constexpr const char* family = "interval-dual";
  static D from_decimal(std::string_view text, long bits) { return D(B::from_decimal(text, bits)); }
  static D from_int(long n, long bits) { return D(B::from_int(n, bits)); }
  static long bits(const D& x) { return B::bits(x.v); }
  static Truth lt(const D& x, const D& y) { return B::lt(x.v, y.v); }
  static Truth le(const D& x, const D& y) { return B::le(x.v, y.v); }
  static Truth is_zero(const D& x) { return B::is_zero(x.v); }
  static bool likely_negative(const D& x) { return B::likely_negative(x.v); }
  // The exact value is known to be >= 0: only the value enclosure is cut (derivatives kept;
  // a square root of it then has an unbounded derivative enclosure if 0 is inside).
  static D nonneg(const D& x) { return {B::nonneg(x.v), x.d[0], x.d[1]}; }
  static bool is_finite(const D& x) { return B::is_finite(x.v); }
  static bool derivatives_finite(const D& x) { return B::is_finite(x.d[0]) && B::is_finite(x.d[1]); }
  static double to_double(const D& x) { return B::to_double(x.v); }
  static int exponent(const D& x) { return B::exponent(x.v); }
  static D pow_3_5(const D& x) {
    Mpfi p = B::pow_3_5(x.v);
    Mpfi f = 3 * p / (5 * x.v);
    return {p, f * x.d[0], f * x.d[1]};
  }
  static std::string to_string(const D& x) { return B::to_string(x.v); }
};

// Rounding guard: the exact value lies in [lo, hi); cut the value enclosure, keep x's
// derivatives (non-template overload: preferred over the templates of traits.hpp/dual.hpp).
inline IDual clamp_to_segment(const IDual& x, const IDual& lo, const IDual& hi) {
  return {intersect(x.v, hull(lo.v, hi.v)), x.d[0], x.d[1]};
}

// Integer part, when certain for the whole enclosure; locally constant: zero derivative.
inline Truth floor_certain(const IDual& x, IDual& out) {
  Mpfi whole(x.v.bits());
  const Truth t = floor_certain(x.v, whole);
  if (t == Truth::yes) out = IDual(whole);
  return t;
}

// The step for interval duals is instantiated once, in lib/src/verify/enclosure.cpp.
extern template class ImpactMap<IDual>;

}  // namespace bouncer
