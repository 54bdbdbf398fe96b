// The precision a scene asks for, and the dispatch from it to a scalar type.
#pragma once

#include <string>
#include <utility>

#include "bouncer/scalar/traits.hpp"

namespace bouncer {

struct Precision {
  enum class Kind { double_, long_double, quad, mpfr, interval } kind = Kind::double_;
  long bits = 53;  // significand bits really used
  std::string text() const;  // double | long | quad | mpfr:BITS | interval:BITS
  bool is_interval() const { return kind == Kind::interval; }
};

// Bits allowed for mpfr:BITS and interval:BITS.
constexpr long kMinBits = 16;
constexpr long kMaxBits = 1L << 20;

// Throws InputError naming `field` (see model/spec.hpp).
Precision parse_precision(const std::string& field, const std::string& text);

template <class T>
struct Tag {
  using type = T;
};

// Calls f(Tag<T>{}) with the scalar type T the precision selects.
template <class F>
decltype(auto) with_scalar(const Precision& p, F&& f) {
  switch (p.kind) {
    case Precision::Kind::double_: return f(Tag<double>{});
    case Precision::Kind::long_double: return f(Tag<long double>{});
    case Precision::Kind::quad: return f(Tag<Quad>{});
    case Precision::Kind::mpfr: return f(Tag<Mpfr>{});
    case Precision::Kind::interval: break;
  }
  return f(Tag<Mpfi>{});
}

// The same for commands that follow point orbits: an interval precision must have been
// refused before (it falls back to double here only to keep the switch total).
template <class F>
decltype(auto) with_point_scalar(const Precision& p, F&& f) {
  switch (p.kind) {
    case Precision::Kind::long_double: return f(Tag<long double>{});
    case Precision::Kind::quad: return f(Tag<Quad>{});
    case Precision::Kind::mpfr: return f(Tag<Mpfr>{});
    default: break;
  }
  return f(Tag<double>{});
}

}  // namespace bouncer
