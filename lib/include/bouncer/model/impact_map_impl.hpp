// Definitions of the impact map templates. Included by lib/src/model/map_instances.cpp, which
// instantiates them for the supported scalar set and the duals over it (one type per
// translation unit), and by code that instantiates the map for further scalar types.
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
#include <type_traits>
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
  Wall<T>& w = m.wall;
  if (ws.shape == WallShape::sine) {
    const T zero = Tr::from_int(0, bits);
    w.shape = WallShape::sine;
    w.start = {zero};
    w.end = {one};
    w.height = {zero};
    w.velocity = {zero};
    w.turn = {Turn::none};
    w.direction = {0};
    w.top = one;
    w.two_pi = Tr::two_pi(bits);
    w.release = sine_release(m.a, w.two_pi, bits);
    return m;
  }
  const size_t n = ws.knots.size();
  size_t top = 0;
  for (size_t j = 0; j < n; ++j) {
    w.start.push_back(num(ws.knots[j]));
    w.knot_exact.push_back(ws.knots[j].value());
    w.height.push_back(num(ws.heights[j]));
    if (ws.heights[top] < ws.heights[j]) top = j;
  }
  w.top = num(ws.heights[top]);
  mpq_class u_max, u_min;
  for (size_t j = 0; j < n; ++j) {
    const size_t k = (j + 1) % n;
    w.end.push_back(k == 0 ? one : w.start[k]);
    w.velocity.push_back((w.height[k] - w.height[j]) / (w.end[j] - w.start[j]));
    // Exact: the sign of u_{j+1} - u_j from the rational knots.
    const mpq_class uj = wall_velocity_exact(ws, ws.knots[j].value());
    const mpq_class uk = wall_velocity_exact(ws, ws.knots[k].value());
    w.turn.push_back(uk < uj ? Turn::down : uk > uj ? Turn::up : Turn::none);
    w.direction.push_back(sgn(uj));
    if (j == 0 || uj > u_max) u_max = uj, w.fastest_up = static_cast<int>(j);
    if (j == 0 || uj < u_min) u_min = uj, w.fastest_down = static_cast<int>(j);
  }
  return m;
}

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
// Pieces of the walk that the common case (ImpactMap::common_step) takes before it leaves
// the flight to step(): the impact in the starting segment, in the next, or after the jump
// and up to two corners (on bench_grid's basin all but about 1e-5 of the steps).
constexpr int kCommonPieces = 4;

// The pieces of the walk, written once: step() and its common case (common_step, the lanes
// of the batched step) compute every value with these, so they agree bit for bit.

// The first zero sigma of the gap G + W s - (a/2) s^2 after s = 0 and, off the wall, the
// relative impact speed there, root_D = sqrt(W^2 + 2aG) (on the wall, G = 0 exactly, sigma
// is 2W/a and the impact speed W).
template <class T>
[[gnu::always_inline]] inline void first_zero(const T& W, const T& G, const T& a, bool on_wall, T& root_D, T& sigma) {
  using Tr = ScalarTraits<T>;
  using std::sqrt;
  if (on_wall) {
    sigma = (W + W) / a;
  } else {
    root_D = W * W + 2 * a * G;
    make_nonneg(root_D);
    root_D = sqrt(root_D);
    if (Tr::likely_negative(W)) {
      sigma = 2 * G / (root_D - W);
    } else {
      sigma = (W + root_D) / a;
    }
  }
}

// Still above the wall at the corner, L after the piece began: the gap there, free of
// cancellation: gap(L) = (a/2)(sigma* - L)(L - sigma_), sigma_ = -2G/(a sigma*) the other root.
template <class T>
[[gnu::always_inline]] inline T gap_at_corner(const T& a, const T& sigma, const T& L, const T& G, bool on_wall) {
  T gap = a * (sigma - L);
  if (on_wall) {
    gap *= L;
  } else {
    gap *= L + 2 * G / (a * sigma);
  }
  gap /= 2;
  make_nonneg(gap);
  return gap;
}

// The relative velocity W on segment k after the time L of a piece on segment j.
template <class T>
[[gnu::always_inline]] inline void onto_next_segment(T& W, const T& a, const T& L, const T& u_j, const T& u_k) {
  W -= a * L;
  W += u_j;
  W -= u_k;
}

// The fall back to the top after the particle, launched from s on segment j0, rose above
// it: the speed at the top, root = sqrt(v^2 - 2a(top - f0)), and the time of the fall back,
// tau_fall = (v + root)/a after the launch.
template <class T>
struct FallToTop {
  T root, tau_fall;
};
template <class T>
[[gnu::always_inline]] inline FallToTop<T> fall_to_top(const Model<T>& m, const State<T>& s, int j0) {
  using std::sqrt;
  const T f0 = m.wall.height_at(j0, s.theta);
  T root = s.v * s.v - 2 * m.a * (m.wall.top - f0);
  make_nonneg(root);
  root = sqrt(root);
  T tau_fall = (s.v + root) / m.a;
  return {std::move(root), std::move(tau_fall)};
}

// The phase theta_fall = x - whole of the landing on the top (x = theta + tau_fall, whole its
// floor), kept in [0, 1).
template <class T>
[[gnu::always_inline]] inline void fall_phase(T& fall, const T& x, const T& whole, const Wall<T>& wall, const T& zero) {
  fall = x - whole;
  clamp_into_segment(fall, zero, wall.end.back());
}

