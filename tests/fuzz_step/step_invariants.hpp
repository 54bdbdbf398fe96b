// The invariants of one step of the impact map, computed independently of the map: shared by
// bouncer-fuzz-step (tests/fuzz_step/fuzz_step.cpp: random parameters and starts) and the libFuzzer
// target tests/fuzz/fuzz_step.cpp (parameters and starts decoded from the fuzzer's bytes),
// so both check one copy of the truth.
//
//   tau > 0            the step takes time (T arithmetic)
//   theta in [0, 1)    the next phase (T arithmetic)
//   v >= wall          the next velocity is at least the wall's at the next phase (T model:
//                      the segment of theta_next found by the T wall, its velocity)
//   no penetration     the free flight y(t) = f(theta0) + v0 t - (a/2) t^2 is never below the
//                      wall f(theta0 + t) before the flight ends. The gap y - f is concave on
//                      each wall segment, so it is checked at every knot crossed in flight
//                      (where a flight's middle stays above the wall's top, checked by
//                      concavity at its two ends), plus at sampled times
//   impact on wall     the flight ends where y = f (impact kind; for a sticking step the
//                      first collision, at the reported phase stuck_theta)
//   collision law      the post-impact relative speed is e(q) q for the impact speed q
//                      (eq. 2: e = eps, 1, or exp(-(q/c)^(3/5)))
//
// The checks use the exact model (from the same decimal parameters) in MPFR at
// max(256, 2 bits + 64) bits, the step's numbers converted exactly; a check fails when the
// error exceeds 2^(10 - bits) times the scale of what is compared: for a gap at flight time
// t, (|v0| + a (t + 1) + max |u|) (1 + t) + the wall's heights (a time off by a relative
// 2^-bits moves the gap by the relative speed times that time); for a velocity,
// |v0| + a (t + 1) + max |u|, each wall velocity |u| weighted by its condition number in the
// rounded knots and heights (a segment 0.825..0.826 loses 10 bits of its velocity in T).
// A violation names the first invariant that fails, with its numbers.
#pragma once

#include <gmpxx.h>
#include <mpfr.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"

namespace bouncer::step_check {

// ---- deterministic random numbers (raw mt19937_64 bits; no std distributions) ----------
struct Rng {
  std::mt19937_64 g;
  explicit Rng(uint64_t seed) : g(seed) {}
  double u01() { return static_cast<double>(g() >> 11) * 0x1p-53; }
  size_t below(size_t n) { return static_cast<size_t>(g() % n); }
  bool chance(double p) { return u01() < p; }
  double log_uniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * u01()); }
};

inline std::string decimal_text(double x, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*g", digits, x);
  return b;
}
inline Decimal dec(const std::string& s) { return *Decimal::parse(s); }

// A rational as a decimal >= it: exact when it has one, else 30 significant digits rounded up.
inline Decimal decimal_at_least(const mpq_class& q) {
  mpz_class den = q.get_den();
  while (mpz_divisible_ui_p(den.get_mpz_t(), 2)) den /= 2;
  while (mpz_divisible_ui_p(den.get_mpz_t(), 5)) den /= 5;
  if (den == 1) {
    // Exact: scale by 10^k until integral.
    mpq_class x = q;
    int k = 0;
    while (mpz_class(x.get_den()) != 1) {
      x *= 10;
      ++k;
    }
    std::string digits = mpz_class(x.get_num()).get_str();
    return dec(digits + "e-" + std::to_string(k));
  }
  mpfr_t r;
  mpfr_init2(r, 200);
  mpfr_set_q(r, q.get_mpq_t(), MPFR_RNDU);
  char buf[128];
  mpfr_snprintf(buf, sizeof buf, "%.30RUe", r);
  mpfr_clear(r);
  Decimal d = dec(buf);
  return d;
}

