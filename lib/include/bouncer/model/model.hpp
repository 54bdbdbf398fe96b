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
#include "bouncer/scalar/dual.hpp"
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
  // The sine wall f(theta) = sin(2 pi theta) (shape == sine; the vectors above then hold one
  // segment [0, 1) of velocity 0 that nothing reads for it, top = 1): 2 pi, and the release
  // phase theta_r in (0, 1/4), where the wall's acceleration -4 pi^2 sin(2 pi theta) falls to
  // -a on its way down: a particle riding the wall leaves it there (docs/model.md).
  WallShape shape = WallShape::piecewise;
  T two_pi{};
  T release{};

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
  bool smooth() const { return shape != WallShape::piecewise; }
  // The wall's height at theta, for either shape.
  T height_at_phase(const T& theta) const {
    if (smooth()) return ScalarTraits<T>::sin_2pi(theta);
    return height_at(segment_of(theta), theta);
  }
  // The wall's velocity at theta, for either shape (piecewise: right-continuous at a knot).
  T velocity_at(const T& theta) const {
    if (smooth()) return two_pi * ScalarTraits<T>::cos_2pi(theta);
    return velocity[segment_of(theta)];
  }
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
  r.wall.shape = m.wall.shape;
  r.wall.two_pi = to(m.wall.two_pi);
  r.wall.release = to(m.wall.release);
  return r;
}

namespace detail {
// A thin interval at the midpoint of an interval (interval Newton's centre).
inline Mpfi thin_mid(const Mpfi& x) {
  const Mpfr m = x.mid();
  return Mpfi(m, m);
}
inline DoubleInterval thin_mid(const DoubleInterval& x) {
  const double m = x.mid();
  return DoubleInterval(m, m);
}
// A thin interval at an interval's lower end.
inline Mpfi thin_lower(const Mpfi& x) {
  const Mpfr lo = x.lower();
  return Mpfi(lo, lo);
}
inline DoubleInterval thin_lower(const DoubleInterval& x) { return DoubleInterval(x.lower(), x.lower()); }
// An interval's width, rounded up to a double (for stopping criteria only).
inline double width_of(const Mpfi& x) {
  Mpfr w(53);
  mpfi_diam_abs(w.get(), x.get());
  return w.to_double();
}
inline double width_of(const DoubleInterval& x) { return x.upper() - x.lower(); }
}  // namespace detail

// The sine wall's release phase theta_r (Wall::release) for gravity 0 < a < 4 pi^2: the root
// of sin(2 pi theta) = a / (2 pi)^2 in (0, 1/4), where sin(2 pi theta) increases. Bisection
// on dyadic points (exact in every type) while the comparisons decide, then Newton: for an
// interval type interval Newton on the bracket, N(X) = m - h(m)/h'(X) intersected with X,
// an enclosure of the root; a dual's is its value's, with zero derivatives (a constant).
template <class T>
T sine_release(const T& a, const T& two_pi, long bits) {
  if constexpr (ValueOf<T>::is_dual) {
    using V = typename ValueOf<T>::type;
    return ValueOf<T>::lift(sine_release<V>(ValueOf<T>::of(a), ValueOf<T>::of(two_pi), bits));
  } else {
    using Tr = ScalarTraits<T>;
    const T target = a / (two_pi * two_pi);
    T lo = Tr::from_int(0, bits), step = Tr::from_int(1, bits) / 4;
    for (int i = 0; i < 48; ++i) {
      step /= 2;
      T mid = lo + step;
      const Truth below = Tr::lt(Tr::sin_2pi(mid), target);
      if (below == Truth::yes) lo = std::move(mid);
      else if (below != Truth::no) break;
    }
    if constexpr (Tr::is_interval) {
      // The bracket [lo, lo + 2 step] (or wider, after an undecided comparison: still valid).
      T x = hull(lo, T(lo + 2 * step));
      for (int i = 0; i < 24; ++i) {
        const T m = detail::thin_mid(x);
        x = intersect(x, T(m - (Tr::sin_2pi(m) - target) / (two_pi * Tr::cos_2pi(x))));
      }
      return x;
    } else {
      T t = lo + step;
      for (int i = 0; i < 6; ++i) t -= (Tr::sin_2pi(t) - target) / (two_pi * Tr::cos_2pi(t));
      return t;
    }
  }
}

// The model with parameter p set to `value`. The sticking threshold `collapse` (and the sine
// wall's release phase) derive from a and eps as make_model builds them, so they are rebuilt
// here and nowhere else.
template <class T>
Model<T> with_parameter(const Model<T>& m, Parameter p, const T& value) {
  Model<T> r = m;
  (p == Parameter::a ? r.a : p == Parameter::eps ? r.eps : r.c) = value;
  r.collapse = r.a * (1 - r.eps) / 2;
  if (r.wall.smooth() && p == Parameter::a) r.wall.release = sine_release(r.a, r.wall.two_pi, r.bits);
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

// A smooth wall's release state: at rest on the wall at its release phase theta_r, marked as
// the release (knot 0), where a stuck particle's ride ends (impact_map_impl.hpp, sine_ride).
template <class T>
State<T> release_state(const Model<T>& m) {
  return State<T>{m.wall.release, m.wall.velocity_at(m.wall.release), 0};
}

// Where a ride on a piecewise wall ends: at the downward turn at knot k, at rest on the wall,
// with the velocity of the segment that ends there (ImpactMap::ride; the certifiers start
// orbits through a sticking step here, where the state is exact). On a smooth wall, the
// release state above.
template <class T>
State<T> release_state(const Model<T>& m, int k) {
  if (m.wall.smooth()) return release_state(m);
  const int before = k == 0 ? m.wall.segments() - 1 : k - 1;
  return State<T>{m.wall.start[k], m.wall.velocity[before], k};
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
