// The trapping region: the top V of a strip {f'(theta) <= v <= V} that every orbit enters
// and never leaves (paper sec. II.C), for every wall and every collision law. Every command
// and test takes it from here: the default v range of basin and scan, the spread of
// lyapunov's starts, the guesses of the periodic-orbit search.
//
// U = the wall's fastest upward velocity, D = its fastest downward speed (U = D = 4 on the
// triangle, 2 pi on the sine wall). Lemma (proofs/trapping_region.cpp has it for the triangle): a flight from
// velocity v that meets the wall arrives with v^- >= -(v + 2D), because the wall cannot fall
// faster than D while the particle falls; so the relative speed at an impact on a segment
// of velocity u <= U is w = u - v^- <= U + 2D + v, and the particle leaves with
// v' = u + eps(w) w <= U + eps(w) w. A release after sticking or riding leaves at a wall
// velocity, at most U.
//
//  * constant eps < 1: V = (U + eps (U + 2D)) / (1 - eps) is forward invariant and attracts
//    geometrically (v' - V <= eps (v - V)); on the triangle 4(1 + 3 eps)/(1 - eps), sharp.
//    eps = 1 (elastic) has none: velocities grow without bound.
//  * eps(w) = exp(-(w/c)^(3/5)): the outgoing relative speed h(w) = w eps(w) is largest at
//    w_m = c (5/3)^(5/3), h_max = w_m e^(-5/3), so v' <= U + h_max after any impact: that
//    top is always invariant and reached at the first impact. The paper's
//    V_c = (U + E (U + 2D)) / (1 - E), E = eps(U + D) (on the triangle 4[2 coth(2^(4/5) /
//    c^(3/5)) - 1]) is the top when it is invariant, i.e. when
//    U + h(min(U + 2D + V_c, w_m)) <= V_c; it is not for small c (proofs/trapping_region:
//    certified counterexamples at c = 1/2 and 1/10), and then U + h_max is.
//
// In an interval type every comparison is decided with outward rounding (an undecided one
// takes the always-valid branch), so the result encloses a proved top; in a point type it
// is that top rounded, as accurate as the type.
#pragma once

#include <optional>
#include <utility>

#include "bouncer/model/model.hpp"
#include "bouncer/scalar/decimal.hpp"

namespace bouncer {

// The sine wall's speeds are at most 2 pi both ways.
template <class T>
T wall_up_speed(const Wall<T>& w) {
  return w.smooth() ? w.two_pi : w.velocity[w.fastest_up];
}
template <class T>
T wall_down_speed(const Wall<T>& w) {
  return w.smooth() ? w.two_pi : -w.velocity[w.fastest_down];
}

// The top V, or nothing for the elastic map (and for constant eps not certainly below 1).
template <class T>
std::optional<T> trapping_top(const Model<T>& m) {
  using Tr = ScalarTraits<T>;
  using std::exp;
  using std::log;
  const T one = Tr::from_int(1, m.bits);
  const T U = wall_up_speed(m.wall), D = wall_down_speed(m.wall);
  if (m.law == Law::constant) {
    if (!certainly(Tr::lt(m.eps, one))) return std::nullopt;
    return (U + m.eps * (U + 2 * D)) / (1 - m.eps);
  }
  if (m.law != Law::veldep) return std::nullopt;
  // V_c with E = exp(-2x), 2x = ((U + D)/c)^(3/5); written so that on the triangle
  // (U + D = 8, ((U + D)/8)^(3/5) = 1 exactly) it is the paper's 4[2 coth(x) - 1] as
  // (e + 1)/(e - 1) = coth x, e = exp(2x), operation for operation.
  const T x = exp(log(one * 2) * 4 / 5) * Tr::pow_3_5((U + D) / 8) / Tr::pow_3_5(m.c);
  const T e = exp(2 * x);
  const T v_c = U * (2 * (e + 1) / (e - 1) - 1) + 2 * (D - U) / (e - 1);
  const T five_thirds = one * 5 / 3;
  const T w_m = m.c * exp(log(five_thirds) * five_thirds);
  const T h_max = w_m * exp(-five_thirds);
  const T w = U + 2 * D + v_c;
  const T h = certainly(Tr::le(w, w_m)) ? w * exp(-Tr::pow_3_5(w / m.c)) : h_max;
  if (certainly(Tr::le(U + h, v_c))) return v_c;
  return U + h_max;
}

// The same for the model's own parameters, exactly where that is possible: the constant
// law's top as a rational (nothing for the other laws, or eps = 1).
std::optional<mpq_class> trapping_top_exact(const ModelSpec& m);

// The default v range of the grid commands (basin, and its certified twin): from the wall's
// fastest upward velocity to the trapping top, rounded up to 4 decimals so that it is an
// exact decimal that still covers the region (exactly for the constant law; from double
// with a relative margin of 1e-12 for the velocity-dependent law). Nothing for the elastic
// map and constant eps = 1.
std::optional<std::pair<Decimal, Decimal>> trapping_v_range(const ModelSpec& m);

}  // namespace bouncer
