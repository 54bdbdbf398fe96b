// Certified border collisions, both sides (issue 23): an enclosure [a*_lo, a*_hi] of the
// parameter value a* at which a branch of period-Q orbits ends because one of its margins
// (analysis/continuation.hpp: knot distance, clearance, impact speed, sticking margin)
// reaches 0, proved by the Krawczyk operator on the augmented system
//
//     unknowns u = (theta_0, v_0, p)          (the orbit's first point and the parameter)
//     G(u)      = ( P_E^Q(theta_0, v_0; p) - (theta_0, v_0),
//                   m_E(theta_0, v_0; p) )     (periodicity, and "the margin is zero"),
//
// or, for an orbit through a sticking step (whose points are the release state R's orbit,
// exact for every p), u = p and G(p) = m_E(R; p).
//
// The map is piecewise smooth: at a* two of its pieces meet. P_E is the piece of the BRANCH
// SIDE, identified by the step's own event sequence E on the branch side (for each step: the
// segment of departure, the segment and wall period of the impact, whether it sticks), and
// written in closed form: the impact is the larger root of the flight's gap to the line of
// the impact segment (the same root the walk of model/impact_map_impl.hpp finds, without
// deciding which segment it lies on). That formula is analytic across the border, so P_E
// extended beyond a* is what the augmented zero solves, and the margins are analytic
// functions of (theta, v, p) along it. Interval evaluation of P_E and m_E (MPFI) and of
// their derivatives (the interval duals of verify/interval_dual.hpp) never decides a
// branch; which piece is the true map is decided separately, by the signs of the margins.
//
// What certify_border_collision proves, for a box Y (the orbit) and a parameter interval
// Z = [z_lo, z_hi] around a* (high end; the low end mirrored):
//   1. (Krawczyk, unknowns (theta, v), free p) for every p in Z exactly one x(p) in Y with
//      P_E^Q(x(p); p) = x(p);
//   2. (Krawczyk on G over Y x Z) exactly one (x*, p*) in Y x Z with G = 0, and
//      p* in [a*_lo, a*_hi] (Y x Z tightened by K(B) n B);
//   3. (intervals) the border margin m(x(p), p) is > 0 at the branch-side end of Z and < 0 at
//      the other (x enclosed there at a thin p, inside Y), so by 1, 2 and continuity it is
//      > 0 for p on the branch side of p* and < 0 beyond: exactly one zero in Z, a*, and a
//      sign change there;
//   4. (intervals) every other margin of every step (departure speed, clearance at every knot
//      the flights pass, impact speed, both knot distances of every impact, the sticking
//      test) keeps its branch-side sign over Y x [z_lo, a*_lo]: there the piece E is the
//      true map, so x(p) is a period-Q orbit of the map with event sequence E (the steps
//      must also chain: each departs from the segment the previous impact landed on);
//   5. (the step itself) at a branch-side parameter next to a*_lo the interval step
//      ImpactMap<Mpfi> (every branch decided by outward-rounded intervals, as the existing
//      certifiers decide them) takes the event sequence E on the enclosed orbit.
// Theorem: for every p in [z_lo, a*_lo) the period-Q orbit with events E exists (unique in
// Y); at exactly one a* in [a*_lo, a*_hi] its margin reaches 0; for p in (a*, z_hi] the piece
// E's orbit violates the margin, so no orbit with events E lies in Y. Orbits through a
// sticking step: the same with Y empty (their points are exact).
//
// Margins that vanish together with the border by an identity are not a failure: an impact
// nearing the end of its segment (knot k) makes the next flight's clearance at k equal to
// delta (W - a delta/2), one nearing the start makes its own flight's clearance at k equal to
// delta (q - a delta/2) (delta the knot distance, W the departure speed, q the impact speed),
// so their sign follows from the border's where the factor is certainly > 0. For orbits
// through the release state (p the only variable) a margin that is monotone over the side
// and positive at both of its ends is positive on it (the knot and the grazing at a = 32).
//
// Grazing (clearance) and sticking ends are the same construction with another margin. A
// touchdown (impact speed 0) never ends a branch alone: the gap to the impact segment's line
// keeps g'^2 + 2 a g = D (the squared impact speed) along the flight, so D >= 2 a c with c the
// clearance at the knot where the flight enters that segment (and D = W^2 for a flight that
// departs from it). The impact speed and the impact's distance to that knot are therefore
// positive wherever that clearance is, which step 4 uses; a corner touchdown (c, g' and D
// reaching 0 together, the release orbit at a = 8) is proved as the clearance's end. Any other
// margin that vanishes at a* makes step 4 fail: nothing is claimed.
//
// Long periods (Formulation): the same proof with all Q orbit points as unknowns, Y a
// box per point, G_i = piece_i(x_i; p) - x_{i+1 mod Q}; every margin of step i is evaluated
// over x_i's own box, and the step's own check (5) runs each step from its point's box.
//
// The question's interval [lo, hi] (verify/branch_end.hpp branch_end_interval) lies on the
// branch side of a double bracket, which may itself lie past a* (issue 23): the branch
// side's orbit is found at its far end (the step's Newton; for unstable orbits, Newton on
// the piece of the last point's events, confirmed by the step), and the parameter interval
// Z of the proof is centred on the augmented Newton's a*, with the interval's width.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "bouncer/analysis/continuation.hpp"
#include "bouncer/verify/branch_end.hpp"
#include "bouncer/verify/periodic_certify.hpp"

