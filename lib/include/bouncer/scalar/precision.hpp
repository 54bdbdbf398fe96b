// The precision a scene asks for, and the dispatch from it to a scalar type. Both follow
// the scalar set (scalar/scalar_set.hpp): each type of the set is one --precision family,
// named by its ScalarTraits<T>::family ("double", "long", "quad" for the types of fixed
// precision; "mpfr:BITS", "interval:BITS" for the others).
#pragma once

#include <string>
#include <tuple>
#include <type_traits>
#include <utility>

#include "bouncer/scalar/scalar_set.hpp"
#include "bouncer/scalar/traits.hpp"

namespace bouncer {

struct Precision {
  // One enumerator per type of the scalar set, named there: double_, long_double, dd, quad,
  // mpfr, interval.
#define BOUNCER_PRECISION_KIND(T, kind) kind,
  enum class Kind { BOUNCER_FOR_EACH_SCALAR(BOUNCER_PRECISION_KIND) } kind = Kind::double_;
#undef BOUNCER_PRECISION_KIND
  long bits = 53;  // significand bits really used
  std::string text() const;  // double | long | dd | quad | mpfr:BITS | interval:BITS | interval:double
  bool is_interval() const;  // an interval type (certified enclosures)
  bool is_analysis() const;  // an analysis scalar (follows one point orbit)
};

// Bits allowed for mpfr:BITS and interval:BITS.
constexpr long kMinBits = 16;
constexpr long kMaxBits = 1L << 20;

// Throws InputError naming `field` (base/error.hpp). Defined in lib/src/scalar/precision.cpp.
Precision parse_precision(const std::string& field, const std::string& text);

// The Precision::Kind of a type of the set.
template <class T>
constexpr Precision::Kind precision_kind() {
#define BOUNCER_PRECISION_KIND_OF(U, kind) if constexpr (std::is_same_v<T, U>) return Precision::Kind::kind; else
  BOUNCER_FOR_EACH_SCALAR(BOUNCER_PRECISION_KIND_OF)
#undef BOUNCER_PRECISION_KIND_OF
  static_assert(sizeof(T) == 0, "not a type of the scalar set (scalar/scalar_set.hpp)");
}

// The --precision values of a list of the set, joined: "double, long, quad, mpfr:BITS",
// with `last` before the last one (", " or " or ").
template <class Tuple>
std::string precision_names(const char* last = ", ") {
  std::string out;
  std::size_t i = 0;
  for_each_scalar<Tuple>([&](auto tag) {
    using Tr = ScalarTraits<typename decltype(tag)::type>;
    if (i > 0) out += i + 1 == std::tuple_size_v<Tuple> ? last : ", ";
    out += Tr::family;
    if (Tr::fixed_bits == 0) out += ":BITS";
    ++i;
  });
  return out;
}

// Calls f(Tag<T>{}) with the scalar type T the precision selects.
template <class F>
decltype(auto) with_scalar(const Precision& p, F&& f) {
#define BOUNCER_PRECISION_CASE(T, kind) \
  case Precision::Kind::kind: return f(Tag<T>{});
  switch (p.kind) { BOUNCER_FOR_EACH_SCALAR(BOUNCER_PRECISION_CASE) }
#undef BOUNCER_PRECISION_CASE
  return f(Tag<std::tuple_element_t<0, Scalars>>{});  // not reached: the switch is total
}

// The same for commands that follow point orbits (the analysis scalars): any other
// precision must have been refused before (it falls back to the first analysis scalar
// here only to keep the switch total).
template <class F>
decltype(auto) with_point_scalar(const Precision& p, F&& f) {
#define BOUNCER_PRECISION_CASE(T, kind) \
  case Precision::Kind::kind: return f(Tag<T>{});
  switch (p.kind) {
    BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_PRECISION_CASE)
    default: break;
  }
#undef BOUNCER_PRECISION_CASE
  return f(Tag<std::tuple_element_t<0, AnalysisScalars>>{});
}

inline bool Precision::is_interval() const {
  return with_scalar(*this, [](auto tag) { return ScalarTraits<typename decltype(tag)::type>::is_interval; });
}

inline bool Precision::is_analysis() const {
  bool in = false;
  for_each_scalar<AnalysisScalars>([&](auto tag) {
    in = in || precision_kind<typename decltype(tag)::type>() == kind;
  });
  return in;
}

}  // namespace bouncer