// ---- exact conversion of a step's numbers to MPFR ------------------------------------
inline Mpfr hp(double x, long bits) {
  Mpfr r(bits);
  mpfr_set_d(r.get(), x, MPFR_RNDN);
  return r;
}
inline Mpfr hp(long double x, long bits) {
  Mpfr r(bits);
  mpfr_set_ld(r.get(), x, MPFR_RNDN);
  return r;
}
inline Mpfr hp(const Quad& x, long bits) {
  // 113 bits = at most three doubles, each difference exact in Quad.
  Mpfr r(bits), part(bits);
  Quad rest = x;
  mpfr_set_zero(r.get(), 1);
  for (int i = 0; i < 3; ++i) {
    const double d = static_cast<double>(rest);
    mpfr_set_d(part.get(), d, MPFR_RNDN);
    mpfr_add(r.get(), r.get(), part.get(), MPFR_RNDN);
    rest -= Quad(d);
  }
  return r;
}
inline Mpfr hp(const DoubleDouble& x, long bits) {
  // hi + lo: exact when bits covers the pair's span (about 106 bits for the map's values).
  Mpfr r(bits);
  mpfr_set_d(r.get(), x.hi(), MPFR_RNDN);
  mpfr_add_d(r.get(), r.get(), x.lo(), MPFR_RNDN);
  return r;
}
inline Mpfr hp(const Mpfr& x, long bits) {
  Mpfr r(bits);
  mpfr_set(r.get(), x.get(), MPFR_RNDN);
  return r;
}

// ---- the independent checker ---------------------------------------------------------
enum Invariant { kTau, kTheta, kVelocity, kPenetration, kOnWall, kLaw, kException, kInvariants };
inline const char* const kInvariantNames[] = {"tau > 0", "theta in [0, 1)", "v >= wall velocity", "no penetration",
                                 "impact on the wall", "collision law", "unexpected exception"};

struct Violation {
  Invariant what;
  std::string detail;
};

// The exact model at high precision, and the flight y(t) from a start.
class Exact {
 public:
  Exact(const ModelSpec& spec, long bits) : m_(make_model<Mpfr>(spec, bits)), bits_(bits) {
    hmin_ = m_.wall.height[0];
    hmax_ = m_.wall.height[0];
    for (const Mpfr& h : m_.wall.height) {
      if (h < hmin_) hmin_ = h;
      if (hmax_ < h) hmax_ = h;
    }
    habs_ = abs(hmin_) < abs(hmax_) ? Mpfr(abs(hmax_)) : Mpfr(abs(hmin_));
    // max |u_j| (1 + the condition number of u_j = (h_k - h_j) / (s_k - s_j) in the knots'
    // and heights rounded to T: a short segment, or close heights, cost relative accuracy).
    umax_ = num(0);
    const Wall<Mpfr>& w = m_.wall;
    for (int j = 0; j < w.segments(); ++j) {
      const int k = w.next(j);
      Mpfr kappa = Mpfr(abs(w.start[j]) + abs(w.end[j])) / Mpfr(w.end[j] - w.start[j]);
      kappa += Mpfr(abs(w.height[j]) + abs(w.height[k])) / Mpfr(abs(Mpfr(w.height[k] - w.height[j])));
      kappa += num(2);
      Mpfr u = abs(w.velocity[j]) * kappa;
      if (umax_ < u) umax_ = u;
    }
  }
  long bits() const { return bits_; }
  const Model<Mpfr>& model() const { return m_; }
  Mpfr num(long n) const { return Mpfr(n, bits_); }

  int segment(const Mpfr& phase) const {
    for (int j = m_.wall.segments() - 1; j > 0; --j)
      if (m_.wall.start[j] <= phase) return j;
    return 0;
  }
  Mpfr frac(const Mpfr& x) const {
    Mpfr f = floor(x);
    return Mpfr(x - f);
  }
  Mpfr wall_at(const Mpfr& theta) const {
    const Mpfr ph = frac(theta);
    return m_.wall.height_at(segment(ph), ph);
  }

