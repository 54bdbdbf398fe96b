// Independent truth for the sinusoidal wall (tests/test_sine_wall.cpp): the first impact by
// a brute-force sampler and the classical period-1 orbits in closed form, in MPFR at 256
// bits. Nothing here calls bouncer's model, map or analysis code: only the Mpfr number type
// (scalar/mpfr.hpp, a thin wrapper of mpfr_t) and MPFR's own sinpi/cospi.
//
// The model (docs/model.md, issue 27): wall height f(theta) = sin(2 pi theta) (amplitude 1,
// period 1), gravity a. A state (theta, v) is the particle on the wall at phase theta with
// velocity v just after an impact (v >= the wall velocity u(theta) = 2 pi cos(2 pi theta)).
// The gap s after the launch is
//     g(s) = sin(2 pi theta) + v s - a s^2/2 - sin(2 pi (theta + s)),
// the next impact is its FIRST root s > 0, and there the particle arrives with velocity
// v- = v - a s, the wall moves with u1 = u(theta + s), the relative approach speed is
// w = u1 - v- >= 0 and the particle leaves with v' = u1 + e(w) w (constant: e = eps;
// elastic: e = 1; veldep: e = exp(-(w/c)^(3/5))).
#pragma once

#include <mpfr.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "bouncer/model/spec.hpp"
#include "bouncer/scalar/mpfr.hpp"

