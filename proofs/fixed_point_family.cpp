// Proof: the fixed-point family of the constant-restitution model (paper sec. II.B.1, eq. 5).
//
// Paper: for a = 8(1+eps)/(p(1-eps)), p = 1, 2, ..., every (theta*, v*) with theta* in
// (0, 1/2) and v* = 4(1+eps)/(1-eps) is a fixed point; its Jacobian has eigenvalues 1, eps^2.
//
// Derivation (by hand). Start on the upward segment, theta in (0,1/2), v = v* = ap/2. The
// particle's height above its start is x(s) = v s - a s^2/2 = (a/2) s (p - s).
//  * Landing after p periods on the upward segment: 4 theta - 1 + v s - a s^2/2 =
//    4(theta + s - p) - 1, i.e. (v - 4) s - a s^2/2 + 4p = 0. Its roots have product
//    -8p/a < 0, so its only positive root is s = p when v = ap/2: theta' = theta exactly,
//    v^- = v - ap = -v*, relative speed v* + 4, v' = 4 + eps (v* + 4) = v* iff
//    v* (1 - eps) = 4 (1 + eps).
//  * No earlier contact: on the first (upward) segment the gap is s((a/2)(p - s) - 4),
//    positive for s < p - 8/a = 2p eps/(1+eps). The segment ends at s = 1/2 - theta, so the
//    flight leaves it iff theta > theta_p := 1/2 - 2p eps/(1+eps). Otherwise the particle
//    lands on the same upward segment at s = 2p eps/(1+eps): NOT a fixed point. On later
//    segments the gap is concave and positive at their ends, hence positive inside.
//  So the family is theta in (max(0, theta_p), 1/2): all of (0,1/2) iff eps >= 1/(4p - 1).
//  * Jacobian on this branch: the landing equation F(s, v) = (v-4)s - a s^2/2 + 4p does
//    not involve theta, so s = s(v) with s'(v) = -F_v/F_s = s/(a s - (v - 4)) = p/(v*+4);
//    theta' = theta + s(v) - p, v' = 4 + eps(a s(v) - v + 4):
//        J = [[1, p/(v*+4)], [0, eps (a p/(v*+4) - 1)]] = [[1, p/(v*+4)], [0, eps^2]]
//    since a p/(v*+4) - 1 = (v* - 4)/(v* + 4) = eps. Eigenvalues 1 and eps^2.
//
// Computation (rigorous): for each (eps, p), the interval step ImpactMap<Mpfi> is applied to
// boxes Theta x {v*} covering [theta_p + delta, 1/2 - delta]; each box must give a single
// impact on the upward segment after exactly p periods (the branch above, decided for every
// point of the box) whose image enclosure contains (Theta, v*) (consistency), and thin
// sample points must map to themselves within 2^-(bits/2) (v*+1). With the branch fixed,
// the algebra above makes the map the identity on each point (the exact identities are
// checked in exact rational arithmetic). Where theta_p > 0, [delta, theta_p - delta] is
// covered the same way, proving there is NO fixed point (the impact is on the same upward
// segment, theta' - theta = 2p eps/(1+eps)). The Jacobian is enclosed by interval
// forward-mode AD through the same step (Dual<Mpfi>) at sample points and compared with the
// hand formula; the eigenvalue enclosures must contain 1 and eps^2.
#include <gmpxx.h>

#include <string>
#include <vector>

#include "bouncer/analysis/periodic.hpp"
#include "certificate.hpp"
#include "interval_jacobian.hpp"

using namespace proofs;
using bouncer::EventKind;
using bouncer::ImpactMap;
using bouncer::Law;
using bouncer::State;
using bouncer::StepResult;

