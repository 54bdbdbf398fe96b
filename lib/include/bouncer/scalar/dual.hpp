// Dual<S>: forward-mode automatic differentiation with two derivative components,
// d/dtheta0 and d/dv0, over a scalar S of the set (scalar/scalar_set.hpp). Over a point
// scalar it gives the Jacobian at a point; over an interval scalar (Dual<Mpfi>) the
// derivative components enclose the Jacobian of the branch over the whole box (every branch
// is decided for the whole box through the three-valued predicates, so the step is one
// smooth formula there; used by the Lohner enclosure, verify/enclosure.hpp).
//
// The impact map is written once as a template (model/impact_map_impl.hpp); instantiating
// it for Dual<S> differentiates exactly the branch the step takes, so the Jacobian is that
// of the same code, not of a transcription. Branches (comparisons) look at values only.
// A step is piecewise smooth: at a branch point the result is the one-sided derivative of
// the branch taken.
//
// ScalarTraits<Dual<S>> is one generic specialisation: it meets the contract of S
// (scalar/contract.hpp), PointScalar when S is a point type and IntervalScalar when S is an
// interval type; the operations of only one kind are forwarded to S's under a requires-clause.
// Conventions at the non-smooth helpers:
//   floor(x), floor_certain(x, out)  value floor, derivative zero (the integer part is
//                    locally constant); theta' = x - floor(x) therefore keeps x's derivative;
//   nonneg(x)        points: x when x >= 0, else exact zero with zero derivative;
//                    intervals: only the value enclosure is cut to [0, inf), the derivatives
//                    are kept (a square root of it then has an unbounded derivative
//                    enclosure if 0 is inside);
//   below(x)         next representable value below, derivative of x;
//   clamp(x, lo, hi) rounding guard: the exact value is inside, so the result keeps the
//                    derivative of x (only the value is moved; S's clamp moves it).
#pragma once

#include <cmath>
#include <concepts>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>

#include "bouncer/scalar/traits.hpp"

namespace bouncer {

template <class S>
class Dual {
  // Bool comparisons (and floor) exist only over a point scalar.
  static constexpr bool kComparable = !ScalarTraits<S>::is_interval;

 public:
  S v;      // value
  S d[2];   // d/dtheta0, d/dv0

  Dual() : v{}, d{S{}, S{}} {}
  // A constant (zero derivatives at the precision of the value).
  explicit Dual(S value) : v(std::move(value)), d{zero_like(v), zero_like(v)} {}
  // From three parts, each an S or anything S is built from. A part that is an expression
  // of the multiple-precision type (scalar/mpfr.hpp) is evaluated straight into its member,
  // with the roundings of a named temporary but without one (and without the move).
  template <class A, class B, class C>
    requires std::convertible_to<A&&, S> && std::convertible_to<B&&, S> && std::convertible_to<C&&, S>
  Dual(A&& value, B&& d0, C&& d1) : v(std::forward<A>(value)), d{S(std::forward<B>(d0)), S(std::forward<C>(d1))} {}
  // Parts to be assigned before they are read, at the precision `bits` where S has one
  // (blank<S>, scalar/traits.hpp), so that the assignments evaluate in place.
  static Dual blank(long bits) { return {bouncer::blank<S>(bits), bouncer::blank<S>(bits), bouncer::blank<S>(bits)}; }

  static S zero_like(const S& x) { return ScalarTraits<S>::from_int(0, ScalarTraits<S>::bits(x)); }
  // Seeds: theta0 -> (1, 0), v0 -> (0, 1).
  static Dual variable(S value, int index) {
    Dual r(std::move(value));
    r.d[index] = ScalarTraits<S>::from_int(1, ScalarTraits<S>::bits(r.v));
    return r;
  }

  Dual& operator+=(const Dual& o) { v += o.v; d[0] += o.d[0]; d[1] += o.d[1]; return *this; }
  Dual& operator-=(const Dual& o) { v -= o.v; d[0] -= o.d[0]; d[1] -= o.d[1]; return *this; }
  // Over Mpfr in place, with the MPFR calls of `*this = *this * o` in the same order (the
  // derivatives are updated before the value they read; o may be *this). Elsewhere through
  // the binary operator: a compound assignment of S need not round as its operator does.
  Dual& operator*=(const Dual& o) {
    if constexpr (!std::is_same_v<S, Mpfr>) {
      *this = *this * o;
      return *this;
    } else if (o.constant()) {
      d[0] *= o.v;
      d[1] *= o.v;
    } else if (constant()) {
      d[0] = v * o.d[0];
      d[1] = v * o.d[1];
    } else {
      S t = v * o.d[0];  // before d[0] changes (o.d[0] may be d[0])
      S u = v * o.d[1];
      d[0] *= o.v;
      d[0] += t;
      d[1] *= o.v;
      d[1] += u;
    }
    v *= o.v;
    return *this;
  }
  Dual& operator/=(const Dual& o) { *this = *this / o; return *this; }
  Dual& operator*=(long n) { v *= n; d[0] *= n; d[1] *= n; return *this; }
  Dual& operator/=(long n) { v /= n; d[0] /= n; d[1] /= n; return *this; }