namespace bouncer::sine_truth {

constexpr mpfr_prec_t kBits = 256;

inline Mpfr num(double x) {  // exact: a double has 53 bits
  Mpfr r(kBits);
  mpfr_set_d(r.get(), x, MPFR_RNDN);
  return r;
}
inline Mpfr num(long n) { return Mpfr(n, kBits); }
inline Mpfr dec(const std::string& text) {  // correctly rounded, as bouncer's Mpfr model reads a decimal
  Mpfr r(kBits);
  if (mpfr_set_str(r.get(), text.c_str(), 10, MPFR_RNDN) != 0) throw std::invalid_argument("not a decimal: " + text);
  return r;
}
inline Mpfr pi() {
  Mpfr r(kBits);
  mpfr_const_pi(r.get(), MPFR_RNDN);
  return r;
}
inline Mpfr sin2pi(const Mpfr& x) {  // sin(2 pi x), MPFR's sinpi of the exact 2x
  Mpfr r(kBits), t(kBits);
  mpfr_mul_2ui(t.get(), x.get(), 1, MPFR_RNDN);
  mpfr_sinpi(r.get(), t.get(), MPFR_RNDN);
  return r;
}
inline Mpfr cos2pi(const Mpfr& x) {
  Mpfr r(kBits), t(kBits);
  mpfr_mul_2ui(t.get(), x.get(), 1, MPFR_RNDN);
  mpfr_cospi(r.get(), t.get(), MPFR_RNDN);
  return r;
}
inline Mpfr abs(const Mpfr& x) {
  Mpfr r(kBits);
  mpfr_abs(r.get(), x.get(), MPFR_RNDN);
  return r;
}
inline Mpfr floor(const Mpfr& x) {
  Mpfr r(kBits);
  mpfr_floor(r.get(), x.get());
  return r;
}
inline Mpfr root(const Mpfr& x) {
  Mpfr r(kBits);
  mpfr_sqrt(r.get(), x.get(), MPFR_RNDN);
  return r;
}
inline Mpfr max1(const Mpfr& x) { return x > num(1L) ? x : num(1L); }
inline Mpfr pow2(long e) {
  Mpfr r(kBits);
  mpfr_set_ui_2exp(r.get(), 1, e, MPFR_RNDN);
  return r;
}
// The wall velocity u(x) = 2 pi cos(2 pi x) and acceleration f''(x) = -4 pi^2 sin(2 pi x).
inline Mpfr wall_velocity(const Mpfr& x) { return 2 * pi() * cos2pi(x); }
inline Mpfr wall_acceleration(const Mpfr& x) { return -4 * pi() * pi() * sin2pi(x); }

// Decimal text of x with `frac` digits after the point (for parse_decimal: no exponent).
inline std::string fixed(const Mpfr& x, int frac) {
  char* s = nullptr;
  mpfr_asprintf(&s, "%.*Rf", frac, x.get());
  std::string out(s);
  mpfr_free_str(s);
  return out;
}
inline std::string show(const Mpfr& x, int digits = 30) {
  char* s = nullptr;
  mpfr_asprintf(&s, "%.*Rg", digits, x.get());
  std::string out(s);
  mpfr_free_str(s);
  return out;
}

// The collision law, from the same decimal texts as the ModelSpec.
struct Law3 {
  Law law = Law::constant;
  Mpfr a, eps, c;
  Law3(Law l, const std::string& a_text, const std::string& eps_text, const std::string& c_text)
      : law(l), a(dec(a_text)), eps(dec(eps_text)), c(dec(c_text)) {}
  // Relative speed after a collision of relative approach speed w >= 0.
  Mpfr rebound(const Mpfr& w) const {
    if (law == Law::elastic) return w;
    if (law == Law::constant) return eps * w;
    Mpfr q = w / c, p(kBits), e(kBits);
    mpfr_pow(p.get(), q.get(), Mpfr(num(3L) / num(5L)).get(), MPFR_RNDN);
    mpfr_neg(p.get(), p.get(), MPFR_RNDN);
    mpfr_exp(e.get(), p.get(), MPFR_RNDN);
    return e * w;
  }
};

// ---------------------------------------------------------------------------------------
// The first impact by brute force.
//
// Bound on the curvature: g''(s) = -a + 4 pi^2 sin(2 pi (theta + s)), so
//     |g''| <= a + 4 pi^2 < a + 40 =: M.
// Two consequences make a sampled grid a proof that no root was skipped:
//  (1) near the launch, g(0) = 0 and g'(0) = w0 = v - u(theta) > 0 give
//      g(s) >= w0 s - M s^2/2 > 0 on (0, 2 w0/M): the scan starts at s = w0/M;
//  (2) on a cell [s, s + h], g minus its chord vanishes at both ends and has second
//      derivative >= -M, so g >= min(g(s), g(s + h)) - M h^2/8 on the cell: a cell whose
//      two samples both exceed M h^2/8 holds no root.
// An excursion of g below 0 of depth delta lasts at least 2 sqrt(2 delta/M) (from its minimum
// g climbs back to 0 no faster than M t^2/2), so a grid of step h sees every excursion deeper
// than M h^2/8 (with M = 75, h = 1/64: 2.3e-3). The grid steps h0 = 1/64 and every cell that
// (2) cannot clear is split in two, recursively, left half first: the grid is refined exactly
// where the gap comes close to 0 (near a graze of depth 1e-9 down to cells of ~3e-6, far
// below the excursion's length of ~2e-5), so no excursion deeper than the rounding of g
// (~1e-70 at 256 bits) is missed, and the first cell where g changes sign is bisected to a
// bracket of relative width 2^-210 (>= 200 bits). The samples are rounded at 256 bits (an
// error below 1e-70 for the flights here, |g|'s terms being below 1e6), so (2) demands a
// margin of 2^-230 on top of M h^2/8. A cell that keeps both ends positive down to 2^-210
// (a double root to 200 bits) is a touch: skipped and reported; none of the states of the
// tests comes near one.
struct FirstImpact {
  bool found = false;   // a root in (0, kMaxFlight]
  bool touch = false;   // a touch was skipped (see above); never expected
  Mpfr tau, unwrapped;  // flight time; theta + tau (phase not reduced)
  Mpfr theta, v;        // the state after the impact (theta in [0, 1))
  Mpfr w;               // relative approach speed at the impact, w = -g'(tau)
  long evaluations = 0;
};

class Sampler {
 public:
  static constexpr int kGridPerUnit = 64;
  static constexpr long kMaxFlight = 200;
  static constexpr long kBracketBits = 210;

  Sampler(const Law3& law, const Mpfr& theta, const Mpfr& v)
      : law_(law), theta_(theta), v_(v), sin0_(sin2pi(theta)), M_(law.a + num(40L)),
        margin_(pow2(-230)) {}