// The piece that begins with the landing on the top at phase fall on segment jf: the time
// left in the segment, the gap and the relative velocity.
template <class T>
[[gnu::always_inline]] inline void after_fall(const Wall<T>& wall, int jf, const T& fall, const T& root, T& L, T& G, T& W) {
  L = wall.end[jf] - fall;
  G = wall.top - wall.height_at(jf, fall);
  make_nonneg(G);
  W = -root - wall.velocity[jf];
}

// The phase of an impact sigma after a piece began at pos on segment j, kept in the segment.
template <class T>
[[gnu::always_inline]] inline T impact_phase(const T& pos, const T& sigma, const Wall<T>& wall, int j) {
  T theta = pos + sigma;
  clamp_into_segment(theta, wall.start[j], wall.end[j]);
  return theta;
}

// The sticking test of the constant-restitution model (paper sec. II.B.3, generalized to any
// segment): the relative speed `out` after an impact at theta on segment j is at most the
// collapse's reach in the time left.
template <class T>
[[gnu::always_inline]] inline Truth sticks_constant(const Model<T>& m, int j, const T& theta, const T& out) {
  return ScalarTraits<T>::le(out, m.collapse * (m.wall.end[j] - theta));
}

// Wall::segment_of and Wall::segment_if_certain for a hardware floating type, without a
// branch per knot: the count of knots s_i <= theta (i >= 1) is the largest such i, as the
// knots increase. A NaN theta counts 0 (segment_of would be undecided: the caller's next
// comparison with it fails); segment_if_certain's -1 for NaN holds (NaN < end is false).
template <class T>
[[gnu::always_inline]] inline int count_segment(const Wall<T>& wall, const T& theta) {
  const T* start = wall.start.data();
  const int n = wall.segments();
  int j = 0;
  for (int i = 1; i < n; ++i) j += start[i] <= theta;
  return j;
}
template <class T>
[[gnu::always_inline]] inline int count_segment_if_certain(const Wall<T>& wall, const T& theta) {
  const int j = count_segment(wall, theta);
  return theta < wall.end[static_cast<size_t>(j)] ? j : -1;
}

// ---- The sine wall (docs/model.md "The sine wall") ---------------------------------------
//
// A flight from phase phi (time 0) at height x with velocity xdot has the gap
//     g(s) = x + xdot s - (a/2) s^2 - sin(2 pi (phi + s)),
//     g'(s) = xdot - a s - 2 pi cos(2 pi (phi + s)),   g''(s) = -a + 4 pi^2 sin(...) >= -M,
// M = a + 4 pi^2. The impact is g's first root after the launch. Taylor's theorem with that
// bound gives, from any s = p where g(p) > 0, a root-free stretch:
//     g(p + h) >= g(p) + g'(p) h - (M/2) h^2 > 0   for 0 <= h < h*(p),
// h* the positive root of the quadratic. The search marches p -> p + h*: every stretch is
// proved root-free, and p converges to the first root from the left (quadratically where
// the root is simple; a near-tangency slows it, but only a true tangency stops it).
// A point type marches with h* itself and stops where its own rounding says g(p) <= 0 or
// p + h = p, then polishes with Newton. An interval type marches with 15/16 h* from thin
// points and checks the bound's positivity in interval arithmetic; at each point where
// g' < 0 is certain it tries to isolate the root: q = a point near p + 2 d (d = g(p) / -g'(p),
// Newton's distance), and where
// g(q) < 0 and g'(hull(p, q)) < 0 are certain the root is the unique one in hull(p, q),
// refined there by interval Newton. Where neither decides, the step is undecided (grazing).
// Where g rises like s^3 (a launch near the release phase, where g''(0) ~ 0) h* ~ sqrt(g / M)
// is much shorter than p and the march would crawl; there a third-order stretch takes over:
// with K = 8 pi^3 >= |g'''| and c = g''(p), for 0 <= s <= h
//     g(p + s) >= g(p) + g'(p) s + c' s^2,   c' = c/2 - K h/6,
// so [p, p + h] is root-free when g'(p) >= 0 and c' > 0. h = 3c/(2K) (c' = c/4; an interval
// type takes 15/16 of it and checks c' > 0) is of the order of p there: the march grows
// geometrically. It is tried where h* < p and g'(p) >= 0 only (the crawl; not the approach
// to a root, where g' < 0).
template <class V>
struct SineFlight {
  V phase, x, xdot;
};
template <class V>
V sine_gap(const SineFlight<V>& f, const V& a, const V& s) {
  return f.x + s * (f.xdot - a * s / 2) - ScalarTraits<V>::sin_2pi(f.phase + s);
}
template <class V>
V sine_gap_rate(const SineFlight<V>& f, const V& a, const V& two_pi, const V& s) {
  return f.xdot - a * s - two_pi * ScalarTraits<V>::cos_2pi(f.phase + s);
}
template <class V>
V sine_gap_curvature(const SineFlight<V>& f, const V& a, const V& two_pi, const V& s) {
  return two_pi * two_pi * ScalarTraits<V>::sin_2pi(f.phase + s) - a;
}

// Longest march (steps of the search) before the step is given up.
constexpr int kSineMarchLimit = 1 << 16;