  // A constant operand (both derivatives exactly zero: the model's parameters, lifted) drops
  // its derivative terms: d(x c) = c dx exactly, so this is the same derivative with fewer
  // operations (over intervals it is also never wider, and never NaN where the full formula
  // would form an unbounded value times a zero derivative). With the branch-free
  // rounding of DoubleInterval it takes the interval:double Lohner step from 64x to 39x a
  // double step (bench_certify --quick).
  bool constant() const {
    using Tr = ScalarTraits<S>;
    return Tr::is_zero(d[0]) == Truth::yes && Tr::is_zero(d[1]) == Truth::yes;
  }
  friend Dual operator+(const Dual& x, const Dual& y) {
    if (y.constant()) return {x.v + y.v, x.d[0], x.d[1]};
    if (x.constant()) return {x.v + y.v, y.d[0], y.d[1]};
    return {x.v + y.v, x.d[0] + y.d[0], x.d[1] + y.d[1]};
  }
  friend Dual operator-(const Dual& x, const Dual& y) {
    if (y.constant()) return {x.v - y.v, x.d[0], x.d[1]};
    if (x.constant()) return {x.v - y.v, -y.d[0], -y.d[1]};
    return {x.v - y.v, x.d[0] - y.d[0], x.d[1] - y.d[1]};
  }
  friend Dual operator*(const Dual& x, const Dual& y) {
    if (y.constant()) return {x.v * y.v, x.d[0] * y.v, x.d[1] * y.v};
    if (x.constant()) return {x.v * y.v, x.v * y.d[0], x.v * y.d[1]};
    return {x.v * y.v, x.d[0] * y.v + x.v * y.d[0], x.d[1] * y.v + x.v * y.d[1]};
  }
  friend Dual operator/(const Dual& x, const Dual& y) {
    S q = x.v / y.v;
    if (y.constant()) return {q, x.d[0] / y.v, x.d[1] / y.v};
    return {q, (x.d[0] - q * y.d[0]) / y.v, (x.d[1] - q * y.d[1]) / y.v};
  }
  friend Dual operator-(const Dual& x) { return {-x.v, -x.d[0], -x.d[1]}; }

  // Exact integer operands.
  friend Dual operator+(const Dual& x, long n) { return {x.v + n, x.d[0], x.d[1]}; }
  friend Dual operator+(long n, const Dual& x) { return {x.v + n, x.d[0], x.d[1]}; }
  friend Dual operator-(const Dual& x, long n) { return {x.v - n, x.d[0], x.d[1]}; }
  friend Dual operator-(long n, const Dual& x) { return {n - x.v, -x.d[0], -x.d[1]}; }
  friend Dual operator*(const Dual& x, long n) { return {x.v * n, x.d[0] * n, x.d[1] * n}; }
  friend Dual operator*(long n, const Dual& x) { return {x.v * n, x.d[0] * n, x.d[1] * n}; }
  friend Dual operator/(const Dual& x, long n) { return {x.v / n, x.d[0] / n, x.d[1] / n}; }
  friend Dual operator/(long n, const Dual& x) {
    S q = n / x.v;  // d(n/x) = -q/x dx
    S f = -(q / x.v);
    return {std::move(q), f * x.d[0], f * x.d[1]};
  }

  // Comparisons look at values only (branching never depends on derivatives). Only where S
  // has them: an interval dual, like an interval, branches through the traits alone.
  friend bool operator<(const Dual& x, const Dual& y) requires kComparable { return x.v < y.v; }
  friend bool operator<=(const Dual& x, const Dual& y) requires kComparable { return x.v <= y.v; }
  friend bool operator>(const Dual& x, const Dual& y) requires kComparable { return x.v > y.v; }
  friend bool operator>=(const Dual& x, const Dual& y) requires kComparable { return x.v >= y.v; }
  friend bool operator==(const Dual& x, const Dual& y) requires kComparable { return x.v == y.v; }
  friend bool operator!=(const Dual& x, const Dual& y) requires kComparable { return !(x.v == y.v); }