  Mpfr gap(const Mpfr& s) {
    ++evaluations_;
    return sin0_ + v_ * s - law_.a * s * s / 2 - sin2pi(theta_ + s);
  }

  FirstImpact first_impact() {
    FirstImpact r;
    const Mpfr w0 = v_ - wall_velocity(theta_);
    if (!(w0 > num(0L))) throw std::invalid_argument("the sampler needs a launch away from the wall (v > u(theta))");
    Mpfr lo = w0 / M_;  // (1): no root in (0, 2 w0/M)
    Mpfr glo = gap(lo);
    const Mpfr h0 = num(1L) / num(static_cast<long>(kGridPerUnit));
    while (lo < num(kMaxFlight)) {
      const Mpfr hi = lo + h0;
      const Mpfr ghi = gap(hi);
      if (search(lo, glo, hi, ghi, r)) break;
      lo = hi;
      glo = ghi;
    }
    r.evaluations = evaluations_;
    if (!r.found) return r;
    r.unwrapped = theta_ + r.tau;
    r.theta = r.unwrapped - floor(r.unwrapped);
    const Mpfr u1 = wall_velocity(r.theta);
    r.w = u1 - (v_ - law_.a * r.tau);
    r.v = u1 + law_.rebound(r.w);
    return r;
  }

 private:
  // The first root in (lo, hi], given g(lo) > 0; false if (2) clears the cell.
  bool search(const Mpfr& lo, const Mpfr& glo, const Mpfr& hi, const Mpfr& ghi, FirstImpact& r) {
    const Mpfr h = hi - lo;
    const bool hi_positive = ghi > num(0L);
    if (hi_positive) {
      const Mpfr low = glo < ghi ? glo : ghi;
      if (low > M_ * h * h / 8 + margin_) return false;
    }
    if (h <= pow2(-kBracketBits) * max1(hi)) {
      // A cell of 2^-210 with both ends positive that (2) cannot clear: g dips below 0 by
      // at most M h^2/8 ~ 1e-125 in it, beyond the precision: a touch, skipped (noted).
      if (hi_positive) {
        r.touch = true;
        return false;
      }
      r.found = true;
      r.tau = hi;
      return true;
    }
    const Mpfr mid = (lo + hi) / 2;
    const Mpfr gmid = gap(mid);
    if (!(gmid > num(0L))) return search(lo, glo, mid, gmid, r);  // a sign change: the root is in (lo, mid]
    return search(lo, glo, mid, gmid, r) || search(mid, gmid, hi, ghi, r);
  }