// The first root of the flight's gap in (p, end), p given with g > 0 on (0, p] (proved by the
// caller); `end` bounds the search (the rise above the top, or the fall below the bottom):
// returns false when the march passed `end` with no root.
template <class V>
bool sine_first_root(const SineFlight<V>& f, const V& a, const V& two_pi, V p, const V& end, V& root) {
  using Tr = ScalarTraits<V>;
  using std::sqrt;
  const long bits = Tr::bits(p);
  const V zero = Tr::from_int(0, bits);
  const V M = a + two_pi * two_pi;
  // The root-free step h* from g(p) = gp > 0 and g'(p) = dp, without cancellation.
  auto safe_step = [&M](const V& gp, const V& dp) {
    V D = dp * dp + 2 * M * gp;
    make_nonneg(D);
    D = sqrt(D);
    if (Tr::likely_negative(dp)) return V(2 * gp / (D - dp));
    return V((dp + D) / M);
  };
  const V K = two_pi * two_pi * two_pi;  // >= |g'''|
  for (int it = 0;; ++it) {
    if (it > kSineMarchLimit) throw Undecided(Reason::walk_limit);
    if (certainly(Tr::le(end, p))) return false;
    const V gp = sine_gap(f, a, p), dp = sine_gap_rate(f, a, two_pi, p);
    if constexpr (!Tr::is_interval) {
      if (!(gp > zero)) break;  // at the root within this type's rounding (NaN: nonfinite later)
      V h = safe_step(gp, dp);
      if (h < p && !(dp < zero)) {
        V h3 = 3 * sine_gap_curvature(f, a, two_pi, p) / (2 * K);
        if (h3 > h) h = std::move(h3);
      }
      const V q = p + h;
      if (!(q > p)) break;
      p = q;
    } else {
      if (!certainly(Tr::lt(zero, gp))) throw Undecided(Reason::grazing);
      if (certainly(Tr::lt(dp, zero))) {
        const V d = gp / -dp;
        const V q = detail::thin_mid(V(p + 2 * d));  // a point: g(q)'s enclosure as thin as g allows
        const V X = hull(p, q);
        if (certainly(Tr::lt(sine_gap(f, a, q), zero)) && certainly(Tr::lt(sine_gap_rate(f, a, two_pi, X), zero))) {
          // Interval Newton, quadratic until rounding: stopped where a step no longer halves
          // the width (each step costs a sine and a cosine enclosure).
          V x = X;
          double w = detail::width_of(x);
          for (int k = 0; k < 8 + bits / 16; ++k) {
            const V m = detail::thin_mid(x);
            x = intersect(x, V(m - sine_gap(f, a, m) / sine_gap_rate(f, a, two_pi, x)));
            const double w_new = detail::width_of(x);
            if (!(w_new < w / 2)) break;
            w = w_new;
          }
          if (!Tr::is_finite(x)) throw Undecided(Reason::nonfinite);
          root = x;
          return true;
        }
      }
      V h = safe_step(gp, dp) * 15 / 16;
      if (!certainly(Tr::lt(zero, V(gp + h * (dp - M * h / 2))))) throw Undecided(Reason::grazing);
      if (certainly(Tr::lt(V(h * 4), p)) && certainly(Tr::le(zero, dp))) {
        // The third-order stretch, checked: c' > 0 (g' >= 0 makes the quadratic positive).
        const V cp = sine_gap_curvature(f, a, two_pi, p);
        const V h3 = detail::thin_lower(V(detail::thin_mid(cp) * 45 / (32 * detail::thin_mid(K))));
        if (certainly(Tr::lt(h, h3)) && certainly(Tr::lt(zero, V(cp / 2 - K * h3 / 6)))) h = h3;
      }
      // g > 0 is proved up to p + h; the march goes on from a point there (p + h itself
      // would widen step by step, h depending on p).
      p = detail::thin_lower(V(p + h));
    }
  }
  // Point types: Newton from where the march stopped (a step at most; a tangency stays put).
  if constexpr (!Tr::is_interval) {
    for (int k = 0; k < 3; ++k) {
      const V dp = sine_gap_rate(f, a, two_pi, p);
      if (!(dp < zero)) break;
      p -= sine_gap(f, a, p) / dp;
    }
  }
  root = p;
  return true;
}

}  // namespace detail