namespace {

const char* const kClaim =
    "eq. (5): for a = 8(1+eps)/(p(1-eps)), every theta* in (0,1/2) with v* = 4(1+eps)/(1-eps) is a "
    "fixed point (impact on the upward wall every p periods); eigenvalues 1 and eps^2";
const char* const kMethod =
    "ImpactMap<Mpfi> on boxes Theta x {v*} covering [theta_p+delta, 1/2-delta] (adaptive bisection), "
    "branch certified per box + exact rational identities on that branch; Jacobian by interval "
    "forward-mode AD (Dual<Mpfi>) through the same step vs the hand-derived formula";
const char* const kConclusion =
    "Fixed points (theta, 4(1+eps)/(1-eps)) at a = 8(1+eps)/(p(1-eps)) exist exactly for theta in "
    "(max(0, 1/2 - 2p eps/(1+eps)), 1/2) (and theta = 0 by the corner convention): all of (0,1/2) iff "
    "eps >= 1/(4p-1); eigenvalues 1 and eps^2 confirmed.";

struct Family {
  long num, den;  // eps = num/den
  int p;
};
const std::vector<Family> kFamilies = {{1, 2, 1}, {1, 2, 2}, {1, 2, 3}, {1, 3, 1}, {1, 3, 2},
                                       {1, 3, 3}, {9, 10, 1}, {9, 10, 2}, {9, 10, 3}, {1, 5, 1},
                                       {1, 5, 2}, {1, 5, 3}};

std::string eps_text(const Family& f) { return std::to_string(f.num) + "/" + std::to_string(f.den); }
std::string family_text(const Family& f) { return "eps=" + eps_text(f) + " p=" + std::to_string(f.p); }

// One family of eq. (5), exact and enclosed: eps, a, v* and theta_p = max(0, 1/2 - 2p eps/(1+eps)).
struct Exact {
  mpq_class eps, a, vstar, theta_p;
  Mpfi A, E, V;
};
Exact exact(const Family& f, long bits) {
  const mpq_class eps(f.num, f.den);
  // The library's eq. 5 and family start, the functions every command uses, checked here.
  const mpq_class a = bouncer::paper::fixed_point_a(eps, f.p);
  const mpq_class vstar = bouncer::paper::fixed_point_v(eps);
  const mpq_class theta_p = bouncer::fixed_point_theta_min(eps, f.p);
  return {eps, a, vstar, theta_p, qi(a, bits), qi(eps, bits), qi(vstar, bits)};
}

// True when some family is restricted (theta_p > 0): the paper's (0,1/2) is then corrected.
bool any_family_restricted() {
  for (const Family& f : kFamilies)
    if (exact(f, 64).theta_p > 0) return true;
  return false;
}

// (theta, v*) is fixed for every theta in [theta_p + delta, 1/2 - delta]: the exact identities
// of the branch hold in rationals, each box of the cover steps on that branch (impact on the
// upward segment after p periods) with an image enclosure containing (Theta, v*) (the exact
// image is the box itself). Appends to `line`; false if not certified.
bool check_fixed_on_branch(const Family& f, const Exact& x, const ImpactMap<Mpfi>& map, const CoverPlan& plan,
                           long bits, std::string& line) {
  const mpq_class &eps = x.eps, &a = x.a, &vstar = x.vstar;
  const bool exact_ok = vstar == a * f.p / 2 && (vstar - 4) * f.p - a * f.p * f.p / 2 + 4 * f.p == 0 &&
                        4 + eps * (vstar + 4) == vstar && eps * (a * f.p / (vstar + 4) - 1) == eps * eps;
  auto fixed_check = [&](const Mpfi& box) -> std::string {
    StepResult<Mpfi> r;
    std::string why = try_step(map, State<Mpfi>{box, x.V}, r);
    if (!why.empty()) return why;
    if (r.kind != EventKind::impact || r.segment != 0 || r.periods != f.p) return "other branch";
    if (!r.next.v.contains(x.V) || !r.next.theta.contains(box)) return "image enclosure misses (Theta, v*)";
    return "";
  };
  Cover fixed;
  cover(qr(x.theta_p + plan.delta, bits), qr(mpq_class(1, 2) - plan.delta, bits), plan.initial, plan.depth,
        fixed_check, fixed);
  line += family_text(f) + " a=" + qs(a) + " v*=" + qs(vstar) + ": theta_p=" + qs(x.theta_p) +
          "; fixed on [theta_p+delta, 1/2-delta]: " + describe(fixed);
  if (!exact_ok) line += " EXACT IDENTITY FAILED";
  return fixed.complete() && exact_ok;
}

// No fixed point for theta in [delta, theta_p - delta] (when theta_p > 0): the step's image of
// each box is certainly not (theta, v*). Where the library step is undecided (only at the
// sticking threshold), the first collision is certified with the sticking test disabled
// (collapse constant < 0): it is on the same upward segment at theta + 2p eps/(1+eps); after
// it the state is that collision's, or, if the chatter collapses, the release state (1/2, 4):
// v = 4 != v*. Appends to `line`; false if not certified.
bool check_not_fixed_below(const Family& f, const Exact& x, const ImpactMap<Mpfi>& map, const CoverPlan& plan,
                           long bits, std::string& line) {
  bouncer::Model<Mpfi> ns = triangle_model(Law::constant, x.A, x.E, Mpfi(1, bits), bits);
  ns.collapse = Mpfi(-1, bits);
  ImpactMap<Mpfi> nostick_map(ns);
  long nostick = 0;
  const mpq_class shift = 2 * f.p * x.eps / (1 + x.eps);
  auto not_fixed = [&](const Mpfi& box) -> std::string {
    StepResult<Mpfi> r;
    std::string why = try_step(map, State<Mpfi>{box, x.V}, r);
    if (why.empty()) {
      if (disjoint(r.next.theta, box) || disjoint(r.next.v, x.V)) return "";
      return "image overlaps (Theta, v*)";
    }
    why = try_step(nostick_map, State<Mpfi>{box, x.V}, r);
    if (!why.empty()) return why;
    if (r.kind != EventKind::impact || r.segment != 0 || r.periods != 0) return "other branch";
    if (!disjoint(r.next.theta, box)) return "first collision overlaps the box";
    ++nostick;
    return "";
  };
  Cover nf;
  cover(qr(plan.delta, bits), qr(x.theta_p - plan.delta, bits), plan.initial, plan.depth, not_fixed, nf);
  line += "; NOT fixed on [delta, theta_p-delta] (same-segment impact after " + qs(shift) + "): " + describe(nf);
  if (nostick) line += " (" + std::to_string(nostick) + " at the sticking threshold via the first collision)";
  return nf.complete();
}

// Thin sample points map to themselves within 2^-(bits/2) (v*+1).
bool check_thin_points_fixed(const Exact& x, const ImpactMap<Mpfi>& map, long bits) {
  const Mpfi tol = exp(log(Mpfi(2, bits)) * (-(bits / 2))) * (x.V + 1);
  bool ok = true;
  for (int k = 1; k <= 3; ++k) {
    const Mpfi th = qi(x.theta_p + (mpq_class(1, 2) - x.theta_p) * (2 * k - 1) / 6, bits);
    StepResult<Mpfi> r;
    if (!try_step(map, State<Mpfi>{th, x.V}, r).empty() || !le(abs(r.next.theta - th), tol) ||
        !le(abs(r.next.v - x.V), tol))
      ok = false;
  }
  return ok;
}

// The family is exactly (theta_p, 1/2) x {v*} (corrected where theta_p > 0, confirmed if no
// family is restricted): per family, fixed on the branch above theta_p, not fixed below it,
// and thin points fixed.
void check_family_domain(SubClaim& sub, bool restricted, const CoverPlan& plan, long bits) {
  bool ok = true;
  for (const Family& f : kFamilies) {
    const Exact x = exact(f, bits);
    ImpactMap<Mpfi> map(triangle_model(Law::constant, x.A, x.E, Mpfi(1, bits), bits));
    std::string line;
    if (!check_fixed_on_branch(f, x, map, plan, bits, line)) ok = false;
    if (x.theta_p > 0 && !check_not_fixed_below(f, x, map, plan, bits, line)) ok = false;
    sub.evidence.push_back(line);
    if (!check_thin_points_fixed(x, map, bits)) {
      ok = false;
      sub.evidence.push_back(family_text(f) + ": thin-point identity check FAILED");
    }
  }
  if (ok)
    sub.settle(restricted ? Verdict::corrected : Verdict::confirmed,
               "(theta, v*) is a fixed point for every theta in (theta_p, 1/2), theta_p = max(0, 1/2 - 2p eps/(1+eps)); "
               "the whole (0,1/2) only when eps >= 1/(4p-1). For 0 < theta < theta_p the particle hits the upward "
               "wall again after 2p eps/(1+eps) (certified: not a fixed point), e.g. eps = 0.2, p = 1: only (1/6, 1/2).");
}

// Eigenvalues 1 and eps^2: at 3 points per family the interval-AD Jacobian of one step is on
// the branch and contains the hand formula J = [[1, p/(v*+4)], [0, eps^2]] (entries 1 and 0
// contained, the others met), and its eigenvalue enclosures contain 1 and eps^2. Where the
// step's jump shortcut is undecided, the same map is walked segment by segment.
void check_eigenvalues(SubClaim& sub, long bits) {
  bool ok = true;
  for (const Family& f : kFamilies) {
    const Exact x = exact(f, bits);
    ImpactMap<IDual> dmap(lift(triangle_model(Law::constant, x.A, x.E, Mpfi(1, bits), bits)));
    ImpactMap<IDual> dwalk(lift(triangle_model(Law::constant, x.A, x.E, Mpfi(1, bits), bits, 1L << 20)));
    const Mpfi j12 = qi(mpq_class(f.p) / (x.vstar + 4), bits), e2 = x.E * x.E;
    int sampled = 0;
    std::string jtext;
    for (int k = 1; k <= 3; ++k) {
      const mpq_class th = x.theta_p + (mpq_class(1, 2) - x.theta_p) * k / 4;
      LinearizedSteps L;
      try {
        L = linearize(dmap, qi(th, bits), x.V, 1);
      } catch (const bouncer::Undecided&) {
        try {
          L = linearize(dwalk, qi(th, bits), x.V, 1);
        } catch (const bouncer::Undecided& u) {
          ok = false;
          sub.evidence.push_back(family_text(f) + " theta=" + qs(th) + ": AD step undecided: " + u.what());
          continue;
        }
      }
      auto ev = eigenvalues(L.J);
      const bool point_ok = L.kinds[0] == EventKind::impact && L.periods[0] == f.p && ev &&
                            ev->hi.contains(Mpfi(1, bits)) && ev->lo.contains(e2) && !disjoint(L.J.a12, j12) &&
                            L.J.a11.contains(Mpfi(1, bits)) && L.J.a21.contains(Mpfi(0, bits)) &&
                            !disjoint(L.J.a22, e2);
      if (!point_ok) ok = false;
      ++sampled;
      if (k == 2)
        jtext = family_text(f) + " theta=" + qs(th) + ": J in " + describe(L.J) +
                (ev ? "; eigenvalues in " + s(ev->hi) + " and " + s(ev->lo) : "") + "; hand formula [[1, " +
                qs(mpq_class(f.p) / (x.vstar + 4)) + "], [0, " + qs(x.eps * x.eps) + "]]";
    }
    if (f.num == 1 && f.den == 2 && f.p == 1) sub.evidence.push_back(jtext);
    if (sampled < 3) ok = false;
  }
  if (ok)
    sub.settle(Verdict::confirmed,
               "J = [[1, p/(v*+4)], [0, eps^2]] (exact on the branch; eps(ap/(v*+4)-1) = eps^2 in exact "
               "rationals); interval-AD enclosures contain its entries 1 and 0 and overlap the others at 3 points per family, eigenvalues enclose 1 and eps^2");
}

// The ends of the open interval (p = 1 families): theta = 1/2 is certainly not fixed; theta = 0
// is an impact exactly at the corner theta = 0 = 1, decided by intervals only when the
// arithmetic is exact, so it is reported as it comes (the exact argument is in the header).
void check_ends(SubClaim& sub, long bits) {
  bool ok = true;
  for (const Family& f : kFamilies) {
    if (f.p != 1) continue;
    const Exact x = exact(f, bits);
    ImpactMap<Mpfi> map(triangle_model(Law::constant, x.A, x.E, Mpfi(1, bits), bits));
    StepResult<Mpfi> rh, r0;
    const Mpfi half = qi(mpq_class(1, 2), bits);
    const std::string whyh = try_step(map, State<Mpfi>{half, x.V}, rh);
    const bool half_ok = whyh.empty() && (disjoint(rh.next.v, x.V) || disjoint(rh.next.theta, half));
    if (!half_ok) ok = false;
    const std::string why0 = try_step(map, State<Mpfi>{Mpfi(0, bits), x.V}, r0);
    std::string t0;
    if (!why0.empty()) t0 = "interval step " + why0 + " (impact exactly at the corner)";
    else t0 = "-> (" + s(r0.next.theta) + ", " + s(r0.next.v) + ")" +
              (r0.next.theta.contains(Mpfi(0, bits)) && r0.next.v.contains(x.V) ? ": fixed (exact arithmetic decided the corner)" : "");
    sub.evidence.push_back("eps=" + eps_text(f) + " p=1: (1/2, v*) -> " +
                           (whyh.empty() ? "(" + s(rh.next.theta) + ", " + s(rh.next.v) + "), not (1/2, v*)" : whyh) +
                           "; (0, v*) " + t0);
  }
  if (ok)
    sub.settle(Verdict::confirmed,
               "the claim is about the open interval and holds on all of it (up to theta_p): covered by boxes on "
               "[theta_p+delta, 1/2-delta], the strips of width delta at the ends by the analytic argument above (gap "
               "positivity, unchanged there). theta = 1/2 is not in the family (wall velocity -4 there; certified "
               "image != (1/2, v*)). theta = 0: if theta_p = 0 the return is an impact exactly at the corner theta = 0 = 1, "
               "fixed with the right-continuous convention u(0) = +4 (exact argument; interval arithmetic decides it only "
               "when the arithmetic is exact, e.g. eps = 1/3); if theta_p > 0 it is not fixed (eps = 1/5: sticking, certified).");
}

}  // namespace

