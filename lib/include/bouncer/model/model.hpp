// The model in a chosen scalar type: the wall profile and the collision law.
//
// Units: period T = 1, amplitude A = 1, gravity g = a (paper sec. II.A). The wall height is
// a continuous periodic piecewise-linear function f(theta), theta = t mod 1. At a knot the
// wall velocity is that of the segment starting there (right-continuous): the triangle's
// velocity at theta = 1/2 is -4 and at theta = 0 is +4.
#pragma once

#include <string>
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
  int fastest_up = 0;       // the segment of largest u_j (exact): U = u_j, the fastest rise
  int fastest_down = 0;     // the segment of smallest u_j (exact): D = -u_j, the fastest fall
  std::vector<mpq_class> knot_exact;  // s_j as exact rationals (from the decimal spec)

  int segments() const { return static_cast<int>(start.size()); }
  int next(int j) const { return j + 1 == segments() ? 0 : j + 1; }

  // The segment j with s_j <= theta < s_{j+1}, decided three-valued.
  int segment_of(const T& theta) const {
    using Tr = ScalarTraits<T>;
    for (int j = segments() - 1; j > 0; --j)
      if (decide(Tr::le(start[j], theta), Reason::phase_at_corner)) return j;
    return 0;
  }
  // The same, or -1 when it is not certain (for optional shortcuts).
  int segment_if_certain(const T& theta) const {
    using Tr = ScalarTraits<T>;
    for (int j = segments() - 1; j >= 0; --j) {
      const Truth after_start = j == 0 ? Truth::yes : Tr::le(start[j], theta);
      if (after_start == Truth::yes) return certainly(Tr::lt(theta, end[j])) ? j : -1;
      if (after_start != Truth::no) return -1;
    }
    return -1;
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

// The same model with every number converted by `to` (e.g. to dual numbers, whose
// derivatives of the parameters are zero). Every field of Model and Wall is listed here and
// nowhere else, so adding a field means changing this one function.
template <class U, class T, class F>
Model<U> convert_model(const Model<T>& m, F&& to) {
  auto all = [&to](const std::vector<T>& xs) {
    std::vector<U> out;
    out.reserve(xs.size());
    for (const T& x : xs) out.push_back(to(x));
    return out;
  };
  Model<U> r{m.law, m.downward, m.bits, to(m.a), to(m.eps), to(m.c), to(m.collapse), m.veldep_collapse, Wall<U>{}};
  r.wall.start = all(m.wall.start);
  r.wall.end = all(m.wall.end);
  r.wall.height = all(m.wall.height);
  r.wall.velocity = all(m.wall.velocity);
  r.wall.turn = m.wall.turn;
  r.wall.direction = m.wall.direction;
  r.wall.top = to(m.wall.top);
  r.wall.fastest_up = m.wall.fastest_up;
  r.wall.fastest_down = m.wall.fastest_down;
  r.wall.knot_exact = m.wall.knot_exact;
  return r;
}

// The model with parameter p set to `value`. The sticking threshold `collapse` is derived
// from a and eps (as make_model builds it), so it is rebuilt here and nowhere else.
template <class T>
Model<T> with_parameter(const Model<T>& m, Parameter p, const T& value) {
  Model<T> r = m;
  (p == Parameter::a ? r.a : p == Parameter::eps ? r.eps : r.c) = value;
  r.collapse = r.a * (1 - r.eps) / 2;
  return r;
}
template <class T>
const T& parameter_of(const Model<T>& m, Parameter p) {
  return p == Parameter::a ? m.a : p == Parameter::eps ? m.eps : m.c;
}

template <class T>
struct State {
  T theta;
  T v;
  // theta is exactly wall knot s_knot (a release or corner state), or -1. An interval
  // enclosure of a knot that is not a binary fraction (0.9) cannot decide s_k <= theta by
  // itself; knowing the phase is the knot exactly keeps the next step decidable.
  int knot = -1;
};

// theta < 1 holds for the exact decimal (validated), but it may round to 1 in T (0.99999999
// 999999999999 in double): that would be a different state (phase 0 of the next period), so
// it is refused, naming the precision's limit, rather than wrapped silently.
template <class T>
State<T> make_state(const InitialCondition& ic, long bits) {
  using Tr = ScalarTraits<T>;
  State<T> s{Tr::from_decimal(ic.theta.text(), bits), Tr::from_decimal(ic.v.text(), bits)};
  if (Tr::le(Tr::from_int(1, bits), s.theta) != Truth::no)
    throw InputError("theta", "'" + ic.theta.text() + "' rounds to 1 (or may) at this precision (" +
                                  std::to_string(Tr::bits(s.theta)) + " bits): give fewer nines or more bits");
  return s;
}

// The same, recognising a start exactly at a wall knot (compared as exact rationals).
template <class T>
State<T> make_state(const Model<T>& m, const InitialCondition& ic) {
  State<T> s = make_state<T>(ic, m.bits);
  for (size_t k = 0; k < m.wall.knot_exact.size(); ++k)
    if (m.wall.knot_exact[k] == ic.theta.value()) s.knot = static_cast<int>(k);
  return s;
}

}  // namespace bouncer