template <class T>
void ImpactMap<T>::sine_step(const State<T>& s, StepResult<T>& r) const {
  using Tr = ScalarTraits<T>;
  using VO = ValueOf<T>;
  using V = typename VO::type;
  using TV = ScalarTraits<V>;
  using std::sqrt;
  const Wall<T>& wall = m_.wall;
  const T& a = m_.a;
  const T& two_pi = wall.two_pi;
  r.tau = zero_;
  r.segment = 0;
  const T f0 = Tr::sin_2pi(s.theta);
  T W = s.v - wall.velocity_at(s.theta);  // the relative velocity at the launch
  if constexpr (!Tr::is_interval) make_nonneg(W);

  // The first point p0 of the search, with g > 0 on (0, p0] by Taylor's theorem at the launch
  // (|g''| <= M = a + 4 pi^2, |g'''| <= 8 pi^3, |g''''| <= 16 pi^4):
  //   launch W > 0:            g(s) >= W s - M s^2 / 2,          p0 = W / M;
  //   at rest, g''(0) = c > 0: g(s) >= c s^2 / 2 - 8 pi^3 s^3 / 6, p0 = 3c / (16 pi^3), or
  //                            the release's p0 below where that is longer (g'''(0) > 0);
  //   at the release (g = g' = g'' = 0, g''' = 8 pi^3 cos(2 pi theta_r) > 0):
  //                            g(s) >= g''' s^3 / 6 - 16 pi^4 s^4 / 24, p0 = g''' / (8 pi^4).
  const V av = VO::of(a), tp = VO::of(two_pi);
  const V tp2 = tp * tp;
  // The release's bound, for a start at rest where g'''(0) = 8 pi^3 cos(2 pi theta) > 0:
  // half of 4 g'''(0) / (16 pi^4) = 2 cos / pi.
  const auto release_p0 = [&] { return V(2 * TV::cos_2pi(VO::of(s.theta)) / tp); };
  V p0;
  // A release state (marked, or at rest exactly at the release phase: a start there, or a
  // release whose mark was lost) leaves as from the release.
  bool release = s.knot == 0;
  if (!release) {
    if (decide(Tr::is_zero(W), Reason::riding)) {
      const T curvature = -sine_gravity(s.theta);  // g''(0)
      if (decide(Tr::le(curvature, zero_), Reason::riding)) {
        if constexpr (!Tr::is_interval) release = VO::of(s.theta) == VO::of(wall.release);
        if (!release) {
          // Pressed against the wall: it rides to the release.
          r.kind = EventKind::ride;
          sine_ride(r, s.theta);
          return;
        }
      } else {
        p0 = 3 * VO::of(curvature) / (2 * tp2 * tp);
        // Where g'''(0) = 8 pi^3 cos(2 pi theta) > 0 the release's bound holds as well (its
        // c s^2 / 2 >= 0 term only adds): at rest a rounding error from theta_r, c is rounding
        // noise, and the quadratic stretch would end where the gap is below the rounding of
        // its own evaluation, so that a point type's march reported a spurious impact there.
        const V rel = release_p0();
        if (certainly(TV::lt(p0, rel))) p0 = rel;
      }
    } else {
      const V w = VO::of(W);
      if (!certainly(TV::lt(TV::from_int(0, m_.bits), w))) throw Undecided(Reason::riding);
      const V M = av + tp2;
      p0 = w / M;
      if constexpr (TV::is_interval)
        if (!certainly(TV::lt(p0, V(2 * w / M)))) throw Undecided(Reason::grazing);
    }
  }
  if (release) p0 = release_p0();

  // The flight rises above the top (1) when v^2 > 2a(1 - f0): no contact between s_up and
  // s_down = (v + R)/a, R = sqrt(v^2 - 2a(1 - f0)); the search jumps over that stretch. The
  // fall below the bottom (-1) bounds it: g < 0 there.
  const T rise = s.v * s.v - 2 * a * (1 - f0);
  const bool over_top = certainly(Tr::lt(zero_, s.v)) && certainly(Tr::lt(zero_, rise));  // rising, and above the top
  detail::SineFlight<V> flight{VO::of(s.theta), VO::of(f0), VO::of(s.v)};
  V root;
  bool jumped = false;
  T R = zero_;
  if (over_top) {
    R = sqrt(rise);
    const V s_up = 2 * (1 - flight.x) / (flight.xdot + VO::of(R));
    jumped = !detail::sine_first_root(flight, av, tp, p0, s_up, root);
  } else {
    V bottom = flight.xdot * flight.xdot + 2 * av * (flight.x + 1);
    make_nonneg(bottom);
    bottom = (flight.xdot + sqrt(bottom)) / av;
    // Past the bottom the gap is negative: the march cannot pass it.
    if (!detail::sine_first_root(flight, av, tp, p0, V(bottom * 2 + 1), root)) throw Undecided(Reason::nonfinite);
  }
  T whole = zero_, origin_phase = s.theta, origin_x = f0, origin_xdot = s.v;
  T tau_before = zero_;
  if (jumped) {
    // Land on the top at s_down, and search from there.
    const T tau_fall = (s.v + R) / a;
    const T x = s.theta + tau_fall;
    const Truth known = Tr::floor_certain(x, whole);
    if (known == Truth::invalid) throw Undecided(Reason::nonfinite);
    if (known != Truth::yes) throw Undecided(Reason::period_boundary);
    origin_phase = x - whole;
    clamp_into_segment(origin_phase, zero_, wall.end.back());
    origin_x = Tr::from_int(1, m_.bits);
    origin_xdot = -R;
    tau_before = tau_fall;
    r.periods = detail::whole_periods(whole);
    r.phase_bits_lost = std::max(0, Tr::exponent(x));
    flight = detail::SineFlight<V>{VO::of(origin_phase), TV::from_int(1, m_.bits), VO::of(origin_xdot)};
    const V g0 = TV::from_int(1, m_.bits) - TV::sin_2pi(flight.phase);
    const Truth above = TV::lt(TV::from_int(0, m_.bits), g0);
    V p_start = TV::from_int(0, m_.bits);
    if (above == Truth::yes) {
      V bottom = flight.xdot * flight.xdot + 4 * av;
      make_nonneg(bottom);
      bottom = (flight.xdot + sqrt(bottom)) / av;
      if (!detail::sine_first_root(flight, av, tp, p_start, V(bottom * 2 + 1), root)) throw Undecided(Reason::nonfinite);
    } else if (above == Truth::no && !TV::is_interval) {
      root = p_start;  // landed on a crest: the impact is the landing itself
    } else {
      throw Undecided(Reason::grazing);
    }
  }
  // The root in T: a dual is given its derivatives by a Newton step on the gap in dual
  // arithmetic (the derivatives become -g_x/g' whatever they were; each further layer of a
  // nested dual, a further order, needs one more step); for an interval dual, X - g(X)/g'(X)
  // still encloses the root and its derivatives. A point dual keeps the value's root: the
  // step uses the gap less its value (0 in the value, exactly), since the gap's value at the
  // root is rounding noise that g' ~ 0 (a launch or an impact near grazing) would turn into
  // a large move, and the dual map is the plain map on values.
  T sigma = VO::lift(std::move(root));
  const auto gap_T = [&](const T& t) {
    return T(origin_x + t * (origin_xdot - a * t / 2) - wall.height_at_phase(T(origin_phase + t)));
  };
  const auto rate_T = [&](const T& t) { return T(origin_xdot - a * t - wall.velocity_at(T(origin_phase + t))); };
  for (int k = 0; k < VO::depth; ++k) {
    T g = gap_T(sigma);
    if constexpr (!TV::is_interval) g -= VO::lift(V(VO::of(g)));
    sigma -= g / rate_T(sigma);
  }
  // The impact: its phase in [0, 1), the time, the relative speed -g'(sigma) >= 0.
  T x = origin_phase + sigma;
  T more = zero_;
  const Truth known = Tr::floor_certain(x, more);
  if (known == Truth::invalid) throw Undecided(Reason::nonfinite);
  if (known != Truth::yes) throw Undecided(Reason::period_boundary);
  r.periods += detail::whole_periods(more);
  x -= more;
  clamp_into_segment(x, zero_, wall.end.back());
  r.tau = tau_before + sigma;
  T speed = -rate_T(sigma);
  make_nonneg(speed);
  r.indirect = jumped ? Truth::yes : Truth::no;
  sine_collide(r, std::move(x), speed);
}

