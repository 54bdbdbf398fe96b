// Velocity-dependent restitution: the chatter on a wall segment of constant velocity
// completes in FINITE time (refutes the paper's sec. II.B.6), with an explicit bound.
//
// In the wall's frame (inertial while the wall velocity is constant) a particle leaving the
// wall with relative speed w flies for 2w/a and returns with relative speed w; the impact
// sends it off with w exp(-(w/c)^(3/5)). So the relative speeds of a chatter sequence are
//     w_0 = w,  w_{n+1} = w_n exp(-(w_n/c)^(3/5)),
// and its total remaining time is T(w) = (2/a) sum_{n>=0} w_n.
//
// Bound. With x_n = (w_n/c)^(3/5): x_{n+1} = x_n exp(-3x_n/5), so
//     1/x_{n+1} = exp(3x_n/5)/x_n >= (1 + 3x_n/5)/x_n = 1/x_n + 3/5,
// hence 1/x_n >= 1/x_0 + 3n/5 and
//     w_n = c x_n^(5/3) <= c (1/x_0 + 3n/5)^(-5/3)                 (chatter_speed_upper_bound).
// The right side decreases in n, so sum_{n>=1} <= c * integral_0^inf (1/x_0 + 3s/5)^(-5/3) ds
// = (5/2) c x_0^(2/3) = (5/2) c (w/c)^(2/5), and
//     T(w) <= B(w) = (2/a) [ w + (5/2) c^(3/5) w^(2/5) ]          (collapse_time_upper_bound).
// (The products prod_{j<n} eps_j = w_n/w_0 tend to 0, not to 1 as the paper argues; the
// bound is tight up to a constant factor: w_n ~ c (5/(3n))^(5/3).)
//
// For Mpfi the result is an enclosure of B computed with outward rounding, so
// T(w) <= result.upper() rigorously for every w, a, c in the argument intervals. For point
// types (double, long double, Quad, Mpfr) it is B rounded to nearest: an upper bound up to
// a few ulps.
#pragma once

#include <cmath>
#include <type_traits>

#include "bouncer/scalar/traits.hpp"

namespace bouncer {

namespace detail {

// y^(num/den) for y >= 0 (num/den > 0) as exp((num/den) log y), which every scalar type of
// the library provides (double, long double, Quad, Mpfr, Mpfi, DoubleInterval, Dual<...>). For an interval the
// result encloses the exact power (num/den itself enclosed); an enclosure touching 0 gives
// [0, upper^(num/den)] by monotonicity. For an interval dual whose value touches 0 the
// value is handled the same way and the derivatives are dropped (the bound is then a
// constant). Non-positive point arguments give 0.
template <class T>
T veldep_power(const T& y, long num, long den) {
  using Tr = ScalarTraits<T>;
  using std::exp;
  using std::log;
  const long bits = Tr::bits(y);
  const T zero = Tr::from_int(0, bits);
  const T e = Tr::from_int(num, bits) / den;
  if (certainly(Tr::lt(zero, y))) return exp(e * log(y));
  if constexpr (Tr::is_interval && requires { y.upper(); }) {
    // An interval type with its ends (Mpfi, DoubleInterval).
    if (certainly(Tr::le(y, zero))) return zero;
    const T up(y.upper(), y.upper());
    const T r = exp(e * log(up));
    return T(zero.lower(), r.upper());
  } else if constexpr (Tr::is_interval && requires { y.v; }) {
    return T(veldep_power(y.v, num, den));
  } else {
    // Zero is right for a point y <= 0 only: another interval type needs its enclosure here.
    static_assert(!Tr::is_interval, "veldep_power: enclose the power for this interval type");
    return zero;
  }
}

}  // namespace detail

// Upper bound B(w) = (2/a)(w + (5/2) c^(3/5) w^(2/5)) of the total remaining time of a
// velocity-dependent chatter sequence that starts with relative speed w >= 0 on a wall
// segment of constant velocity (gravity a > 0, restitution constant c > 0). B(0) = 0.
template <class T>
T collapse_time_upper_bound(const T& w, const T& a, const T& c) {
  const T y25 = detail::veldep_power(T(w / c), 2, 5);
  return 2 * (w + 5 * c * y25 / 2) / a;
}

// Upper bound c (1/x_0 + 3n/5)^(-5/3), x_0 = (w/c)^(3/5), of the relative speed after n
// impacts of the chatter starting with relative speed w (n = 0 gives w itself).
template <class T>
T chatter_speed_upper_bound(const T& w, const T& c, long n) {
  using Tr = ScalarTraits<T>;
  const long bits = Tr::bits(w);
  if (n == 0) return w;
  const T x0 = detail::veldep_power(T(w / c), 3, 5);
  if constexpr (Tr::is_interval) {
    if (certainly(Tr::is_zero(x0))) return Tr::from_int(0, bits);
  }
  const T s = 1 / x0 + Tr::from_int(3 * n, bits) / 5;  // >= 3n/5 > 0
  return c / detail::veldep_power(s, 5, 3);
}

}  // namespace bouncer