int main(int argc, char** argv) {
  Certificate cert("fixed_point_family", kClaim, kMethod, 128, argc, argv);
  const CoverPlan plan = cover_plan(cert.full(), 12, 14, 24, 36);
  cert.note(plan.text() +
            "; box test: branch (impact, upward segment, p periods) + image enclosure contains (Theta, v*); "
            "thin-point test: |theta'-theta|, |v'-v*| <= 2^-(bits/2) (v*+1) at 3 points per family");
  SubClaim& family = cert.add("family", "eq. (5): theta* in (0,1/2) arbitrary, v* = 4(1+eps)/(1-eps), a = 8(1+eps)/(p(1-eps))");
  SubClaim& eigen = cert.add("eigenvalues", "Df has eigenvalues 1 and eps^2 on the family");
  SubClaim& ends = cert.add("ends", "(open interval) behaviour as theta* -> 0 and theta* -> 1/2");

  const bool restricted = any_family_restricted();  // some theta_p > 0: (0,1/2) is corrected
  check_family_domain(family, restricted, plan, cert.bits());
  check_eigenvalues(eigen, cert.bits());
  check_ends(ends, cert.bits());

  cert.conclude(restricted ? Verdict::corrected : Verdict::confirmed, kConclusion);
  return cert.finish();
}