// A collision with the sine wall at phase theta, relative impact speed `speed`: the collision
// law, then sticking (constant eps): the chatter that follows, in the wall's frame under the
// effective gravity G = a + f''(theta) = a - 4 pi^2 sin(2 pi theta) frozen at the impact,
// collapses after 2 out / ((1 - eps) G) (the triangle's rule, where G = a); the particle
// sticks iff G > 0 and the collapse ends before the release phase, then rides to it.
template <class T>
void ImpactMap<T>::sine_collide(StepResult<T>& r, T theta, const T& speed) const {
  using Tr = ScalarTraits<T>;
  const Wall<T>& wall = m_.wall;
  const T u = wall.velocity_at(theta);
  const T out = rebound(speed);
  r.segment = 0;
  r.next.v = u + out;
  if (m_.law == Law::constant) {
    const T G = sine_gravity(theta);
    if (decide(Tr::lt(zero_, G), Reason::sticking_threshold)) {
      // G > 0 outside [theta_r, 1/2 - theta_r]: the release is the next theta_r.
      const bool before = decide(Tr::lt(theta, wall.release), Reason::sticking_threshold);
      const T left = before ? T(wall.release - theta) : T(wall.release + 1 - theta);
      if (decide(Tr::le(T(2 * out), T((1 - m_.eps) * G * left)), Reason::sticking_threshold)) {
        r.kind = EventKind::sticking;
        r.stick_segment = 0;
        r.stuck_theta = theta;
        r.stuck_v = r.next.v;
        sine_ride(r, theta);
        return;
      }
    }
  }
  r.next.theta = std::move(theta);
  r.next.knot = -1;
}

// In the sine wall's frame the particle feels the effective gravity G = a + f''(theta) =
// a - 4 pi^2 sin(2 pi theta): pressed against the wall where G > 0, thrown off where G < 0.
template <class T>
T ImpactMap<T>::sine_gravity(const T& theta) const {
  const T& tp = m_.wall.two_pi;
  return m_.a - tp * tp * ScalarTraits<T>::sin_2pi(theta);
}

template <class T>
void ImpactMap<T>::sine_ride(StepResult<T>& r, const T& from) const {
  using Tr = ScalarTraits<T>;
  const Wall<T>& wall = m_.wall;
  // At the release phase itself (a start at rest there) the ride takes no time.
  if (decide(Tr::le(from, wall.release), Reason::riding)) {
    r.tau += wall.release - from;
  } else {
    r.tau += wall.release + 1 - from;
    ++r.periods;
  }
  r.segment = 0;
  r.next = release_state(m_);  // marked: the next step starts from its Taylor bound
}

template <class T>
StepResult<T> ImpactMap<T>::step(const State<T>& s) const {
  // The result is built in place (no copy of the whole StepResult at the end); every field
  // is defined (stuck_theta and stuck_v are 0 unless the step sticks), as in step_n.
  StepResult<T> r{};
  step_into(s, r);
  return r;
}

