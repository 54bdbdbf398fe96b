// bouncer-fuzz-step: random states and parameters through ImpactMap<T>::step, in every
// collision model, each step checked against invariants computed independently of the map:
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
// Each random start is followed for --chain steps, so post-impact, sticking and release
// states (exact knots) are checked too. Deterministic for a given --seed.
// Exit status: 0 no violation, 1 a violation (the first one is printed, with the state in
// round-trip digits and the parameters as exact decimals, and a command reproducing it),
// 2 bad options.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/precision.hpp"
#include "bouncer/scalar/thread_caches.hpp"

namespace {

using namespace bouncer;

// ---- deterministic random numbers (raw mt19937_64 bits; no std distributions) ----------
struct Rng {
  std::mt19937_64 g;
  explicit Rng(uint64_t seed) : g(seed) {}
  double u01() { return static_cast<double>(g() >> 11) * 0x1p-53; }
  size_t below(size_t n) { return static_cast<size_t>(g() % n); }
  bool chance(double p) { return u01() < p; }
  double log_uniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * u01()); }
};

std::string decimal_text(double x, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*g", digits, x);
  return b;
}
Decimal dec(const std::string& s) { return *Decimal::parse(s); }

// A rational as a decimal >= it: exact when it has one, else 30 significant digits rounded up.
Decimal decimal_at_least(const mpq_class& q) {
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

// ---- random parameters and starts ----------------------------------------------------
struct Choice {
  std::string model = "all", wall = "all";
};

ModelSpec random_spec(Rng& rng, const Choice& ch) {
  ModelSpec m;
  static const char* laws[] = {"elastic", "constant", "veldep"};
  const std::string law = ch.model == "all" ? laws[rng.below(3)] : ch.model;
  m.law = parse_law("model", law);
  const double pa = rng.u01();
  if (pa < 0.1) {
    static const char* special[] = {"24", "1e9", "0.01", "0.5", "28.82", "8"};
    m.a = dec(special[rng.below(6)]);
  } else if (pa < 0.5) {
    m.a = dec(decimal_text(1 + 49 * rng.u01(), 1 + static_cast<int>(rng.below(17))));
  } else {
    m.a = dec(decimal_text(rng.log_uniform(0.01, 1e6), 1 + static_cast<int>(rng.below(17))));
  }
  if (m.law == Law::constant) {
    const double pe = rng.u01();
    if (pe < 0.25) {
      static const char* special[] = {"0", "1", "0.5", "1e-9", "0.999999999", "0.9", "0.96", "0.25"};
      m.eps = dec(special[rng.below(8)]);
    } else {
      m.eps = dec(decimal_text(rng.u01(), 1 + static_cast<int>(rng.below(17))));
    }
  }
  if (m.law == Law::veldep) {
    m.c = dec(decimal_text(rng.log_uniform(1e-3, 1e7), 1 + static_cast<int>(rng.below(17))));
    m.veldep_collapse = rng.chance(0.5);
  }
  m.downward = rng.chance(0.5) ? DownwardSticking::paper : DownwardSticking::impact;
  static const char* walls[] = {"triangle", "sawtooth", "asymmetric", "knots"};
  const std::string w = ch.wall == "all" ? walls[rng.below(4)] : ch.wall;
  if (w == "triangle" || w == "sawtooth") {
    m.wall = parse_wall("wall", w);
  } else if (w == "asymmetric") {
    std::string r;
    do r = decimal_text(0.01 + 0.98 * rng.u01(), 1 + static_cast<int>(rng.below(6)));
    while (!(dec(r) > Decimal::from_int(0) && dec(r) < Decimal::from_int(1)));
    m.wall = parse_wall("wall", "asymmetric:" + r);
  } else {
    // 2..6 knots at distinct 3-digit phases, heights in [-3, 3] (not all equal).
    for (;;) {
      const size_t n = 2 + rng.below(5);
      std::vector<int> s{0};
      while (s.size() < n) {
        const int k = 1 + static_cast<int>(rng.below(999));
        if (std::find(s.begin(), s.end(), k) == s.end()) s.push_back(k);
      }
      std::sort(s.begin(), s.end());
      std::string text = "knots:";
      for (size_t j = 0; j < n; ++j) {
        const int h = static_cast<int>(rng.below(601)) - 300;
        text += (j ? "," : "") + decimal_text(s[j] / 1000.0, 3) + ":" + decimal_text(h / 100.0, 3);
      }
      m.wall = parse_wall("wall", text);
      try {
        validate(m);
        break;
      } catch (const InputError&) {  // flat: draw again
      }
    }
  }
  validate(m);
  return m;
}

InitialCondition random_start(Rng& rng, const ModelSpec& m) {
  InitialCondition ic;
  const size_t n = m.wall.knots.size();
  const double pt = rng.u01();
  if (pt < 0.2) {
    ic.theta = m.wall.knots[rng.below(n)];  // exactly at a knot
  } else {
    std::string t;
    do t = decimal_text(rng.u01(), 1 + static_cast<int>(rng.below(17)));
    while (!(dec(t) < Decimal::from_int(1)));
    ic.theta = dec(t);
  }
  const mpq_class u = wall_velocity_exact(m.wall, ic.theta.value());
  const double pv = rng.u01();
  double delta;
  if (pv < 0.1) {
    delta = 0;  // moving with the wall: ride, or sticking at once
  } else if (pv < 0.15) {
    // A release-like start: at a knot with the previous segment's (larger) velocity.
    ic.theta = m.wall.knots[rng.below(n)];
    const int j = wall_segment_exact(m.wall, ic.theta.value());
    const int prev = j == 0 ? static_cast<int>(n) - 1 : j - 1;
    const mpq_class up = wall_velocity_exact(m.wall, m.wall.knots[static_cast<size_t>(prev)].value());
    const mpq_class uj = wall_velocity_exact(m.wall, ic.theta.value());
    ic.v = decimal_at_least(up > uj ? up : uj);
    return ic;
  } else if (pv < 0.4) {
    delta = rng.log_uniform(1e-12, 1e-2);
  } else if (pv < 0.95) {
    delta = rng.log_uniform(1e-2, 1e3);
  } else {
    delta = rng.log_uniform(1e3, 1e12);
  }
  const Decimal ud = decimal_at_least(u);
  if (delta == 0) {
    ic.v = ud;
  } else {
    const Decimal v = dec(decimal_text(u.get_d() + delta, 1 + static_cast<int>(rng.below(17))));
    ic.v = v < ud ? ud : v;
  }
  if (ic.v > dec("1e15")) ic.v = dec("1e15");
  return ic;
}

// ---- exact conversion of a step's numbers to MPFR ------------------------------------
Mpfr hp(double x, long bits) {
  Mpfr r(bits);
  mpfr_set_d(r.get(), x, MPFR_RNDN);
  return r;
}
Mpfr hp(long double x, long bits) {
  Mpfr r(bits);
  mpfr_set_ld(r.get(), x, MPFR_RNDN);
  return r;
}
Mpfr hp(const Quad& x, long bits) {
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
Mpfr hp(const DoubleDouble& x, long bits) {
  // hi + lo: exact when bits covers the pair's span (about 106 bits for the map's values).
  Mpfr r(bits);
  mpfr_set_d(r.get(), x.hi(), MPFR_RNDN);
  mpfr_add_d(r.get(), r.get(), x.lo(), MPFR_RNDN);
  return r;
}
Mpfr hp(const Mpfr& x, long bits) {
  Mpfr r(bits);
  mpfr_set(r.get(), x.get(), MPFR_RNDN);
  return r;
}

// ---- the independent checker ---------------------------------------------------------
enum Invariant { kTau, kTheta, kVelocity, kPenetration, kOnWall, kLaw, kException, kInvariants };
const char* kInvariantNames[] = {"tau > 0", "theta in [0, 1)", "v >= wall velocity", "no penetration",
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
  Checker(const ModelSpec& spec, const Model<T>& model, long hp_bits, Rng& rng)
      : ex_(spec, hp_bits), model_(model), rng_(rng) {}

  long long unchecked = 0;  // flights too long and low to check every knot

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
    long long budget = 1000000;
    for (const auto& [lo, hi] : windows) {
      Mpfr kf = ceil_of(Mpfr(lo - d));
      if (kf < ex_.num(0)) kf = ex_.num(0);
      for (Mpfr t = d + kf; t <= hi && t <= t_max + tol; t = t + 1) {
        if (--budget < 0) return std::nullopt;
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

std::string spec_options(const ModelSpec& m) {
  std::string s = std::string("--model ") + name(m.law) + " --a " + m.a.text();
  if (m.law == Law::constant) s += " --eps " + m.eps.text();
  if (m.law == Law::veldep) s += " --c " + m.c.text() + " --veldep-collapse " + (m.veldep_collapse ? "on" : "off");
  s += " --wall " + m.wall.text + " --downward-sticking " + name(m.downward);
  return s;
}

struct Counts {
  long long starts = 0, skipped = 0, steps = 0;
  std::map<std::string, long long> kinds, undecided;
  long long violations[kInvariants] = {};
  long long unchecked = 0;
  std::vector<std::pair<long long, std::string>> reports;  // (start, text): the first, or all

  void add(const Counts& o) {
    starts += o.starts;
    skipped += o.skipped;
    steps += o.steps;
    for (const auto& [k, n] : o.kinds) kinds[k] += n;
    for (const auto& [k, n] : o.undecided) undecided[k] += n;
    for (int i = 0; i < kInvariants; ++i) violations[i] += o.violations[i];
    unchecked += o.unchecked;
    reports.insert(reports.end(), o.reports.begin(), o.reports.end());
  }
};

// Start i draws from its own generator, seeded from (seed, i): a start is reproduced alone
// with --first-start i --states 1, and threads split the starts without changing them.
uint64_t start_seed(uint64_t seed, long long i) {
  uint64_t z = seed * 0x9e3779b97f4a7c15ULL + static_cast<uint64_t>(i) + 1;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

template <class T>
void run(const Precision& prec, long long first, long long last, long long stride, uint64_t seed, int chain,
         const Choice& ch, bool verbose, Counts& c) {
  using Tr = ScalarTraits<T>;
  const long hp_bits = std::max<long>(256, 2 * prec.bits + 64);
  for (long long i = first; i < last; i += stride) {
    Rng rng(start_seed(seed, i));
    const ModelSpec spec = random_spec(rng, ch);
    const InitialCondition ic = random_start(rng, spec);
    ++c.starts;
    try {
      validate(spec, ic, "theta", "v");
    } catch (const InputError& e) {
      ++c.skipped;  // the generator drew an invalid start (should not happen)
      continue;
    }
    const Model<T> model = make_model<T>(spec, prec.bits);
    const ImpactMap<T> map(model);
    State<T> s;
    try {
      s = make_state(model, ic);
    } catch (const InputError&) {
      ++c.skipped;  // theta rounds to 1 at this precision
      continue;
    }
    Checker<T> checker(spec, model, hp_bits, rng);
    for (int k = 0; k < chain; ++k) {
      std::optional<Violation> bad;
      StepResult<T> r;
      try {
        r = map.step(s);
        ++c.steps;
        ++c.kinds[name(r.kind)];
        bad = checker.check(s, r);
      } catch (const Undecided& e) {
        ++c.undecided[describe(e.reason)];
        break;
      } catch (const std::exception& e) {
        bad = Violation{kException, e.what()};
      }
      if (bad) {
        ++c.violations[bad->what];
        if (c.reports.empty() || verbose) {
          std::ostringstream o;
          o << "counterexample (--seed " << seed << " --first-start " << i << ", step " << k + 1 << " of its chain): "
            << kInvariantNames[bad->what] << ": " << bad->detail << "\n"
            << "  state: theta " << Tr::to_string(s.theta) << " v " << Tr::to_string(s.v)
            << (s.knot >= 0 ? " (at knot " + std::to_string(s.knot) + ")" : std::string()) << "\n"
            << "  parameters: " << spec_options(spec) << " --precision " << prec.text() << "\n"
            << "  reproduce: bouncer orbit " << spec_options(spec) << " --precision " << prec.text()
            << " --theta " << Tr::to_string(s.theta) << " --v " << Tr::to_string(s.v) << " --steps 1\n";
          c.reports.emplace_back(i, o.str());
        }
        break;
      }
      s = r.next;
    }
    c.unchecked += checker.unchecked;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bouncer-fuzz-step: random states and parameters through the impact map, checked against "
               "invariants (tau > 0, theta in [0,1), v >= wall velocity, no penetration, impact on the wall, "
               "collision law). Exit 1 on a violation."};
  long long states = 10000;
  uint64_t seed = 1;
  int chain = 4;
  Choice ch;
  std::string precision_text = "double";
  bool verbose = false;
  long long first_start = 0;
  int threads = 1;
  app.add_option("--states", states, "Random starts, integer >= 1 (default 10000)")->check(CLI::Range(1LL, 1000000000000LL));
  app.add_option("--seed", seed, "Seed of the random draws (default 1)");
  app.add_option("--chain", chain, "Steps followed from each start, integer in [1, 1000] (default 4)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--model", ch.model, "elastic | constant | veldep | all (default all)")
      ->check(CLI::IsMember({"elastic", "constant", "veldep", "all"}));
  app.add_option("--wall", ch.wall, "triangle | sawtooth | asymmetric | knots | all (default all)")
      ->check(CLI::IsMember({"triangle", "sawtooth", "asymmetric", "knots", "all"}));
  app.add_option("--precision", precision_text, "double (default) | long | dd | quad | mpfr:BITS");
  app.add_option("--first-start", first_start, "Index of the first start (default 0): --first-start I --states 1 "
                                               "re-runs start I of a seed alone")
      ->check(CLI::Range(0LL, 1000000000000LL));
  app.add_option("--threads", threads, "Threads, integer in [1, 256] (default 1); the starts do not depend on it")
      ->check(CLI::Range(1, 256));
  app.add_flag("--verbose", verbose, "Print every violation, not only the first");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "bouncer-fuzz-step: " << e.what() << "\n";
    return 2;
  }
  Precision prec;
  try {
    prec = parse_precision("precision", precision_text);
    if (prec.is_interval()) throw InputError("precision", "interval precisions are not fuzzed (point types only)");
  } catch (const InputError& e) {
    std::cerr << "bouncer-fuzz-step: " << e.what() << "\n";
    return 2;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Counts> parts(static_cast<size_t>(threads));
  {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        const MpfrThreadCaches caches;  // freed when this thread ends
        with_point_scalar(prec, [&](auto tag) {
          using T = typename decltype(tag)::type;
          run<T>(prec, first_start + t, first_start + states, threads, seed, chain, ch, verbose, parts[t]);
        });
      });
    for (auto& th : pool) th.join();
  }
  Counts c;
  for (const Counts& p : parts) c.add(p);
  std::sort(c.reports.begin(), c.reports.end());
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  long long total = 0;
  for (long long v : c.violations) total += v;
  std::cout << "bouncer-fuzz-step: precision " << prec.text() << ", seed " << seed << ", model " << ch.model
            << ", wall " << ch.wall << ", " << c.starts << " starts x up to " << chain << " steps, "
            << secs << " s\n";
  std::cout << "steps checked: " << c.steps;
  for (const auto& [k, n] : c.kinds) std::cout << ", " << k << " " << n;
  std::cout << "\nstarts skipped (theta rounds to 1): " << c.skipped << "\n";
  std::cout << "undecided steps:";
  if (c.undecided.empty()) std::cout << " none";
  for (const auto& [k, n] : c.undecided) std::cout << " [" << k << "] " << n;
  std::cout << "\nlong low flights not checked knot by knot: " << c.unchecked << "\n";
  for (int i = 0; i < kInvariants; ++i)
    std::cout << "  " << kInvariantNames[i] << ": " << c.violations[i] << " violations\n";
  if (verbose) {
    for (const auto& [i, text] : c.reports) std::cout << text;
  } else if (!c.reports.empty()) {
    std::cout << "first " << c.reports.front().second;
  }
  std::cout << (total ? "FAIL" : "OK") << ": " << total << " violations\n";
  return total ? 1 : 0;
}