  // The free flight from (theta0, v0) on the wall.
  struct Flight {
    Mpfr theta0, v0, f0;
  };
  Flight flight(const Mpfr& theta0, const Mpfr& v0) const { return Flight{theta0, v0, wall_at(theta0)}; }
  Mpfr height(const Flight& f, const Mpfr& t) const {
    Mpfr y = f.v0 * t;
    y += f.f0;
    Mpfr fall = m_.a * t;
    fall *= t;
    fall /= 2;
    y -= fall;
    return y;
  }
  Mpfr gap(const Flight& f, const Mpfr& t) const {
    Mpfr th = f.theta0 + t;
    return Mpfr(height(f, t) - wall_at(th));
  }
  // Error scale of a gap at flight time t computed from the step's numbers: a time (or
  // phase) off by a relative 2^-bits moves the gap by the relative speed times
  // (1 + t) 2^-bits; heights by their size times 2^-bits.
  Mpfr scale(const Flight& f, const Mpfr& t) const {
    Mpfr t1 = t + 1;
    Mpfr s = speed_scale(f, t);
    s *= t1;
    s += habs_;
    s += abs(f.f0);
    s += num(1);
    return s;
  }
  // Bound on the relative speed up to time t, |v0| + a (t + 1) + max |u|, with the wall
  // velocities weighted by their condition number (above).
  Mpfr speed_scale(const Flight& f, const Mpfr& t) const {
    Mpfr s = abs(f.v0);
    Mpfr at = m_.a * (t + 1);
    s += at;
    s += umax_;
    return s;
  }
  // Times where y(t) = h on the way down (the larger root), or nullopt if never reached.
  std::optional<Mpfr> descend_to(const Flight& f, const Mpfr& h) const {
    Mpfr d = f.v0 * f.v0;
    Mpfr two_a = 2 * m_.a;
    Mpfr drop = h - f.f0;
    drop *= two_a;
    d -= drop;
    if (d < num(0)) return std::nullopt;
    d = sqrt(d);
    return Mpfr((f.v0 + d) / m_.a);
  }
  std::optional<Mpfr> ascend_to(const Flight& f, const Mpfr& h) const {
    Mpfr d = f.v0 * f.v0;
    Mpfr drop = h - f.f0;
    drop *= 2 * m_.a;
    d -= drop;
    if (d < num(0)) return std::nullopt;
    d = sqrt(d);
    return Mpfr((f.v0 - d) / m_.a);
  }
  const Mpfr& hmin() const { return hmin_; }
  const Mpfr& hmax() const { return hmax_; }

  // e(q) q, the relative speed after an impact of relative speed q (eq. 2).
  Mpfr rebound(const Mpfr& q) const {
    switch (m_.law) {
      case Law::elastic: return q;
      case Law::constant: return Mpfr(q * m_.eps);
      case Law::veldep: break;
    }
    if (!(num(0) < q)) return q;
    Mpfr x = log(Mpfr(q / m_.c));
    x *= 3;
    x /= 5;
    x = exp(x);
    return Mpfr(q * exp(-x));
  }

 private:
  Model<Mpfr> m_;
  long bits_;
  Mpfr hmin_, hmax_, habs_, umax_;
};

template <class T>
class Checker {
 public:
  // touch_budget: the periods a sticking step's first collision is looked for in (beyond
  // them the step is counted in `unchecked`, not as a violation).
  Checker(const ModelSpec& spec, const Model<T>& model, long hp_bits, Rng& rng, long long touch_budget = 1000000)
      : ex_(spec, hp_bits), model_(model), rng_(rng), touch_budget_(touch_budget) {}

  // Flights too long to check: too low to check every knot, or a sticking step whose first
  // collision lies beyond a million periods (a in 1e-20, say: no phase bits left in T).
  long long unchecked = 0;