template <class T>
template <int K>
unsigned ImpactMap<T>::step_n(const State<T>* s, StepResult<T>* out, Reason* why) const {
  static_assert(K >= 1 && K <= 32, "a lane mask of 32 bits");
  bool common[K];
  // One copy of the common case per lane (unrolled), so that each lane's branches are
  // predicted on their own and the processor sees the lanes' independent chains together.
#pragma GCC unroll 32
  for (int k = 0; k < K; ++k) common[k] = common_step(s[k], out[k]);
  unsigned failed = 0;
  for (int k = 0; k < K; ++k) {
    if (common[k]) continue;
    try {
      out[k] = step(s[k]);
    } catch (const Undecided& e) {
      failed |= 1u << k;
      why[k] = e.reason;
    }
  }
  return failed;
}

template <class T>
bool ImpactMap<T>::common_step(const State<T>& s, StepResult<T>& r) const {
  // The hardware floating types only (the others take step(): the class's explicit
  // instantiation compiles this for every type of the scalar set). Their comparisons are
  // those of ScalarTraits (yes/no, or NaN: the lane is left to step(), which decides it).
  if constexpr (!std::is_floating_point_v<T>) {
    (void)s;
    (void)r;
    return false;
  } else {
    using Tr = ScalarTraits<T>;
    const Wall<T>& wall = m_.wall;
    if (wall.smooth()) return false;
    const T a = m_.a;
    const T* start = wall.start.data();
    const T* end = wall.end.data();
    const T* velocity = wall.velocity.data();
    // A NaN theta (segment 0 here) makes L NaN: the first comparison leaves it to step().
    int j = s.knot >= 0 ? s.knot : detail::count_segment(wall, s.theta);
    const int j0 = j;
    T W = s.v - velocity[j];
    make_nonneg(W);
    if (!(W > 0)) return false;  // rides (W = 0), or NaN
    T tau = 0;
    long long periods = 0;
    int phase_bits_lost = 0;
    T pos = s.theta;  // step(): *pos
    T L = end[j] - s.theta;
    T G = 0, root_D = 0, sigma = 0;
    bool on_wall = true;
    bool jumped = false;
    bool landed = false;  // step(): pos == &fall
    for (int piece = 0;; ++piece) {
      if (piece == detail::kCommonPieces) return false;
      detail::first_zero(W, G, a, on_wall, root_D, sigma);
      if (sigma < L) break;
      if (!(L < sigma)) return false;  // the corner itself (or NaN)
      const int k = wall.next(j);
      tau += L;
      if (k == 0) ++periods;
      G = detail::gap_at_corner(a, sigma, L, G, on_wall);
      detail::onto_next_segment(W, a, L, velocity[j], velocity[k]);
      on_wall = false;
      j = k;
      pos = start[k];
      landed = false;
      L = end[k] - start[k];
      if (!jumped && wall.top < wall.height[static_cast<size_t>(j)] + G) {
        jumped = true;
        const detail::FallToTop<T> f = detail::fall_to_top(m_, s, j0);
        const T x = s.theta + f.tau_fall;
        T whole = 0;
        if (Tr::floor_certain(x, whole) != Truth::yes) return false;
        detail::fall_phase(pos, x, whole, wall, zero_);
        const int jf = detail::count_segment_if_certain(wall, pos);
        if (jf < 0) return false;
        periods = detail::whole_periods(whole);
        phase_bits_lost = std::max(0, Tr::exponent(x));
        tau = f.tau_fall;
        j = jf;
        landed = true;
        detail::after_fall(wall, j, pos, f.root, L, G, W);
      }
    }
    // Impact inside segment j (step(): its first branch, then collide()).
    if (landed && !(sigma != 0)) return false;  // perhaps on the top's corner
    const T q = on_wall ? W : root_D;
    tau += sigma;
    const T theta = detail::impact_phase(pos, sigma, wall, j);
    const Truth indirect = jumped ? Truth::yes : left_zone(s, j0, velocity[j], q);
    const T out = rebound(q);
    if (m_.law == Law::veldep && m_.veldep_collapse) return false;
    if (m_.law == Law::constant && detail::sticks_constant(m_, j, theta, out) != Truth::no) return false;
    const T v = velocity[j] + out;
    if (!Tr::is_finite(theta) || !Tr::is_finite(v)) return false;
    r.next.theta = theta;
    r.next.v = v;
    r.next.knot = -1;
    r.tau = tau;
    r.periods = periods;
    r.segment = j;
    r.kind = EventKind::impact;
    r.corner = false;
    r.indirect = indirect;
    r.stick_segment = -1;
    r.passed_upward_turn = false;
    r.stuck_theta = 0;
    r.stuck_v = 0;
    r.phase_bits_lost = phase_bits_lost;
    return true;
  }
}

