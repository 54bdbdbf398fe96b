// The scalar contract: what a number type must provide for the impact map (and everything
// built on it) to run in it. These concepts ARE the contract; README "The scalar contract"
// describes them in prose and must say no more and no less. Every explicit instantiation
// asserts them (scalar/scalar_set.hpp, and ImpactMap<T> itself), so a type that misses a
// piece fails at compile time with the name of the missing requirement.
//
//   Scalar<T>          every type of the set (points, intervals, duals of either):
//     values           default-constructible, copyable;
//     arithmetic       T op T and T op long, long - T, long * T, long / T (op in + - * /, an
//                      integer operand is exact), unary -, T op= T (op in + - * /),
//                      T *= long, T /= long; sqrt, exp, log found by ADL or in std;
//     ScalarTraits<T>  is_interval     constant: an enclosure type (no bool comparisons);
//                      family          the --precision name ("double", "mpfr", ...);
//                      fixed_bits      constant: significand bits of every value, or 0 when
//                                      each value carries its own precision (family:BITS);
//                      from_decimal(text, bits)  a decimal (validated before, by Decimal)
//                                      correctly rounded (points; dd: hi = RN(d) and
//                                      lo = RN(d - hi), see scalar/double_double.hpp) or
//                                      enclosed (intervals);
//                                      throws std::invalid_argument for text that is not a
//                                      number at all;
//                      from_int(n, bits)  exact (for |n| < 2^bits);
//                      bits(x)         significand bits of x;
//                      lt, le, is_zero three-valued (Truth): yes/no, unknown when an
//                                      enclosure cannot decide, invalid for NaN;
//                      likely_negative(x)  a formula choice between two algebraically equal
//                                      forms, never a model branch;
//                      nonneg(x)       x cut to [0, inf): the caller knows the exact value is
//                                      >= 0, only rounding made it negative;
//                      clamp(x, lo, hi)  x cut to [lo, hi): the caller knows the exact value
//                                      lies there (points: lo, or the number below hi);
//                      floor_certain(x, out)  yes with the integer part of x in out when it
//                                      is certain; else unknown (an enclosure whose ends have
//                                      different integer parts) or invalid (a point x that is
//                                      NaN or infinite);
//                      is_finite(x), to_double(x) (an interval: its midpoint), exponent(x)
//                                      (e with 2^(e-1) <= |x| < 2^e, 0 for 0; an interval: of
//                                      its largest magnitude), pow_3_5(x) = x^(3/5) for
//                                      x >= 0, two_pi(bits) = 2 pi, sin_2pi(x) = sin(2 pi x)
//                                      and cos_2pi(x) (the sine wall; enclosed for
//                                      intervals), to_string(x) (reads back to the same value;
//                                      an interval: "[lo, hi]" rounded outward).
//   PointScalar<T>     Scalar<T>, not an interval, with bool comparisons < <= > >= == !=
//                      and ScalarTraits<T>::below(x) (the next value below x) and
//                      ScalarTraits<T>::floor(x). The analysis layer (Newton, eigenvalues,
//                      continuation, Lyapunov exponents) needs these.
//   IntervalScalar<T>  Scalar<T>, an interval, WITHOUT bool comparisons (every branch goes
//                      through lt/le/is_zero), with ScalarTraits<T>::lower_string(x) and
//                      upper_string(x) (the ends, rounded down and up).
//
// Dual<S> (scalar/dual.hpp) composes: Dual<S> is a PointScalar when S is one, an
// IntervalScalar when S is one (scalar_set.hpp asserts both for the whole set).
#pragma once

#include <cmath>
#include <concepts>
#include <string>
#include <string_view>
#include <type_traits>

#include "bouncer/scalar/truth.hpp"