  std::optional<Violation> check(const State<T>& s, const StepResult<T>& r) {
    using Tr = ScalarTraits<T>;
    const T zero = model_.zero();
    const T one = Tr::from_int(1, model_.bits);
    if (!(zero < r.tau)) return Violation{kTau, "tau = " + Tr::to_string(r.tau)};
    if (!(zero <= r.next.theta && r.next.theta < one))
      return Violation{kTheta, "theta_next = " + Tr::to_string(r.next.theta)};
    const int jn = r.next.knot >= 0 ? r.next.knot : model_.wall.segment_of(r.next.theta);
    if (r.next.v < model_.wall.velocity[jn])
      return Violation{kVelocity, "v_next = " + Tr::to_string(r.next.v) + " < wall velocity " +
                                      Tr::to_string(model_.wall.velocity[jn]) + " on segment " + std::to_string(jn)};
    // No free flight: a start moving with the wall rides it (and, with the impact convention,
    // may collide at an upward turn and stick there).
    const int j0 = s.knot >= 0 ? s.knot : model_.wall.segment_of(s.theta);
    if (r.kind == EventKind::ride || s.v <= model_.wall.velocity[j0]) return std::nullopt;

    const long H = ex_.bits();
    // A state at a knot (s.knot) is exactly at the knot, whatever T's rounding of it.
    const auto f = ex_.flight(s.knot >= 0 ? ex_.model().wall.start[s.knot] : hp(s.theta, H), hp(s.v, H));
    const long bits = Tr::bits(s.v);
    // The end of the free flight: the step's time for an impact; for a sticking step the
    // first collision, at phase stuck_theta (found below, independently of tau).
    Mpfr t_end(H);
    if (r.kind == EventKind::impact) {
      t_end = hp(r.tau, H);
    } else {
      auto t1 = first_touch(f, hp(r.stuck_theta, H), ex_.model().wall.velocity[r.stick_segment], hp(r.tau, H), bits);
      if (!t1 && touch_budget_spent_) {
        ++unchecked;
        return std::nullopt;
      }
      if (!t1) return Violation{kOnWall, "no point of the free flight at stuck_theta " + Tr::to_string(r.stuck_theta) +
                                             " is on the wall (tau " + Tr::to_string(r.tau) + ")"};
      t_end = *t1;
    }
    const Mpfr tol = tolerance(f, t_end, bits);
    // Impact on the wall.
    const Mpfr g_end = ex_.gap(f, t_end);
    if (tol < abs(g_end))
      return Violation{kOnWall, "gap at the end of the flight " + text(g_end) +
                                    " (tolerance " + text(tol) + ")"};
    // No penetration: knots crossed in flight and sampled times.
    if (auto v = penetration(f, t_end, tol)) return v;
    // Collision law: q = u - v^-, after the impact v - u = e(q) q.
    const int seg = r.kind == EventKind::impact ? r.segment : r.stick_segment;
    const Mpfr& u = ex_.model().wall.velocity[seg];
    Mpfr vminus = ex_.model().a * t_end;
    vminus = f.v0 - vminus;
    const Mpfr q = u - vminus;
    const Mpfr out_expected = ex_.rebound(q);
    Mpfr out = hp(r.kind == EventKind::impact ? r.next.v : r.stuck_v, H);
    out -= u;
    const Mpfr tol_v = ulps(ex_.speed_scale(f, t_end), bits);
    if (tol_v < abs(Mpfr(out - out_expected)))
      return Violation{kLaw, "relative speed after impact " + text(out) + ", law gives " + text(out_expected) +
                                 " for impact speed " + text(q)};
    return std::nullopt;
  }

  static std::string text(const Mpfr& x) {
    char buf[64];
    mpfr_snprintf(buf, sizeof buf, "%.17Rg", x.get());
    return buf;
  }

 private:
  Exact ex_;
  const Model<T>& model_;
  Rng& rng_;
  long long touch_budget_;
  bool touch_budget_spent_ = false;  // first_touch gave up: more periods than its budget

  Mpfr ulps(const Mpfr& scale, long bits) const {
    Mpfr t = scale;
    mpfr_mul_2si(t.get(), t.get(), 10 - bits, MPFR_RNDN);
    return t;
  }
  Mpfr tolerance(const Exact::Flight& f, const Mpfr& t_end, long bits) const {
    return ulps(ex_.scale(f, t_end), bits);
  }

  // The first t in (0, t_max] with phase theta0 + t = phase (mod 1) and a collision there
  // with the wall segment of velocity u. Candidates are limited to the times where the
  // flight is within the wall's height band.
  std::optional<Mpfr> first_touch(const Exact::Flight& f, const Mpfr& phase, const Mpfr& u, const Mpfr& t_max,
                                  long bits) {
    touch_budget_spent_ = false;
    // A collision: on the wall, approaching it (v^- = v0 - a t <= u, within rounding).
    auto collision = [&](const Mpfr& t) {
      if (tolerance(f, t, bits) < abs(ex_.gap(f, t))) return false;
      Mpfr approach = ex_.model().a * t;
      approach = f.v0 - approach;
      approach -= u;
      return approach <= ulps(ex_.speed_scale(f, t), bits);
    };
    const Mpfr tol = tolerance(f, t_max, bits);
    const Mpfr top = ex_.hmax() + tol, bottom = ex_.hmin() - tol;
    const auto t_bottom = ex_.descend_to(f, bottom);
    if (!t_bottom) return std::nullopt;
    std::vector<std::pair<Mpfr, Mpfr>> windows;
    const auto up = ex_.ascend_to(f, top), down = ex_.descend_to(f, top);
    if (up && down) {
      windows.push_back({ex_.num(0), *up});
      windows.push_back({*down, *t_bottom});
    } else {
      windows.push_back({ex_.num(0), *t_bottom});
    }
    const Mpfr d = ex_.frac(Mpfr(phase - f.theta0));
    // The collision at the start's own phase in T (d within rounding of 0 or 1): a flight
    // shorter than the phase's resolution, 2 W / a on the start's segment, W = v0 - u.
    Mpfr near = Mpfr(1 - d) < d ? Mpfr(1 - d) : d;
    mpfr_mul_2si(near.get(), near.get(), bits - 10, MPFR_RNDN);
    if (near <= ex_.num(1)) {
      Mpfr w = f.v0 - ex_.model().wall.velocity[ex_.segment(ex_.frac(f.theta0))];
      if (w < ex_.num(0)) w = ex_.num(0);
      Mpfr t = 2 * w / ex_.model().a;
      if (collision(t)) return t;
    }
    long long budget = touch_budget_;
    for (const auto& [lo, hi] : windows) {
      Mpfr kf = ceil_of(Mpfr(lo - d));
      if (kf < ex_.num(0)) kf = ex_.num(0);
      for (Mpfr t = d + kf; t <= hi && t <= t_max + tol; t = t + 1) {
        if (--budget < 0) {
          touch_budget_spent_ = true;
          return std::nullopt;
        }
        if (!(ex_.num(0) < t)) continue;
        if (collision(t)) return t;
      }
    }
    return std::nullopt;
  }
  Mpfr ceil_of(const Mpfr& x) const {
    Mpfr r = x;
    mpfr_ceil(r.get(), x.get());
    return r;
  }

