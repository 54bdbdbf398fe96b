// Definitions of the impact map templates. Included by lib/src/impact_map.cpp, which
// instantiates them for the supported scalar set, and by code that instantiates the map
// for further scalar types (dual numbers for Jacobians).
//
// The derivation (README "The model"): between impacts the gap between particle and wall
// on wall segment j, as a function of the time sigma since the segment began, is
//     gap(sigma) = G + W sigma - (a/2) sigma^2,
// where G >= 0 is the gap and W the relative velocity when the segment begins. It is a
// concave quadratic, so its first zero after sigma = 0 is the larger root
//     sigma* = (W + sqrt(W^2 + 2 a G)) / a = 2 G / (sqrt(W^2 + 2 a G) - W)
// (the first form when W >= 0, the second when W < 0: no cancellation either way), and
// the relative speed at impact is exactly sqrt(W^2 + 2 a G). The walk goes segment by
// segment; a particle above the wall's top is moved analytically to the moment it falls
// back to the top. Theta is always rebuilt as (knot + time within segment); absolute time
// is never accumulated, except that a long flight's (theta_n + flight time) mod 1 is
// unavoidable and its loss of phase bits is reported.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

#include "bouncer/model/impact_map.hpp"

namespace bouncer {

template <class T>
Model<T> make_model(const ModelSpec& spec, long bits) {
  using Tr = ScalarTraits<T>;
  auto num = [bits](const Decimal& d) { return Tr::from_decimal(d.text(), bits); };
  const T one = Tr::from_int(1, bits);
  Model<T> m{spec.law, spec.downward, bits, num(spec.a),
             spec.law == Law::constant ? num(spec.eps) : one,
             num(spec.c), Tr::from_int(0, bits), spec.veldep_collapse, Wall<T>{}};
  m.collapse = m.a * (1 - m.eps) / 2;

  const WallSpec& ws = spec.wall;
  const size_t n = ws.knots.size();
  Wall<T>& w = m.wall;
  size_t top = 0;
  for (size_t j = 0; j < n; ++j) {
    w.start.push_back(num(ws.knots[j]));
    w.knot_exact.push_back(ws.knots[j].value());
    w.height.push_back(num(ws.heights[j]));
    if (ws.heights[top] < ws.heights[j]) top = j;
  }
  w.top = num(ws.heights[top]);
  for (size_t j = 0; j < n; ++j) {
    const size_t k = (j + 1) % n;
    w.end.push_back(k == 0 ? one : w.start[k]);
    w.velocity.push_back((w.height[k] - w.height[j]) / (w.end[j] - w.start[j]));
    // Exact: the sign of u_{j+1} - u_j from the rational knots.
    const mpq_class uj = wall_velocity_exact(ws, ws.knots[j].value());
    const mpq_class uk = wall_velocity_exact(ws, ws.knots[k].value());
    w.turn.push_back(uk < uj ? Turn::down : uk > uj ? Turn::up : Turn::none);
    w.direction.push_back(sgn(uj));
  }
  return m;
}

template <class T>
struct ImpactMap<T>::Walk {
  StepResult<T> r;
};

namespace detail {

inline Truth both(Truth x, Truth y) {
  if (x == Truth::no || y == Truth::no) return Truth::no;
  if (x == Truth::yes && y == Truth::yes) return Truth::yes;
  return Truth::unknown;
}

template <class T>
long long whole_periods(const T& whole) {
  const double d = ScalarTraits<T>::to_double(whole);
  return d > 9e18 ? static_cast<long long>(9e18) : static_cast<long long>(d);
}

// Longest walk over wall segments in one flight before giving up (a far below 1e-3).
constexpr long kWalkLimit = 1L << 24;
// Flights longer than this many periods are only taken by the analytic jump.
constexpr long kLongestWalkedFlight = 64;

}  // namespace detail

template <class T>
StepResult<T> ImpactMap<T>::step(const State<T>& s) const {
  using Tr = ScalarTraits<T>;
  using std::sqrt;
  const Wall<T>& wall = m_.wall;
  const T& a = m_.a;
  const T zero = m_.zero();

  Walk w;
  w.r.tau = zero;
  int j = s.knot >= 0 ? s.knot : wall.segment_of(s.theta);
  if constexpr (Tr::is_interval)
    if (s.knot < 0) decide(Tr::lt(s.theta, wall.end[j]), Reason::phase_at_corner);
  const int j0 = j;
  const T rel = s.v - wall.velocity[j];
  if (decide(Tr::is_zero(rel), Reason::riding)) {
    w.r.kind = EventKind::ride;
    ride(w, j, s.theta);
  } else {
    T pos = s.theta;                // phase at which the current piece of the walk begins
    T L = wall.end[j] - s.theta;    // time left in the current segment
    T G = zero, W = rel;            // gap and relative velocity as the piece begins
    bool on_wall = true;            // G == 0 exactly (the root is then 2W/a)
    bool jumped = false;
    for (long iter = 0;; ++iter) {
      if (iter > detail::kWalkLimit) throw Undecided(Reason::walk_limit);
      T q = on_wall ? W : sqrt(Tr::nonneg(W * W + 2 * a * G));  // relative impact speed
      T sigma = on_wall ? 2 * W / a
                        : Tr::likely_negative(W) ? 2 * G / (q - W) : (W + q) / a;
      if (decide(Tr::lt(sigma, L), Reason::impact_at_corner)) {
        // Impact inside segment j.
        w.r.tau += sigma;
        T theta = clamp_to_segment(pos + sigma, wall.start[j], wall.end[j]);
        if (jumped) {
          w.r.indirect = Truth::yes;
        } else {
          // Left the collision zone iff the apex is above the top and the impact follows it.
          const T f0 = wall.height_at(j0, s.theta);
          w.r.indirect = detail::both(Tr::lt(2 * a * (wall.top - f0), s.v * s.v),
                                      Tr::lt(wall.velocity[j] - q, zero));
        }
        collide(w, j, std::move(theta), std::move(q));
        break;
      }
      const int k = wall.next(j);
      w.r.tau += L;
      if (k == 0) ++w.r.periods;
      if (!decide(Tr::lt(L, sigma), Reason::impact_at_corner)) {
        // The gap closes exactly at the corner: impact only if approaching the new segment.
        T Wk = W - a * L + wall.velocity[j] - wall.velocity[k];
        if (decide(Tr::lt(Wk, zero), Reason::corner_approach)) {
          w.r.corner = true;
          w.r.indirect = jumped ? Truth::yes : Truth::no;
          collide(w, k, wall.start[k], -Wk, k);
          break;
        }
        if (decide(Tr::is_zero(Wk), Reason::riding)) {  // lands with zero relative speed
          ride(w, k, wall.start[k]);
          break;
        }
        G = zero;  // grazes the corner and flies on
        W = std::move(Wk);
        on_wall = true;
      } else {
        // Still above the wall at the corner. The gap there, free of cancellation:
        // gap(L) = (a/2)(sigma* - L)(L - sigma_), sigma_ = -2G/(a sigma*) the other root.
        T gap = on_wall ? a * (sigma - L) * L / 2
                        : a * (sigma - L) * (L + 2 * G / (a * sigma)) / 2;
        W = W - a * L + wall.velocity[j] - wall.velocity[k];
        G = Tr::nonneg(gap);
        on_wall = false;
      }
      j = k;
      pos = wall.start[k];
      L = wall.end[k] - wall.start[k];
      if (!jumped && certainly(Tr::lt(wall.top, wall.height[j] + G))) {
        // Above the wall's top: no contact until the particle falls back to it, at
        // tau_fall = (v + sqrt(v^2 - 2a(top - f0)))/a after launch; jump there. The jump
        // is a shortcut: where its phase is not certain (an enclosure of theta_fall
        // straddling a period boundary or a corner), the walk simply goes on.
        jumped = true;
        const T f0 = wall.height_at(j0, s.theta);
        const T root = sqrt(Tr::nonneg(s.v * s.v - 2 * a * (wall.top - f0)));
        const T tau_fall = (s.v + root) / a;
        const T x = s.theta + tau_fall;
        T whole = zero;
        const Truth whole_known = floor_certain(x, whole);
        if (whole_known == Truth::invalid) throw Undecided(Reason::nonfinite);
        if (whole_known == Truth::yes) {
          T fall = clamp_to_segment(x - whole, zero, wall.end.back());
          const int jf = wall.segment_if_certain(fall);
          if (jf >= 0) {
            w.r.periods = detail::whole_periods(whole);
            w.r.phase_bits_lost = std::max(0, Tr::exponent(x));
            w.r.tau = tau_fall;
            j = jf;
            pos = std::move(fall);
            L = wall.end[j] - pos;
            G = Tr::nonneg(wall.top - wall.height_at(j, pos));
            W = -root - wall.velocity[j];
            on_wall = false;
            continue;
          }
        }
        // Walking a very long flight instead would only end at the walk limit.
        if (certainly(Tr::lt(Tr::from_int(detail::kLongestWalkedFlight, m_.bits), tau_fall)))
          throw Undecided(whole_known == Truth::yes ? Reason::phase_at_corner : Reason::period_boundary);
      }
    }
  }
  if (!Tr::is_finite(w.r.next.theta) || !Tr::is_finite(w.r.next.v)) throw Undecided(Reason::nonfinite);
  return std::move(w.r);
}

// The collision law (paper eq. 2) with relative impact speed `speed` = |v^- - fdot| on
// segment j, then the sticking test of the constant-restitution model.
template <class T>
void ImpactMap<T>::collide(Walk& w, int j, T theta, T speed, int knot) const {
  using Tr = ScalarTraits<T>;
  using std::exp;
  const Wall<T>& wall = m_.wall;
  // Relative speed after the impact: eps * speed.
  T out = m_.law == Law::elastic    ? std::move(speed)
          : m_.law == Law::constant ? m_.eps * speed
                                    : exp(-Tr::pow_3_5(speed / m_.c)) * speed;
  w.r.segment = j;
  w.r.next.v = wall.velocity[j] + out;
  // Sticking (paper sec. II.B.3, generalized to any segment): in the wall's frame each
  // flight lasts 2w/a and w shrinks by eps, so the collapse takes 2 out / (a (1 - eps)).
  // It completes within the segment iff out <= a (1 - eps)/2 * (time left); the paper's
  // xi_up and xi_down are this test on the triangle. "<=" rather than the paper's "<":
  // at equality the collapse ends exactly at the corner, with the same release.
  const bool sticks =
      (m_.law == Law::constant &&
       decide(Tr::le(out, m_.collapse * (wall.end[j] - theta)), Reason::sticking_threshold)) ||
      (m_.law == Law::veldep && m_.veldep_collapse && veldep_collapse_certain(out, wall.end[j] - theta));
  if (sticks) {
    if (w.r.kind != EventKind::sticking) {
      w.r.kind = EventKind::sticking;
      w.r.stick_segment = j;
      w.r.stuck_theta = theta;
      w.r.stuck_v = w.r.next.v;
    }
    ride(w, j, std::move(theta));
    return;
  }
  w.r.next.theta = std::move(theta);
  w.r.next.knot = knot;
}

// Velocity-dependent collapse (refutes the paper's sec. II.B.6): with x_n = (w_n/c)^(3/5),
// w_{n+1} = w_n exp(-x_n) gives x_{n+1} = x_n exp(-3x_n/5), so 1/x_{n+1} >= 1/x_n + 3/5 and
// w_n <= c (1/x_0 + 3n/5)^(-5/3). Summing (the tail by an integral),
//     sum_{n>=0} w_n <= w_0 + (5/2) c (w_0/c)^(2/5),
// so the chatter's total time (2/a) sum w_n is finite. When this bound is certainly below
// the time left in the segment the collapse completes there: the particle sticks. Where
// the bound does not decide, the map simply goes on bouncing (exact dynamics either way).
template <class T>
bool ImpactMap<T>::veldep_collapse_certain(const T& out, const T& time_left) const {
  using Tr = ScalarTraits<T>;
  using std::exp;
  using std::log;
  if (certainly(Tr::is_zero(out))) return true;
  if (!certainly(Tr::lt(m_.zero(), out))) return false;
  const T y = out / m_.c;
  const T bound = 2 * (out + 5 * m_.c * exp(2 * log(y) / 5) / 2) / m_.a;
  return certainly(Tr::le(bound, time_left));
}

// The particle moves with the wall from `pos` to the end of segment j. At a downward turn
// it is released with the old wall velocity; at an upward turn the downward-sticking
// convention decides (paper: keep riding; impact: the turn is a collision).
template <class T>
void ImpactMap<T>::ride(Walk& w, int j, T pos) const {
  const Wall<T>& wall = m_.wall;
  for (;;) {
    w.r.tau += wall.end[j] - pos;
    const int k = wall.next(j);
    if (k == 0) ++w.r.periods;
    w.r.segment = j;
    switch (wall.turn[j]) {
      case Turn::down:
        w.r.next = {wall.start[k], wall.velocity[j], k};
        return;
      case Turn::none:
        break;
      case Turn::up:
        w.r.passed_upward_turn = true;
        // Only models with sticking re-collapse at the turn (paper convention).
        if (m_.downward == DownwardSticking::paper &&
            (m_.law == Law::constant || (m_.law == Law::veldep && m_.veldep_collapse)))
          break;
        w.r.corner = true;
        collide(w, k, wall.start[k], wall.velocity[k] - wall.velocity[j], k);
        return;
    }
    j = k;
    pos = wall.start[k];
  }
}

}  // namespace bouncer
