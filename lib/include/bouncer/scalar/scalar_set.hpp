// The supported scalar types, listed once. Every explicit instantiation, `extern template`,
// runtime dispatch on --precision (scalar/precision.hpp) and typed-test list goes through
// the lists below, so adding a number type means: its ScalarTraits (scalar/traits.hpp,
// meeting the contract of scalar/contract.hpp) and one entry here.
//
// X-macros: BOUNCER_FOR_EACH_...(X) expands X(T, kind) for each type T of the set, kind
// being its Precision::Kind enumerator (the --precision family the type is chosen by).
// Use them as
//     #define BOUNCER_X(T, kind) template class ImpactMap<T>;
//     BOUNCER_FOR_EACH_SCALAR(BOUNCER_X)
//     #undef BOUNCER_X
// The same sets as std::tuple type lists: Scalars, PointScalars, ... (below).
#pragma once

#include <cstddef>
#include <tuple>
#include <utility>

#include "bouncer/scalar/contract.hpp"
#include "bouncer/scalar/dual.hpp"
#include "bouncer/scalar/traits.hpp"

// clang-format off
// Point types: one rounded value (bool comparisons).
#define BOUNCER_FOR_EACH_POINT_SCALAR(X) \
  X(double, double_)                     \
  X(long double, long_double)            \
  X(DoubleDouble, dd)                    \
  X(Quad, quad)                          \
  X(Mpfr, mpfr)
// Interval types: an enclosure, rounded outward (three-valued comparisons only).
#define BOUNCER_FOR_EACH_INTERVAL_SCALAR(X) \
  X(Mpfi, interval)                         \
  X(DoubleInterval, interval_double)
// clang-format on

// The whole set: the impact map and its model are instantiated for each (model/).
#define BOUNCER_FOR_EACH_SCALAR(X) BOUNCER_FOR_EACH_POINT_SCALAR(X) BOUNCER_FOR_EACH_INTERVAL_SCALAR(X)

// Named subsets, for the templates that are instantiated for part of the set only.
//
// Analysis scalars: the types that follow one point orbit through the analysis layer
// (Jacobians through ImpactMap<Dual<T>>, Newton, eigenvalues, continuation, Lyapunov
// exponents, classification; analysis/) and the commands that dispatch to it
// (with_point_scalar).
#define BOUNCER_FOR_EACH_ANALYSIS_SCALAR(X) BOUNCER_FOR_EACH_POINT_SCALAR(X)
// Enclosure scalars: the S for which the Lohner enclosure runs the step in Dual<S>
// (verify/enclosure.cpp).
#define BOUNCER_FOR_EACH_ENCLOSURE_SCALAR(X) BOUNCER_FOR_EACH_INTERVAL_SCALAR(X)

namespace bouncer {

// A type as a value, for dispatch: f(Tag<T>{}) and then typename decltype(tag)::type.
template <class T>
struct Tag {
  using type = T;
};

namespace scalar_set_detail {
template <class Void, class... T>
struct List {
  using type = std::tuple<T...>;
};
template <class Tuple>
struct Duals;
template <class... S>
struct Duals<std::tuple<S...>> {
  using type = std::tuple<Dual<S>...>;
};
}  // namespace scalar_set_detail

#define BOUNCER_SCALAR_SET_ITEM(T, kind) , T
using Scalars = scalar_set_detail::List<void BOUNCER_FOR_EACH_SCALAR(BOUNCER_SCALAR_SET_ITEM)>::type;
using PointScalars = scalar_set_detail::List<void BOUNCER_FOR_EACH_POINT_SCALAR(BOUNCER_SCALAR_SET_ITEM)>::type;
using IntervalScalars = scalar_set_detail::List<void BOUNCER_FOR_EACH_INTERVAL_SCALAR(BOUNCER_SCALAR_SET_ITEM)>::type;
using AnalysisScalars = scalar_set_detail::List<void BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_SCALAR_SET_ITEM)>::type;
using EnclosureScalars = scalar_set_detail::List<void BOUNCER_FOR_EACH_ENCLOSURE_SCALAR(BOUNCER_SCALAR_SET_ITEM)>::type;
#undef BOUNCER_SCALAR_SET_ITEM

// Dual<S> for each S of a list.
template <class Tuple>
using DualsOf = typename scalar_set_detail::Duals<Tuple>::type;

// f(Tag<T>{}) for each T of a list, in order.
template <class Tuple, class F>
constexpr void for_each_scalar(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f(Tag<std::tuple_element_t<I, Tuple>>{}), ...);
  }(std::make_index_sequence<std::tuple_size_v<Tuple>>{});
}

// The contract (scalar/contract.hpp) holds for every type of the set and for the duals
// over it; a type that misses a piece stops the build here, naming the concept.
#define BOUNCER_SCALAR_SET_ASSERT_POINT(T, kind) \
  static_assert(PointScalar<T> && PointScalar<Dual<T>>, #T ": a point scalar must meet PointScalar (scalar/contract.hpp)");
#define BOUNCER_SCALAR_SET_ASSERT_INTERVAL(T, kind) \
  static_assert(IntervalScalar<T> && IntervalScalar<Dual<T>>, #T ": an interval scalar must meet IntervalScalar (scalar/contract.hpp)");
BOUNCER_FOR_EACH_POINT_SCALAR(BOUNCER_SCALAR_SET_ASSERT_POINT)
BOUNCER_FOR_EACH_INTERVAL_SCALAR(BOUNCER_SCALAR_SET_ASSERT_INTERVAL)
// The analysis layer compares and floors values: its types are point types.
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_SCALAR_SET_ASSERT_POINT)
// The enclosure runs Dual<S> over boxes: S is an interval type.
BOUNCER_FOR_EACH_ENCLOSURE_SCALAR(BOUNCER_SCALAR_SET_ASSERT_INTERVAL)
#undef BOUNCER_SCALAR_SET_ASSERT_POINT
#undef BOUNCER_SCALAR_SET_ASSERT_INTERVAL

}  // namespace bouncer