  std::optional<Violation> penetration(const Exact::Flight& f, const Mpfr& t_end, const Mpfr& tol) {
    const Mpfr zero = ex_.num(0);
    auto below = [&](const Mpfr& t) -> std::optional<Violation> {
      if (!(zero < t && t < t_end)) return std::nullopt;
      const Mpfr g = ex_.gap(f, t);
      if (g < Mpfr(-tol))
        return Violation{kPenetration, "gap " + text(g) + " at flight time " + text(t) + " of " + text(t_end) +
                                           " (tolerance " + text(tol) + ")"};
      return std::nullopt;
    };
    // Sampled times, and times just before the end.
    for (int i = 0; i < 6; ++i) {
      Mpfr t = t_end * Mpfr(hp(rng_.u01(), ex_.bits()));
      if (auto v = below(t)) return v;
    }
    for (int k : {8, 24, 40}) {
      Mpfr t = t_end;
      mpfr_mul_2si(t.get(), t.get(), -k, MPFR_RNDN);
      t = t_end - t;
      if (auto v = below(t)) return v;
    }
    // The knots crossed: the gap is concave between knots, so these decide.
    const auto& starts = ex_.model().wall.start;
    const Mpfr d0 = ex_.frac(f.theta0);
    auto knots_in = [&](const Mpfr& lo, const Mpfr& hi) -> std::optional<Violation> {
      // periods m with lo <= s_j - d0 + m (+ floor(theta0) cancels: phase arithmetic) <= hi
      Mpfr m = floor(Mpfr(lo + d0));
      m = m - 1;
      for (; m <= hi + d0; m = m + 1) {
        for (const Mpfr& s : starts) {
          Mpfr t = s - d0;
          t += m;
          if (t < lo || hi < t) continue;
          if (auto v = below(t)) return v;
        }
      }
      return std::nullopt;
    };
    const Mpfr head = ex_.num(2), tail_len = ex_.num(64);
    if (t_end <= head + tail_len + 2) return knots_in(zero, t_end);
    // A long flight: its middle [2, t_end - 64] is above the wall's top if both ends are
    // (y is concave); else every knot, within a budget.
    const Mpfr b = t_end - tail_len;
    const Mpfr top = ex_.hmax() + tol;
    if (top <= ex_.height(f, head) && top <= ex_.height(f, b)) {
      if (auto v = knots_in(zero, head)) return v;
      return knots_in(b, t_end);
    }
    if (ex_.num(200000) < t_end) {
      ++unchecked;
      return std::nullopt;
    }
    return knots_in(zero, t_end);
  }
};

inline std::string spec_options(const ModelSpec& m) {
  std::string s = std::string("--model ") + name(m.law) + " --a " + m.a.text();
  if (m.law == Law::constant) s += " --eps " + m.eps.text();
  if (m.law == Law::veldep) s += " --c " + m.c.text() + " --veldep-collapse " + (m.veldep_collapse ? "on" : "off");
  s += " --wall " + m.wall.text + " --downward-sticking " + name(m.downward);
  return s;
}

}  // namespace bouncer::step_check