namespace bouncer {

template <class T>
struct ScalarTraits;

namespace contract_detail {

// sqrt, exp, log are looked up as the generic code does: std:: or by ADL.
using std::exp;
using std::log;
using std::sqrt;

template <class T>
concept Arithmetic = std::default_initializable<T> && std::copyable<T> &&
                     requires(T& m, const T& x, const T& y, long n) {
                       { x + y } -> std::convertible_to<T>;
                       { x - y } -> std::convertible_to<T>;
                       { x * y } -> std::convertible_to<T>;
                       { x / y } -> std::convertible_to<T>;
                       { -x } -> std::convertible_to<T>;
                       { x + n } -> std::convertible_to<T>;
                       { x - n } -> std::convertible_to<T>;
                       { n - x } -> std::convertible_to<T>;
                       { x * n } -> std::convertible_to<T>;
                       { n * x } -> std::convertible_to<T>;
                       { x / n } -> std::convertible_to<T>;
                       { n / x } -> std::convertible_to<T>;
                       m += x;
                       m -= x;
                       m *= x;
                       m /= x;
                       m *= n;
                       m /= n;
                       { sqrt(x) } -> std::convertible_to<T>;
                       { exp(x) } -> std::convertible_to<T>;
                       { log(x) } -> std::convertible_to<T>;
                     };

template <class T, class Tr = ScalarTraits<T>>
concept Traits = requires(const T& x, const T& y, const T& z, T& out, std::string_view text, long n) {
  typename std::bool_constant<Tr::is_interval>;         // a constant expression
  typename std::integral_constant<long, Tr::fixed_bits>;  // likewise
  { Tr::family } -> std::convertible_to<const char*>;
  { Tr::from_decimal(text, n) } -> std::same_as<T>;
  { Tr::from_int(n, n) } -> std::same_as<T>;
  { Tr::bits(x) } -> std::same_as<long>;
  { Tr::lt(x, y) } -> std::same_as<Truth>;
  { Tr::le(x, y) } -> std::same_as<Truth>;
  { Tr::is_zero(x) } -> std::same_as<Truth>;
  { Tr::likely_negative(x) } -> std::same_as<bool>;
  { Tr::nonneg(x) } -> std::same_as<T>;
  { Tr::clamp(x, y, z) } -> std::same_as<T>;
  { Tr::floor_certain(x, out) } -> std::same_as<Truth>;
  { Tr::is_finite(x) } -> std::same_as<bool>;
  { Tr::to_double(x) } -> std::same_as<double>;
  { Tr::exponent(x) } -> std::same_as<int>;
  { Tr::pow_3_5(x) } -> std::same_as<T>;
  { Tr::two_pi(n) } -> std::same_as<T>;
  { Tr::sin_2pi(x) } -> std::same_as<T>;
  { Tr::cos_2pi(x) } -> std::same_as<T>;
  { Tr::to_string(x) } -> std::same_as<std::string>;
};

template <class T>
concept BoolComparable = requires(const T& x, const T& y) {
  { x < y } -> std::convertible_to<bool>;
  { x <= y } -> std::convertible_to<bool>;
  { x > y } -> std::convertible_to<bool>;
  { x >= y } -> std::convertible_to<bool>;
  { x == y } -> std::convertible_to<bool>;
  { x != y } -> std::convertible_to<bool>;
};

}  // namespace contract_detail

template <class T>
concept Scalar = contract_detail::Arithmetic<T> && contract_detail::Traits<T>;

template <class T>
concept PointScalar = Scalar<T> && (!ScalarTraits<T>::is_interval) && contract_detail::BoolComparable<T> &&
                      requires(const T& x) {
                        { ScalarTraits<T>::below(x) } -> std::same_as<T>;
                        { ScalarTraits<T>::floor(x) } -> std::same_as<T>;
                      };

template <class T>
concept IntervalScalar = Scalar<T> && ScalarTraits<T>::is_interval &&
                         (!requires(const T& x, const T& y) { x < y; }) &&
                         requires(const T& x) {
                           { ScalarTraits<T>::lower_string(x) } -> std::same_as<std::string>;
                           { ScalarTraits<T>::upper_string(x) } -> std::same_as<std::string>;
                         };

}  // namespace bouncer