template <class T>
void ImpactMap<T>::step_into(const State<T>& s, StepResult<T>& r) const {
  using Tr = ScalarTraits<T>;
  const Wall<T>& wall = m_.wall;
  const T& a = m_.a;
  const T& zero = zero_;

  if (wall.smooth()) {
    sine_step(s, r);
    if (!Tr::is_finite(r.next.theta) || !Tr::is_finite(r.next.v)) throw Undecided(Reason::nonfinite);
    return;
  }
  r.tau = zero;
  int j = s.knot >= 0 ? s.knot : wall.segment_of(s.theta);
  if constexpr (Tr::is_interval)
    if (s.knot < 0) decide(Tr::lt(s.theta, wall.end[j]), Reason::phase_at_corner);
  const int j0 = j;
  T W = s.v - wall.velocity[j];  // relative velocity as the current piece of the walk begins
  // A valid state has v >= the wall's velocity (exactly: validated input, or the map's own
  // output), but in a point type the wall velocity rounded in T may exceed v rounded in T
  // (asymmetric:0.29 and v = 200/29 rounded up): W < 0 would be a flight of negative length
  // into the wall. It is zero: the particle rides. (An interval W keeps its enclosure.)
  if constexpr (!Tr::is_interval) make_nonneg(W);
  if (decide(Tr::is_zero(W), Reason::riding)) {
    r.kind = EventKind::ride;
    ride(r, j, s.theta);
  } else {
    const T* pos = &s.theta;       // phase at which the current piece begins
    T fall = blank<T>(m_.bits);    // theta_fall after a jump (pos points here then)
    T L = wall.end[j] - s.theta;   // time left in the current segment
    T G = zero;                    // gap as the piece begins
    T root_D = blank<T>(m_.bits);  // sqrt(W^2 + 2aG) (when G > 0)
    T sigma = blank<T>(m_.bits);   // the first zero of the gap
    bool on_wall = true;           // G == 0 exactly: the root is 2W/a, the impact speed W
    bool jumped = false;
    for (long iter = 0;; ++iter) {
      if (iter > detail::kWalkLimit) throw Undecided(Reason::walk_limit);
      detail::first_zero(W, G, a, on_wall, root_D, sigma);
      const T& q = on_wall ? W : root_D;  // relative impact speed if the impact is here
      if (decide(Tr::lt(sigma, L), Reason::impact_at_corner)) {
        // Impact inside segment j.
        r.tau += sigma;
        T theta = detail::impact_phase(*pos, sigma, wall, j);
        r.indirect = jumped ? Truth::yes : left_zone(s, j0, wall.velocity[j], q);
        // Only a landing exactly on the top after a jump can have sigma = 0; it is a corner
        // impact when the top is a knot (the triangle's peak), as the walk would report.
        r.corner = pos == &fall && certainly(Tr::is_zero(sigma)) && certainly(Tr::is_zero(T(fall - wall.start[j])));
        collide(r, j, std::move(theta), q);
        break;
      }
      const int k = wall.next(j);
      r.tau += L;
      if (k == 0) ++r.periods;
      if (!decide(Tr::lt(L, sigma), Reason::impact_at_corner)) {
        // The gap closes exactly at the corner: an impact unless the particle moves away
        // from the new segment. Landing with zero relative speed is a collision of speed
        // 0, as everywhere else (the particle then moves with the wall; constant eps: it
        // sticks), so a touchdown is labelled the same whichever path finds it.
        detail::onto_next_segment(W, a, L, wall.velocity[j], wall.velocity[k]);
        if (decide(Tr::le(W, zero), Reason::corner_approach)) {
          r.corner = true;
          W = -W;  // the impact speed
          r.indirect = jumped ? Truth::yes : left_zone(s, j0, wall.velocity[k], W);
          collide(r, k, wall.start[k], W, k);
          break;
        }
        G = zero;  // grazes the corner and flies on
        on_wall = true;
      } else {
        // Still above the wall at the corner.
        G = detail::gap_at_corner(a, sigma, L, G, on_wall);
        detail::onto_next_segment(W, a, L, wall.velocity[j], wall.velocity[k]);
        on_wall = false;
      }
      j = k;
      pos = &wall.start[k];
      L = wall.end[k] - wall.start[k];
      if (!jumped && certainly(Tr::lt(wall.top, wall.height[j] + G))) {
        // Above the wall's top: no contact until the particle falls back to it, at
        // tau_fall = (v + sqrt(v^2 - 2a(top - f0)))/a after launch; jump there. The jump
        // is a shortcut: where its phase is not certain (an enclosure of theta_fall
        // straddling a period boundary or a corner), the walk simply goes on.
        jumped = true;
        const detail::FallToTop<T> f = detail::fall_to_top(m_, s, j0);
        const T x = s.theta + f.tau_fall;
        T whole = zero;
        const Truth whole_known = Tr::floor_certain(x, whole);
        if (whole_known == Truth::invalid) throw Undecided(Reason::nonfinite);
        if (whole_known == Truth::yes) {
          detail::fall_phase(fall, x, whole, wall, zero);
          const int jf = wall.segment_if_certain(fall);
          if (jf >= 0) {
            r.periods = detail::whole_periods(whole);
            r.phase_bits_lost = std::max(0, Tr::exponent(x));
            r.tau = f.tau_fall;
            j = jf;
            pos = &fall;
            detail::after_fall(wall, j, fall, f.root, L, G, W);
            on_wall = false;
            continue;
          }
        }
        // Walking a very long flight instead would only end at the walk limit.
        if (certainly(Tr::lt(Tr::from_int(detail::kLongestWalkedFlight, m_.bits), f.tau_fall)))
          throw Undecided(whole_known == Truth::yes ? Reason::phase_at_corner : Reason::period_boundary);
      }
    }
  }
  if (!Tr::is_finite(r.next.theta) || !Tr::is_finite(r.next.v)) throw Undecided(Reason::nonfinite);
}