namespace bouncer {

struct BorderCollisionQuestion {
  // The end as `continue` reports it (verify/branch_end.hpp): the model, the varied
  // parameter, the period, the last orbit point on the branch side, the interval next to a*
  // on the branch side (branch_end_interval) and which end. Its width sets the width of Z.
  BranchEndQuestion end;
  // The margin that vanishes (BranchEnd::margin), if known; else the margin whose zero,
  // extrapolated from two branch-side orbits, is nearest.
  std::optional<Margin> margin;
  long bits = 128;  // MPFI precision of every interval evaluation
  // If > bits: when the proof fails, it is tried again at twice the bits, up to max_bits.
  // The composed formulation of long periods needs it: q interval steps widen a box by up to
  // the product of the steps' derivative norms (about 2^66 over a period-66 orbit), and the
  // parameter interval Z must be wide against that growth times the precision's ulp (the
  // margins' signs at Z's ends, the step's own events next to a*) yet narrow against the
  // margins divided by it (the Krawczyk operator over Y x Z): at 128 bits that window can be
  // empty. Multiple shooting (Formulation) does not compose, and proves them at 128.
  long max_bits = 0;
  Formulation formulation = Formulation::automatic;
};

struct BorderCollisionCertificate {
  bool certified = false;
  long bits = 0;
  // a* in [lo, hi]: exact rationals (the ends of the MPFI enclosure), and as decimal texts.
  mpq_class lo, hi;
  Enclosure parameter;
  double width = 0;        // hi - lo
  // The margin that vanishes: its kind, the step of the orbit it belongs to (0-based from
  // the orbit's first point), the knot involved (knot, clearance), and in words.
  Margin margin = Margin::knot;
  int step = -1;
  int knot = -1;
  std::string margin_text;
  std::string events;      // E, the branch side's event sequence (analysis/continuation.hpp event_text)
  bool through_release = false;
  bool shooting = false;   // proved by multiple shooting (all Q points unknowns), else composed
  // The parameter interval Z = [z_lo, z_hi] of the proof, as exact rationals: the orbit with
  // events E exists for p in [z_lo, lo] (high end; [hi, z_hi] at a low end) and the border
  // margin is < 0 (the piece is left) beyond a*, up to z_hi (down to z_lo).
  mpq_class z_lo, z_hi;
  mpq_class checked_at;    // where ImpactMap<Mpfi> itself decided the events E (step 5)
  std::vector<EnclosedOrbitPoint> orbit;  // the orbit at a* (the release state's orbit: its points)
  std::string statement;   // the theorem, or "Not certified at N bits: why"
  std::string reason;      // why not certified
  double seconds = 0;
};

// The two-sided certificate of the end described by q (see the header comment). Never
// guesses: when any step of the proof fails, certified is false and the reason says which.
BorderCollisionCertificate certify_border_collision(const BorderCollisionQuestion& q);

// Period doubling (the smooth end that Krawczyk handles as it does a border collision): the
// augmented system (P^Q(x; p) - x, det(DP^Q(x; p) + I)) in the unknowns (theta_0, v_0, p),
// its Jacobian from nested interval duals (second derivatives of P^Q) through the step
// itself, every branch decided over the box (a period doubling is inside a piece). Proves:
// for every p in Z exactly one period-Q point x(p) in Y (events fixed); exactly one p* in
// [lo, hi] where det(DP^Q + I) = 0, i.e. a multiplier of x(p*) is exactly -1; that
// determinant changes sign across p*, so a real multiplier crosses -1. Which way the doubled
// orbit branches (the normal form's coefficient) is not certified. Folds: certify_fold below.
// Long periods: where that composed form fails, the same proof with all Q orbit points as
// unknowns (multiple shooting; the determinant's derivatives from prefix and suffix
// products of the steps' Jacobians), then both again at twice the bits, up to max_bits.
struct PeriodDoublingQuestion {
  ModelSpec model;                  // any value of the varied parameter
  Parameter vary = Parameter::a;
  long period = 1;
  InitialCondition point;           // an orbit point near a* (continuation: the nearest branch point)
  Decimal lo, hi;                   // an interval holding a* (e.g. Bifurcation's bracket)
  long bits = 128;
  long max_bits = 0;                // as BorderCollisionQuestion::max_bits: retried at twice the bits up to it
};

struct PeriodDoublingCertificate {
  bool certified = false;
  long bits = 0;
  mpq_class lo, hi;                 // p* in [lo, hi]
  Enclosure parameter;
  double width = 0;
  std::string events;
  mpq_class z_lo, z_hi;             // Z
  Enclosure trace, det;             // of DP^Q over the tight box at p*
  Enclosure other;                  // the other multiplier, -det (the product is det)
  std::vector<EnclosedOrbitPoint> orbit;  // x(p*), its first point
  std::string statement, reason;
  double seconds = 0;
};

PeriodDoublingCertificate certify_period_doubling(const PeriodDoublingQuestion& q);

// Fold (saddle-node), the same question and certificate: the augmented system
// (P^Q(x; p) - x, det(DP^Q(x; p) - I)) in (theta_0, v_0, p), Krawczyk over a small box around
// its Newton point (every branch decided over the box). Proves: exactly one (x*, p*) in the
// box with P^Q(x*) = x* and a multiplier exactly +1 (the other, det DP^Q, is `other`, not +1),
// p* in [lo, hi]; and, because K(B) inside B makes every Jacobian over B nonsingular, that
// the fold is nondegenerate (the period-Q points near x* form one smooth curve that turns
// back quadratically at p*: two orbits on one side, none on the other; the argument is in
// border_collision.cpp run_fold). Not certified: how large that neighbourhood is, and which
// side has the two orbits (the branch's side, by continuation). z_lo, z_hi = lo, hi; trace,
// det, other over the tight box.
PeriodDoublingCertificate certify_fold(const PeriodDoublingQuestion& q);

// `continue --certify` on one end of a branch: the question over branch_end_interval's
// interval (its texts lo, hi) and its certificate.
// The one-sided certificate (certify_branch_end) and the two-sided one
// (certify_border_collision, at max(128, the branch's bits), and at twice those bits if that
// fails), and whether the branch's own
// bracket of a* (in its scalar) contains the certified enclosure: a double bracket can lie
// past a* (issue 23), and this says so.
struct CertifiedBranchEnd {
  bool high_end = true;
  std::string lo, hi;  // the interval certified over (round-trip texts of the branch's scalar)
  BranchEndCertificate certificate;
  BorderCollisionCertificate two_sided;
  bool bracket_contains = false;  // two_sided certified and [a*_lo, a*_hi] inside the branch's bracket
};
// Both ends of a branch: set at each border end (EndReason::border), empty at the others.
struct CertifiedBranchEnds {
  std::optional<CertifiedBranchEnd> low, high;
  // certify_smooth_events: per bifurcation of the branch (aligned with Branch::bifurcations)
  // the period doubling's or fold's certificate (a Neimark-Sacker is not offered: not
  // certified, with the reason), and a fold end's or a doubling end's (the period doubling
  // of the period-q/2 orbit the branch is born from).
  std::vector<PeriodDoublingCertificate> bifurcations;
  std::optional<PeriodDoublingCertificate> low_smooth, high_smooth;
};

// The question for a smooth event of b (a period doubling or a fold, on the branch or at an
// end) at `param` with the bracket [lo, hi] (the branch scalar's texts): the branch point
// nearest to it starts the proof, at max(bits, 128).
template <class T>
PeriodDoublingQuestion smooth_event_question(const ModelSpec& model, Parameter vary, long period, const Branch<T>& b,
                                             double param, const std::string& lo, const std::string& hi, long bits) {
  using Tr = ScalarTraits<T>;
  const BranchPoint<T>* near = &b.points.front();
  for (const BranchPoint<T>& p : b.points)
    if (std::fabs(Tr::to_double(p.param) - param) < std::fabs(Tr::to_double(near->param) - param)) near = &p;
  PeriodDoublingQuestion q;
  q.model = model;
  q.vary = vary;
  q.period = period;
  q.point = {parse_decimal("theta", Tr::to_string(near->orbit.points[0].theta)),
             parse_decimal("v", Tr::to_string(near->orbit.points[0].v))};
  q.lo = parse_decimal("lo", lo);
  q.hi = parse_decimal("hi", hi);
  q.bits = std::max<long>(bits, 128);
  q.max_bits = 2 * q.bits;
  return q;
}

// The proof of a smooth end of b (a fold, or a doubling: then the period doubling of the
// period-q/2 orbit it is born from, started from b's orbit there, which is next to that orbit
// traversed twice); nullopt at the other ends.
template <class T>
std::optional<PeriodDoublingCertificate> certify_smooth_end(const ModelSpec& model, Parameter vary, long period,
                                                            const Branch<T>& b, const BranchEnd<T>& e, long bits) {
  using Tr = ScalarTraits<T>;
  if (e.reason != EndReason::fold && e.reason != EndReason::doubling) return std::nullopt;
  const bool doubling = e.reason == EndReason::doubling;
  const PeriodDoublingQuestion q = smooth_event_question(model, vary, doubling ? e.mother_period : period, b, Tr::to_double(e.param),
                                                         Tr::to_string(e.bracket_lo), Tr::to_string(e.bracket_hi), bits);
  return doubling ? certify_period_doubling(q) : certify_fold(q);
}

// `continue --certify`: proves every period doubling and fold of b (certify_period_doubling,
// certify_fold) and its fold and doubling ends, into c.
template <class T>
void certify_smooth_events(const ModelSpec& model, Parameter vary, long period, const Branch<T>& b, long bits,
                           CertifiedBranchEnds& c) {
  using Tr = ScalarTraits<T>;
  if (!b.started || b.points.empty()) return;
  c.bifurcations.clear();
  for (const Bifurcation<T>& x : b.bifurcations) {
    if (x.kind == SmoothKind::neimark_sacker) {
      PeriodDoublingCertificate none;
      none.reason = "a Neimark-Sacker bifurcation has no certifier";
      none.statement = "Not certified: " + none.reason + ". Nothing is claimed.";
      c.bifurcations.push_back(none);
      continue;
    }
    const PeriodDoublingQuestion q = smooth_event_question(model, vary, period, b, Tr::to_double(x.param),
                                                           Tr::to_string(x.bracket_lo), Tr::to_string(x.bracket_hi), bits);
    c.bifurcations.push_back(x.kind == SmoothKind::period_doubling ? certify_period_doubling(q) : certify_fold(q));
  }
  c.low_smooth = certify_smooth_end(model, vary, period, b, b.low, bits);
  c.high_smooth = certify_smooth_end(model, vary, period, b, b.high, bits);
}

// Certifies each border end of `b`: its branch side (model: the branch's, any value of the
// varied parameter; bits: the branch's precision), and a* on both sides. one_sided = false
// skips the one-sided certificate (certify_branch_end bisects its interval, seconds to
// minutes for long periods; `attractors --vary` needs only the two-sided enclosure of a*).
template <class T>
CertifiedBranchEnds certify_branch_ends(const ModelSpec& model, Parameter vary, long period, const Branch<T>& b, long bits,
                                        bool one_sided = true) {
  using Tr = ScalarTraits<T>;
  // The branch's length (each end's param: a* where located, else the last point).
  const double span = Tr::to_double(b.high.param) - Tr::to_double(b.low.param);
  auto one = [&](const BranchEnd<T>& e, bool high) -> std::optional<CertifiedBranchEnd> {
    if (e.reason != EndReason::border) return std::nullopt;
    BranchEndQuestion c;
    c.model = model;
    c.vary = vary;
    c.period = period;
    c.last_point = {parse_decimal("certify", Tr::to_string(e.last_point.theta)),
                    parse_decimal("certify", Tr::to_string(e.last_point.v))};
    CertifiedBranchEnd r;
    r.high_end = high;
    std::tie(r.lo, r.hi) = branch_end_interval(e.bracket_lo, e.bracket_hi, high, bits, span);
    c.lo = parse_decimal("certify", r.lo);
    c.hi = parse_decimal("certify", r.hi);
    c.high_end = high;
    if (one_sided) r.certificate = certify_branch_end(c);
    if (model.wall.shape != WallShape::piecewise) {
      // The two-sided proof is built on the piecewise wall's margins (knots, corners, the
      // flight's clearance at a knot); a smooth wall's grazing is a tangency, not one of them.
      r.two_sided.reason = "the two-sided proof of a border collision knows only piecewise-linear walls";
      r.two_sided.statement = "Not certified: " + r.two_sided.reason + ". Nothing is claimed about a* beyond the one-sided bound.";
      return r;
    }
    BorderCollisionQuestion bq;
    bq.end = c;
    if (e.margin >= 0) bq.margin = static_cast<Margin>(e.margin);
    bq.bits = std::max<long>(bits, 128);
    bq.max_bits = 2 * bq.bits;
    r.two_sided = certify_border_collision(bq);
    if (r.two_sided.certified) {
      const mpq_class lo = parse_decimal("certify", Tr::to_string(e.bracket_lo)).value();
      const mpq_class hi = parse_decimal("certify", Tr::to_string(e.bracket_hi)).value();
      r.bracket_contains = lo <= r.two_sided.lo && r.two_sided.hi <= hi;
    }
    return r;
  };
  CertifiedBranchEnds ends;
  ends.low = one(b.low, false);
  ends.high = one(b.high, true);
  return ends;
}

}  // namespace bouncer
