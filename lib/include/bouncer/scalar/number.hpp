// A number computed in a run's scalar type T, held independently of T: `digits`, a decimal
// that reads back to the same T
// (what ScalarTraits<T>::to_string prints, or the exact decimal of a dyadic value where an
// output states exact parameters), so that an output prints the run's own number and a
// reader can recover it in its type; and `value`, that decimal rounded to the nearest double
// (for pictures and numpy; what a reader of the CSV gets with strtod). Grid results (run/)
// keep their numbers so.
#pragma once

#include <cstdlib>
#include <string>

#include "bouncer/scalar/traits.hpp"

namespace bouncer {

struct Number {
  double value = 0;
  std::string digits;
};

template <class T>
Number number_of(const T& x) {
  std::string d = ScalarTraits<T>::to_string(x);
  const double v = std::strtod(d.c_str(), nullptr);
  return {v, std::move(d)};
}

}  // namespace bouncer
