// The model in a chosen scalar type: the wall profile and the collision law.
//
// Units: period T = 1, amplitude A = 1, gravity g = a (paper sec. II.A). The wall height is
// a continuous periodic piecewise-linear function f(theta), theta = t mod 1. At a knot the
// wall velocity is that of the segment starting there (right-continuous): the triangle's
// velocity at theta = 1/2 is -4 and at theta = 0 is +4.
#pragma once

#include <vector>

#include "bouncer/model/spec.hpp"
#include "bouncer/scalar/traits.hpp"

namespace bouncer {

// Direction of the velocity change at the end of a segment, from exact rationals.
enum class Turn : signed char { down = -1, none = 0, up = 1 };

template <class T>
struct Wall {
  std::vector<T> start;     // s_j
  std::vector<T> end;       // s_{j+1}, with s_n = 1
  std::vector<T> height;    // f(s_j)
  std::vector<T> velocity;  // u_j on [s_j, s_{j+1})
  std::vector<Turn> turn;   // sign of u_{j+1} - u_j at the end of segment j
  std::vector<int> direction;  // sign of u_j (exact): +1 up, -1 down, 0 flat
  T top;                    // max f: above it the particle cannot meet the wall

  int segments() const { return static_cast<int>(start.size()); }
  int next(int j) const { return j + 1 == segments() ? 0 : j + 1; }

  // The segment j with s_j <= theta < s_{j+1}, decided three-valued.
  int segment_of(const T& theta) const {
    using Tr = ScalarTraits<T>;
    for (int j = segments() - 1; j > 0; --j)
      if (decide(Tr::le(start[j], theta), Reason::phase_at_corner)) return j;
    return 0;
  }
  T height_at(int j, const T& theta) const { return height[j] + velocity[j] * (theta - start[j]); }
};

template <class T>
struct Model {
  Law law;
  DownwardSticking downward;
  long bits;
  T a;
  T eps;       // Law::constant (1 for elastic)
  T c;         // Law::veldep
  T collapse;  // a (1 - eps) / 2: sticking iff relative speed <= collapse * (time left)
  bool veldep_collapse;
  Wall<T> wall;

  T zero() const { return ScalarTraits<T>::from_int(0, bits); }
};

// Every decimal is converted from its text by the scalar type (correctly rounded, or
// enclosed for intervals). `bits` is used by Mpfr and Mpfi and ignored by fixed types.
template <class T>
Model<T> make_model(const ModelSpec& spec, long bits);

template <class T>
struct State {
  T theta;
  T v;
};

template <class T>
State<T> make_state(const InitialCondition& ic, long bits) {
  using Tr = ScalarTraits<T>;
  return {Tr::from_decimal(ic.theta.text(), bits), Tr::from_decimal(ic.v.text(), bits)};
}

}  // namespace bouncer