  friend Dual sqrt(const Dual& x) {
    using std::sqrt;
    S r = sqrt(x.v);
    S f = 1 / (2 * r);
    return {std::move(r), f * x.d[0], f * x.d[1]};
  }
  friend Dual exp(const Dual& x) {
    using std::exp;
    S e = exp(x.v);
    return {e, e * x.d[0], e * x.d[1]};
  }
  friend Dual log(const Dual& x) {
    using std::log;
    S f = 1 / x.v;
    return {log(x.v), f * x.d[0], f * x.d[1]};
  }
  friend Dual floor(const Dual& x) requires kComparable { return Dual(ScalarTraits<S>::floor(x.v)); }
};

template <class S>
struct ScalarTraits<Dual<S>> {
  using D = Dual<S>;
  using B = ScalarTraits<S>;
  static constexpr bool is_interval = B::is_interval;
  static constexpr const char* family = B::is_interval ? "interval-dual" : "dual";
  static constexpr long fixed_bits = B::fixed_bits;
  static D from_decimal(std::string_view text, long bits) { return D(B::from_decimal(text, bits)); }
  static D from_int(long n, long bits) { return D(B::from_int(n, bits)); }
  static long bits(const D& x) { return B::bits(x.v); }
  static Truth lt(const D& x, const D& y) { return B::lt(x.v, y.v); }
  static Truth le(const D& x, const D& y) { return B::le(x.v, y.v); }
  static Truth is_zero(const D& x) { return B::is_zero(x.v); }
  static bool likely_negative(const D& x) { return B::likely_negative(x.v); }
  static D nonneg(const D& x) {
    if constexpr (B::is_interval) return {B::nonneg(x.v), x.d[0], x.d[1]};
    else return B::likely_negative(x.v) ? D(D::zero_like(x.v)) : x;
  }
  static D clamp(const D& x, const D& lo, const D& hi) { return {B::clamp(x.v, lo.v, hi.v), x.d[0], x.d[1]}; }
  static Truth floor_certain(const D& x, D& out) {
    S whole = x.v;
    const Truth t = B::floor_certain(x.v, whole);
    if (t == Truth::yes) out = D(std::move(whole));
    return t;
  }
  static bool is_finite(const D& x) { return B::is_finite(x.v); }
  static bool derivatives_finite(const D& x) { return B::is_finite(x.d[0]) && B::is_finite(x.d[1]); }
  static double to_double(const D& x) { return B::to_double(x.v); }
  static int exponent(const D& x) { return B::exponent(x.v); }
  // d(x^(3/5)) = (3/5) x^(3/5) / x dx  (x > 0 at every impact that uses it).
  static D pow_3_5(const D& x) {
    S p = B::pow_3_5(x.v);
    S f = 3 * p / (5 * x.v);
    return {std::move(p), f * x.d[0], f * x.d[1]};
  }
  static std::string to_string(const D& x) { return B::to_string(x.v); }
  // d sin(2 pi x) = 2 pi cos(2 pi x) dx, d cos(2 pi x) = -2 pi sin(2 pi x) dx.
  static D two_pi(long bits) { return D(B::two_pi(bits)); }
  static D sin_2pi(const D& x) {
    S f = B::two_pi(B::bits(x.v)) * B::cos_2pi(x.v);
    return {B::sin_2pi(x.v), f * x.d[0], f * x.d[1]};
  }
  static D cos_2pi(const D& x) {
    S f = -(B::two_pi(B::bits(x.v)) * B::sin_2pi(x.v));
    return {B::cos_2pi(x.v), f * x.d[0], f * x.d[1]};
  }

  // Point duals only.
  static D below(const D& x) requires(!B::is_interval) { return {B::below(x.v), x.d[0], x.d[1]}; }
  static D floor(const D& x) requires(!B::is_interval) { return D(B::floor(x.v)); }
  // Interval duals only: the value's ends.
  static std::string lower_string(const D& x) requires B::is_interval { return B::lower_string(x.v); }
  static std::string upper_string(const D& x) requires B::is_interval { return B::upper_string(x.v); }
};

// The value part of a scalar: x itself, or a dual's value (its derivatives dropped); lift
// makes a value a scalar of the type again (a dual with zero derivatives). Code that solves
// for a quantity on values (the sine wall's first impact) and differentiates the solution
// afterwards uses these.
// Nested duals (second derivatives) are unwrapped to their innermost value; depth counts the
// layers.
template <class T>
struct ValueOf {
  using type = T;
  static constexpr bool is_dual = false;
  static constexpr int depth = 0;
  static const T& of(const T& x) { return x; }
  static T lift(T x) { return x; }
};
template <class S>
struct ValueOf<Dual<S>> {
  using type = typename ValueOf<S>::type;
  static constexpr bool is_dual = true;
  static constexpr int depth = ValueOf<S>::depth + 1;
  static const type& of(const Dual<S>& x) { return ValueOf<S>::of(x.v); }
  static Dual<S> lift(type x) { return Dual<S>(ValueOf<S>::lift(std::move(x))); }
};

// In-place forms of nonneg and clamp (scalar/traits.hpp's make_nonneg and
// clamp_into_segment) for duals: the results of ScalarTraits<Dual<S>>::nonneg and ::clamp
// without copying the dual.
template <class S>
void make_nonneg(Dual<S>& x) {
  using B = ScalarTraits<S>;
  if constexpr (B::is_interval) {
    make_nonneg(x.v);
  } else if (B::likely_negative(x.v)) {
    x = Dual<S>(Dual<S>::zero_like(x.v));
  }
}
template <class S>
void clamp_into_segment(Dual<S>& x, const Dual<S>& lo, const Dual<S>& hi) {
  clamp_into_segment(x.v, lo.v, hi.v);
}

// "value (d/dtheta0, d/dv0)", each part printed as its scalar type prints.
template <class S>
std::ostream& operator<<(std::ostream& os, const Dual<S>& x) {
  return os << x.v << " (d " << x.d[0] << ", " << x.d[1] << ")";
}

}  // namespace bouncer