  const Law3& law_;
  Mpfr theta_, v_, sin0_, M_, margin_;
  long evaluations_ = 0;
};

inline FirstImpact first_impact(const Law3& law, const Mpfr& theta, const Mpfr& v) {
  return Sampler(law, theta, v).first_impact();
}

// ---------------------------------------------------------------------------------------
// Near-grazing launches. Pick the phase phi where the parabola should (almost) touch the
// wall, s0 > 0 after the launch, with g'(s0) = 0 and g(s0) = delta. g'(s0) = 0 fixes
//     v = a s0 + u(phi),   theta = phi - s0 (mod 1),
// and then g(s0) = G(s0) with
//     G(s) = sin(2 pi (phi - s)) - sin(2 pi phi) + u(phi) s + a s^2/2.
// g''(s0) = -a - f''(phi) = 4 pi^2 sin(2 pi phi) - a > 0 when sin(2 pi phi) > a/(4 pi^2):
// s0 is then a local minimum of the gap, a near miss (delta > 0) or a shallow excursion
// into the wall of depth |delta| lasting ~2 sqrt(2 |delta| / g''(s0)) (delta < 0). For
// small s, G(s) ~ -g''(s0) s^2/2 < 0 and G grows like a s^2/2 later: s0 is the first
// s >= 0.01 where G crosses delta, found on a grid of 0.01 and bisected to 240 bits. The
// launch is valid (v > u(theta)) iff G'(s0) = g'(0) > 0, which holds at such a crossing.
struct NearGraze {
  bool ok = false;
  Mpfr theta, v, s0, curvature;  // curvature = g''(s0)
};

inline NearGraze near_graze(const Mpfr& a, const Mpfr& phi, const Mpfr& delta) {
  NearGraze r;
  const Mpfr sphi = sin2pi(phi), uphi = wall_velocity(phi);
  auto G = [&](const Mpfr& s) -> Mpfr { return sin2pi(phi - s) - sphi + uphi * s + a * s * s / 2; };
  const Mpfr step = num(1L) / num(100L);
  Mpfr lo = step;
  if (!(G(lo) <= delta)) return r;
  for (;;) {
    const Mpfr hi = lo + step;
    if (hi > num(5L)) return r;
    if (G(hi) > delta) {
      Mpfr l = lo, h = hi;
      for (int i = 0; i < 240; ++i) {
        const Mpfr m = (l + h) / 2;
        (G(m) > delta ? h : l) = m;
      }
      r.s0 = h;
      break;
    }
    lo = hi;
  }
  r.v = a * r.s0 + uphi;
  const Mpfr t = phi - r.s0;
  r.theta = t - floor(t);
  r.curvature = 4 * pi() * pi() * sphi - a;
  r.ok = r.v > wall_velocity(r.theta) && r.curvature > num(0L);
  return r;
}

// ---------------------------------------------------------------------------------------
// Classical period-1 orbits (derivation in docs/model.md, "The sinusoidal wall: classical
// period-1 orbits", and in tests/test_sine_wall.cpp). Constant restitution eps (eps = 1:
// elastic), flight time n whole periods, branch +1: sin(2 pi theta*) > 0 (the wall
// decelerating, the candidate stable orbit), -1: sin(2 pi theta*) < 0 (a saddle).
struct Period1 {
  bool exists = false;
  Mpfr theta, v;  // the fixed point
  Mpfr C, S;      // cos and sin of 2 pi theta*
  Mpfr j11, j12, j21, j22;
  Mpfr trace, det;
};

inline Period1 period1(const Mpfr& a, const Mpfr& eps, long n, int branch) {
  Period1 p;
  const Mpfr P = pi(), one = num(1L);
  p.C = a * n * (one - eps) / (4 * P * (one + eps));
  if (abs(p.C) > one) return p;
  p.exists = true;
  Mpfr ac(kBits);
  mpfr_acos(ac.get(), p.C.get(), MPFR_RNDN);
  const Mpfr t = ac / (2 * P);  // in [0, 1/2]
  p.theta = branch > 0 ? t : Mpfr(one - t);
  p.S = root(one - p.C * p.C);
  if (branch < 0) p.S = num(0L) - p.S;
  p.v = a * n / 2;
  const Mpfr k = 4 * P * P;  // 4 pi^2
  p.j11 = one;
  p.j12 = (one + eps) / a;
  p.j21 = num(0L) - k * (one + eps) * p.S;
  p.j22 = eps * eps - k * (one + eps) * (one + eps) * p.S / a;
  p.trace = one + eps * eps - k * (one + eps) * (one + eps) * p.S / a;
  p.det = eps * eps;
  return p;
}

// The period-doubling threshold of the branch +1 orbit (trace = -(1 + det)):
//     a_pd = 4 pi^2 (1+eps)^2 / sqrt(4 (1+eps^2)^2 + pi^2 n^2 (1-eps^2)^2),
// and the saddle-node where both branches are born (cos(2 pi theta*) = 1):
//     a_sn = 4 pi (1+eps) / (n (1-eps)).
inline Mpfr a_period_doubling(const Mpfr& eps, long n) {
  const Mpfr P = pi(), one = num(1L);
  const Mpfr q = one + eps * eps, r = one - eps * eps;
  return 4 * P * P * (one + eps) * (one + eps) / root(4 * q * q + P * P * (n * n) * r * r);
}
inline Mpfr a_saddle_node(const Mpfr& eps, long n) {
  const Mpfr one = num(1L);
  return 4 * pi() * (one + eps) / (n * (one - eps));
}

}  // namespace bouncer::sine_truth