// Whether a flight from s (on segment j0) that ends with relative impact speed q on a
// segment of velocity u left the collision zone (paper sec. II.A): iff the impact follows
// the apex (falling: v^- = u - q < 0) and the apex is above the wall's top
// (2a(top - f0) < v^2). Flights that took the jump are indirect without this test.
template <class T>
Truth ImpactMap<T>::left_zone(const State<T>& s, int j0, const T& u, const T& q) const {
  using Tr = ScalarTraits<T>;
  const Truth falling = Tr::lt(u, q);
  if (falling == Truth::no) return Truth::no;
  T f0 = m_.wall.height_at(j0, s.theta);
  f0 = m_.wall.top - f0;
  f0 *= m_.a;
  return detail::both(Tr::lt(2 * f0, s.v * s.v), falling);
}

// The collision law (paper eq. 2) in the wall's frame, written once: the map's collisions
// and the trajectory's chatter bounces (analysis/trajectory.cpp) both use it.
// Inlined into step() and each lane of step_n: in the library's instantiation unit GCC kept
// it a call, which put the lane's impact speed and result through memory on every step.
template <class T>
[[gnu::always_inline]] inline T ImpactMap<T>::rebound(const T& speed) const {
  using Tr = ScalarTraits<T>;
  using std::exp;
  T out = speed;
  if (m_.law == Law::constant) out *= m_.eps;
  if (m_.law == Law::veldep) out *= exp(-Tr::pow_3_5(speed / m_.c));
  return out;
}

// A collision of relative impact speed `speed` = |v^- - fdot| on segment j: the collision
// law, then the sticking test of the constant-restitution model.
template <class T>
void ImpactMap<T>::collide(StepResult<T>& r, int j, T theta, const T& speed, int knot,
                           std::vector<Collapse>* collapses) const {
  const Wall<T>& wall = m_.wall;
  const T out = rebound(speed);  // relative speed after the impact
  r.segment = j;
  r.next.v = wall.velocity[j] + out;
  // Sticking (paper sec. II.B.3, generalized to any segment): in the wall's frame each
  // flight lasts 2w/a and w shrinks by eps, so the collapse takes 2 out / (a (1 - eps)).
  // It completes within the segment iff out <= a (1 - eps)/2 * (time left); the paper's
  // xi_up and xi_down are this test on the triangle. "<=" rather than the paper's "<":
  // at equality the collapse ends exactly at the corner, with the same release.
  const bool sticks =
      (m_.law == Law::constant && decide(detail::sticks_constant(m_, j, theta, out), Reason::sticking_threshold)) ||
      (m_.law == Law::veldep && m_.veldep_collapse && veldep_collapse_certain(out, wall.end[j] - theta));
  if (sticks) {
    if (r.kind != EventKind::sticking) {
      r.kind = EventKind::sticking;
      r.stick_segment = j;
      r.stuck_theta = theta;
      r.stuck_v = r.next.v;
    }
    if (collapses) collapses->push_back({r.tau, out});
    ride(r, j, theta, collapses);
    return;
  }
  r.next.theta = std::move(theta);
  r.next.knot = knot;
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
  if (!certainly(Tr::lt(zero_, out))) return false;
  const T y = out / m_.c;
  const T bound = 2 * (out + 5 * m_.c * exp(2 * log(y) / 5) / 2) / m_.a;
  return certainly(Tr::le(bound, time_left));
}

// The particle moves with the wall from `from` to the end of segment j. At a downward turn
// it is released with the old wall velocity; at an upward turn the downward-sticking
// convention decides (paper: keep riding; impact: the turn is a collision).
template <class T>
void ImpactMap<T>::ride(StepResult<T>& r, int j, const T& from, std::vector<Collapse>* collapses) const {
  const Wall<T>& wall = m_.wall;
  const T* pos = &from;
  for (;;) {
    r.tau += wall.end[j] - *pos;
    const int k = wall.next(j);
    if (k == 0) ++r.periods;
    r.segment = j;
    switch (wall.turn[j]) {
      case Turn::down:
        r.next = release_state(m_, k);
        return;
      case Turn::none:
        break;
      case Turn::up:
        r.passed_upward_turn = true;
        // Only models with sticking re-collapse at the turn (paper convention).
        if (m_.downward == DownwardSticking::paper &&
            (m_.law == Law::constant || (m_.law == Law::veldep && m_.veldep_collapse)))
          break;
        r.corner = true;
        collide(r, k, wall.start[k], wall.velocity[k] - wall.velocity[j], k, collapses);
        return;
    }
    j = k;
    pos = &wall.start[k];
  }
}

// The walk of ride() again from the stuck collision, with its own tau from zero, recording
// the collapses (collide() appends one where a corner collision sticks again).
template <class T>
T ImpactMap<T>::after_sticking(const StepResult<T>& st, std::vector<Collapse>& collapses) const {
  StepResult<T> r;  // the walk's own account: tau from the stuck collision
  r.tau = zero_;
  r.kind = EventKind::sticking;
  if (m_.wall.smooth()) {
    collapses.push_back({zero_, T(st.stuck_v - m_.wall.velocity_at(st.stuck_theta))});
    sine_ride(r, st.stuck_theta);
    return r.tau;
  }
  const int j = st.stick_segment;
  collapses.push_back({zero_, T(st.stuck_v - m_.wall.velocity[j])});
  ride(r, j, st.stuck_theta, &collapses);
  return r.tau;
}

}  // namespace bouncer
