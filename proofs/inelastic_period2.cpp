// Proof: the inelastic period-2 family, p = 1, k = 0 (paper sec. II.B.1, eq. 10).
//
// Paper: for a = 32/(1-eps) - 16/(1+eps^2) - 8, theta_n in (0,1/2) and
// v_n = 4(eps-3)(eps^3-eps^2-3eps-3)/((eps-1)^2(eps^2+1)) (also written
// v_n = a(eps^2-4)/((eps-1)(eps+1)^2) + 4), two impacts on the upward wall per period;
// lambda1 = 1, lambda2 = 2eps^2 - eps^5 sqrt(eps^2+1)/sqrt(eps^6-2eps^3+2eps+1), and
// lambda2 = 1 at eps* ~ 0.829146: stable below, unstable above.
//
// Derivation (by hand). Both impacts on the upward wall, in the same period (k = 0), then
// the next period (p = 1): tau1 = Delta theta, tau2 = 1 - tau1. With w = v_n - 4:
//   flight 1 stays on the upward segment: v tau1 - a tau1^2/2 = 4 tau1, so tau1 = 2w/a, and
//   v_{n+1} = 4 + eps w (in the wall's frame the relative speed is just multiplied by eps);
//   impact 2 (E4): w = eps(a tau2 - eps w), so a tau2 = w(1+eps^2)/eps;
//   tau1 + tau2 = 1: w = eps a/(1+eps)^2, i.e.
//        v_n = 4 + eps a/(1+eps)^2 = 4 + 8 eps (1+eps)/((1-eps)(1+eps^2));
//   flight 2 (E2): (v_{n+1}-4) tau2 - a tau2^2/2 + 4 = 0 gives w^2 (1-eps^4) = 8 eps^2 a, so
//        a = 8 (1+eps)^3/((1-eps)(1+eps^2)) = 32/(1-eps) - 16/(1+eps^2) - 8   (paper's a: right).
//   Admissibility: flight 1 must end inside the segment, theta_n + 2eps/(1+eps)^2 < 1/2, and
//   flight 2 must leave it, 2 eps w/a > 1/2 - theta_{n+1}, i.e. theta_n > 1/2 - 2eps/(1+eps);
//   the later segments cannot be hit (concave gap, positive at their ends). So
//        theta_n in (max(0, 1/2 - 2eps/(1+eps)), (1-eps)^2/(2(1+eps)^2)),  not (0, 1/2).
//   The paper's two v_n expressions agree with each other but not with this (eps = 1/2:
//   148 against 13.6): v_n = a(4-eps^2)/((1-eps)(1+eps)^2) + 4 is neither root of the
//   paper's own eq. (8) at k = 0, whose roots are 4 + eps a/(1+eps)^2 and 4 + eps a/(1-eps^2).
//   Jacobian of the 2-step map on this branch: step 1 theta1 = theta + 2(v-4)/a,
//   v1 = 4 + eps(v-4); step 2's landing equation (v1-4) s - a s^2/2 + 4 = 0 has no theta, so
//   s = s(v1), s' = s/sqrt(u^2 + 8a) with u = v1 - 4; theta2 = theta1 + s - 1,
//   v2 = 4 + eps(a s - v1 + 4). Hence d(v2)/d(theta) = 0, d(theta2)/d(theta) = 1 (upper
//   triangular, as the paper says) and
//        lambda2 = dv2/dv = eps^2 (a s' - 1) = eps^2 u / sqrt(u^2 + 8a) = eps^4,
//   because sqrt(u^2 + 8a) = w/eps on the orbit (from w^2(1-eps^4) = 8 eps^2 a). So
//   0 < lambda2 < 1 for every eps in (0,1): there is no bifurcation lambda2 = 1 at eps*.
//
// Computation (rigorous): exact rational identities at eps in {1/5, 1/2, 17/20, 9/10};
// ImpactMap<Mpfi> on boxes Theta x {v_n} covering [theta_lo + delta, theta_hi - delta]
// (two steps: impact on the upward segment in the same period, then after one period; the
// image contains the start box; thin points return within 2^-(bits/2)); the paper's v_n
// certified not to return; interval AD (Dual<Mpfi>) Jacobian of the 2-step map enclosing
// eigenvalues 1 and eps^4 and excluding the paper's lambda2; an MPFR finite-difference sanity
// check; eps* as the certified root of the paper's lambda2(eps) = 1 by interval Newton.
#include <gmpxx.h>

#include <string>
#include <vector>

#include "certificate.hpp"
#include "interval_jacobian.hpp"

using namespace proofs;
using bouncer::EventKind;
using bouncer::ImpactMap;
using bouncer::Law;
using bouncer::State;
using bouncer::StepResult;

namespace {

// The paper's lambda2 and its derivative (forward-mode, interval).
IDual paper_lambda2(const IDual& e) {
  const IDual e2 = e * e, e3 = e2 * e, e5 = e3 * e2, e6 = e3 * e3;
  return 2 * e2 - e5 * sqrt(e2 + 1) / sqrt(e6 - 2 * e3 + 2 * e + 1);
}
Mpfi paper_lambda2(const Mpfi& e) { return paper_lambda2(IDual(e)).v; }

bouncer::Model<Mpfr> mpfr_model(const mpq_class& a, const mpq_class& eps, long bits) {
  bouncer::ModelSpec spec;
  spec.law = Law::constant;
  spec.wall = bouncer::parse_wall("wall", "triangle");
  bouncer::Model<Mpfr> m = bouncer::make_model<Mpfr>(spec, bits);
  m.a = qr(a, bits);
  m.eps = qr(eps, bits);
  m.collapse = m.a * (1 - m.eps) / 2;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  Certificate cert(
      "inelastic_period2",
      "eq. (10), p = 1, k = 0: theta_n in (0,1/2), v_n = 4(eps-3)(eps^3-eps^2-3eps-3)/((eps-1)^2(eps^2+1)) for "
      "a = 32/(1-eps) - 16/(1+eps^2) - 8; lambda2 = 2eps^2 - eps^5 sqrt(eps^2+1)/sqrt(eps^6-2eps^3+2eps+1); "
      "lambda2 = 1 at eps* ~ 0.829146 (unstable above)",
      "exact rationals; ImpactMap<Mpfi> two-step images of boxes covering the theta-domain; interval AD "
      "Jacobian (Dual<Mpfi>); MPFR finite differences (sanity only); interval Newton for eps*",
      128, argc, argv);
  const long bits = cert.bits();
  const CoverPlan plan = cover_plan(cert.full(), 16, 14, 36, 24);
  const auto [delta_exp, depth, initial, delta] = plan;
  cert.note(plan.text());

  SubClaim& sa = cert.add("a-formula", "a = 32/(1-eps) - 16/(1+eps^2) - 8");
  SubClaim& sv = cert.add("v_n-formula", "v_n = 4(eps-3)(eps^3-eps^2-3eps-3)/((eps-1)^2(eps^2+1)) = a(eps^2-4)/((eps-1)(eps+1)^2) + 4");
  SubClaim& sd = cert.add("theta-domain", "theta_n in (0, 1/2)");
  SubClaim& sl = cert.add("lambda2", "lambda1 = 1, lambda2 = 2eps^2 - eps^5 sqrt(eps^2+1)/sqrt(eps^6-2eps^3+2eps+1) (upper triangular)");
  SubClaim& se = cert.add("eps*", "lambda2 = 1 at eps* ~ 0.829146; stable for eps < eps*, unstable for eps* < eps < 1");

  bool a_ok = true, v_ok = true, d_ok = true, l_ok = true, paper_v_consistent = true;
  long exc_paper = 0, exc_domain = 0;
  Mpfr exc_paper_w(0, 64), exc_domain_w(0, 64);
  const std::vector<std::pair<long, long>> epss = {{1, 5}, {1, 2}, {17, 20}, {9, 10}};
  for (auto [n, dd] : epss) {
    const mpq_class eps(n, dd);
    const std::string et = qs(eps);
    const mpq_class a = 8 * (1 + eps) * (1 + eps) * (1 + eps) / ((1 - eps) * (1 + eps * eps));
    const mpq_class a_paper = 32 / (1 - eps) - 16 / (1 + eps * eps) - 8;
    const mpq_class w = eps * a / ((1 + eps) * (1 + eps)), vn = 4 + w, v1 = 4 + eps * w;
    const mpq_class vp1 = 4 * (eps - 3) * (eps * eps * eps - eps * eps - 3 * eps - 3) / ((eps - 1) * (eps - 1) * (eps * eps + 1));
    const mpq_class vp2 = a_paper * (eps * eps - 4) / ((eps - 1) * (eps + 1) * (eps + 1)) + 4;
    mpq_class th_lo = mpq_class(1, 2) - 2 * eps / (1 + eps);
    if (th_lo < 0) th_lo = 0;
    const mpq_class th_hi = (1 - eps) * (1 - eps) / (2 * (1 + eps) * (1 + eps));
    const mpq_class tau1 = 2 * w / a, tau2 = 1 - tau1, u = v1 - 4;
    // Exact identities of the derivation.
    const bool exact = a == a_paper && w * w * (1 - eps * eps * eps * eps) == 8 * eps * eps * a &&
                       u * tau2 - a * tau2 * tau2 / 2 + 4 == 0 &&           // flight 2 lands after 1 - tau1
                       4 + eps * (a * tau2 - v1 + 4) == vn &&                // impact 2 restores v_n
                       u * u + 8 * a == (w / eps) * (w / eps);               // sqrt(u^2+8a) = w/eps: lambda2 = eps^4
    if (!exact) a_ok = l_ok = false;
    if (vp1 != vp2) paper_v_consistent = false;

    const Mpfi A = qi(a, bits), E = qi(eps, bits), V = qi(vn, bits), VP = qi(vp1, bits);
    ImpactMap<Mpfi> map(triangle_model(Law::constant, A, E, Mpfi(1, bits), bits));
    auto step = [&](const Mpfi& th, const Mpfi& vv, StepResult<Mpfi>& r) {
      return try_step(map, State<Mpfi>{th, vv}, r);
    };
    auto two = [&](const Mpfi& th, const Mpfi& vv, StepResult<Mpfi>& r1, StepResult<Mpfi>& r2) {
      std::string why = step(th, vv, r1);
      return why.empty() ? step(r1.next.theta, r1.next.v, r2) : why;
    };
    // Period 2 on the domain: the branch (same-segment impact, then one period later on the
    // upward segment), image containing the start box.
    auto returns = [&](const Mpfi& box) -> std::string {
      StepResult<Mpfi> r1, r2;
      std::string why = two(box, V, r1, r2);
      if (!why.empty()) return why;
      if (r1.kind != EventKind::impact || r1.segment != 0 || r1.periods != 0) return "step 1: other branch";
      if (r2.kind != EventKind::impact || r2.segment != 0 || r2.periods != 1) return "step 2: other branch";
      if (!r2.next.theta.contains(box) || !r2.next.v.contains(V)) return "image misses the start box";
      return "";
    };
    Cover c;
    cover(qr(th_lo + delta, bits), qr(th_hi - delta, bits), initial, depth, returns, c);
    // Outside the domain, up to 1/2: not period 2 (two-step image disjoint from the start).
    auto no_return = [&](const Mpfi& box) -> std::string {
      StepResult<Mpfi> r1, r2;
      std::string why = two(box, V, r1, r2);
      if (!why.empty()) return why;
      return disjoint(r2.next.theta, box) || disjoint(r2.next.v, V) ? "" : "image overlaps the start box";
    };
    Cover out_hi;
    cover(qr(th_hi + delta, bits), qr(mpq_class(1, 2) - delta, bits), initial, depth, no_return, out_hi);
    if (th_lo > 0) cover(qr(delta, bits), qr(th_lo - delta, bits), initial, depth, no_return, out_hi);
    exc_domain += out_hi.failed;
    mpfr_add(exc_domain_w.get(), exc_domain_w.get(), out_hi.failed_measure.get(), MPFR_RNDU);
    // Thin points inside the domain return within 2^-(bits/2)(v_n+1).
    const Mpfi tol = exp(log(Mpfi(2, bits)) * (-(bits / 2))) * (V + 1);
    bool pts = true;
    for (int k = 1; k <= 3; ++k) {
      const Mpfi th = qi(th_lo + (th_hi - th_lo) * k / 4, bits);
      StepResult<Mpfi> r1, r2;
      if (!two(th, V, r1, r2).empty() || !le(abs(r2.next.theta - th), tol) || !le(abs(r2.next.v - V), tol)) pts = false;
    }
    // The paper's v_n: two steps never return, over the paper's whole (0, 1/2).
    Cover pc;
    auto paper_no_return = [&](const Mpfi& box) -> std::string {
      StepResult<Mpfi> r1, r2;
      std::string why = two(box, VP, r1, r2);
      if (!why.empty()) return why;
      return disjoint(r2.next.theta, box) || disjoint(r2.next.v, VP) ? "" : "image overlaps the start box";
    };
    cover(qr(delta, bits), qr(mpq_class(1, 2) - delta, bits), initial, depth, paper_no_return, pc);

    // The verdicts rest on the certified returns; the no-return covers are supporting
    // evidence and leave isolated boxes (an orbit point exactly at a corner or at the
    // sticking threshold cannot be decided in interval arithmetic): counted and reported.
    if (!c.complete() || !pts) v_ok = d_ok = false;
    if (pc.certified == 0) v_ok = false;
    exc_paper += pc.failed;
    mpfr_add(exc_paper_w.get(), exc_paper_w.get(), pc.failed_measure.get(), MPFR_RNDU);
    sv.evidence.push_back("eps=" + et + ": a = " + qs(a) + " (paper's a: equal), v_n = " + qs(vn) + " (paper: " + qs(vp1) +
                          "), v_{n+1} = " + qs(v1) + "; period 2 on [theta_lo+delta, theta_hi-delta]: " + describe(c) +
                          (pts ? "; 3 thin points return" : "; THIN POINTS FAILED") +
                          "; paper's v_n never returns on [delta, 1/2-delta]: " + describe(pc));
    sd.evidence.push_back("eps=" + et + ": theta_lo = " + qs(th_lo) + ", theta_hi = " + qs(th_hi) +
                          "; not period 2 on [delta, theta_lo-delta] and [theta_hi+delta, 1/2-delta]: " + describe(out_hi));

    // Jacobian of the 2-step map by interval AD at the domain's midpoint.
    try {
      ImpactMap<IDual> dmap(lift(triangle_model(Law::constant, A, E, Mpfi(1, bits), bits, 1L << 20)));
      const Mpfi th = qi((th_lo + th_hi) / 2, bits);
      LinearizedSteps L = linearize(dmap, th, V, 2);
      auto ev = eigenvalues(L.J);
      const Mpfi e4 = E * E * E * E, pl = paper_lambda2(E);
      const bool ok = ev && ev->hi.contains(Mpfi(1, bits)) && ev->lo.contains(e4) && disjoint(ev->lo, pl) &&
                      L.J.a21.contains(Mpfi(0, bits));
      if (!ok) l_ok = false;
      // MPFR central finite difference of v2 in v (sanity only, not part of the proof).
      const long fb = 256;
      ImpactMap<Mpfr> pm(mpfr_model(a, eps, fb));
      Mpfr h(1, fb);
      mpfr_div_2ui(h.get(), h.get(), 80, MPFR_RNDN);
      auto v2 = [&](const Mpfr& v) {
        auto r = pm.step(State<Mpfr>{qr((th_lo + th_hi) / 2, fb), v});
        return pm.step(r.next).next.v;
      };
      const Mpfr vq = qr(vn, fb);
      const Mpfr fd = (v2(vq + h) - v2(vq - h)) / (2 * h);
      sl.evidence.push_back("eps=" + et + ": 2-step J in " + describe(L.J) + "; eigenvalues in " +
                            (ev ? s(ev->hi) + " and " + s(ev->lo) : std::string("?")) + "; eps^4 = " + qs(eps * eps * eps * eps) +
                            "; paper's lambda2 in " + s(pl) + "; MPFR central difference (h = 2^-80, sanity) " +
                            bouncer::mpfr_to_string(fd.get(), MPFR_RNDN).substr(0, 22));
    } catch (const bouncer::Undecided& u) {
      l_ok = false;
      sl.evidence.push_back("eps=" + et + ": AD step undecided: " + u.what());
    }
  }

  if (a_ok) {
    sa.verdict = Verdict::confirmed;
    sa.statement = "a = 32/(1-eps) - 16/(1+eps^2) - 8 = 8(1+eps)^3/((1-eps)(1+eps^2)) (exact identity; certified against the map)";
  }
  if (v_ok && a_ok) {
    sv.verdict = Verdict::corrected;
    sv.statement = std::string("v_n = 4 + eps a/(1+eps)^2 = 4 + 8eps(1+eps)/((1-eps)(1+eps^2)), v_{n+1} = 4 + eps^2 a/(1+eps)^2") +
                   " (derived for all eps; certified at eps = 1/5, 1/2, 17/20, 9/10: two steps return). The paper's two expressions " +
                   (paper_v_consistent ? "agree with each other (exact) but" : "do not even agree with each other and") +
                   " are certified not to return after two steps for theta in [delta, 1/2-delta]" +
                   (exc_paper ? " except " + std::to_string(exc_paper) + " boxes of total width " + s(exc_paper_w) +
                                    " around isolated corner events (undecidable there)" : std::string()) +
                   " (e.g. eps = 1/2: 148 vs the true 68/5 = 13.6)";
  }
  if (d_ok) {
    sd.verdict = Verdict::corrected;
    sd.statement = "theta_n in (max(0, 1/2 - 2eps/(1+eps)), (1-eps)^2/(2(1+eps)^2)) (theta_n the impact with the larger "
                   "velocity; theta_{n+1} = theta_n + 2eps/(1+eps)^2); at eps = 1/5, 1/2, 17/20, 9/10: certified period 2 on "
                   "[theta_lo+delta, theta_hi-delta]; "
                   "certified NOT period 2 on the rest of [delta, 1/2-delta]" +
                   (exc_domain ? " except " + std::to_string(exc_domain) + " boxes of total width " + s(exc_domain_w) +
                                     " at isolated corner/sticking-threshold events (undecidable there)" : std::string());
  }

  // eps*: the root of the paper's lambda2(eps) = 1 by interval Newton.
  {
    Mpfi X(dec("0.8291", bits).lower(), dec("0.8292", bits).upper());
    bool unique = false;
    for (int it = 0; it < 60; ++it) {
      const Mpfi m = point(X.mid());
      const Mpfi gm = paper_lambda2(m) - 1;
      const IDual gX = paper_lambda2(IDual::variable(X, 0));
      const Mpfi N = m - gm / gX.d[0];
      if (mpfi_has_zero(gX.d[0].get())) break;
      if (lt(point(X.lower()), N) && lt(N, point(X.upper()))) unique = true;  // N(X) in int(X)
      const Mpfi Y = intersect(N, X);
      if (!(Y.width() < X.width())) { X = Y; break; }
      X = Y;
    }
    Mpfr w = X.width();
    const bool digits15 = unique && w < Mpfr(1, bits) / Mpfr(1000000000000000L, bits) / 10;
    const Mpfi true_l2 = X * X * X * X;
    if (digits15) {
      se.verdict = Verdict::corrected;
      se.statement = "the paper's formula equals 1 exactly once in [0.8291, 0.8292], at eps* in " + s(X) +
                     " (interval Newton: N(X) inside X, unique root), but that formula is not the multiplier: the true "
                     "lambda2 = eps^4 is in " + s(true_l2) + " there, and eps^4 < 1 for all eps in (0,1): no bifurcation "
                     "of this family at any eps in (0,1); it is (marginally) stable for every eps, e.g. at eps = 17/20 and "
                     "9/10 above eps* (certified above)";
    }
    se.evidence.push_back("interval Newton on 2eps^2 - eps^5 sqrt(eps^2+1)/sqrt(eps^6-2eps^3+2eps+1) - 1 (derivative by "
                          "interval forward-mode AD): enclosure " + s(X) + ", width " + s(w));
  }
  if (l_ok) {
    sl.verdict = Verdict::corrected;
    sl.statement = "lambda1 = 1 (confirmed, upper triangular confirmed), lambda2 = eps^4 (derived; exact in rationals on the "
                   "branch; interval-AD eigenvalue enclosures contain eps^4 and exclude the paper's value at eps = 1/5, 1/2, "
                   "17/20, 9/10)";
  }
  cert.conclude(Verdict::corrected,
                "For p = 1, k = 0 and a = 32/(1-eps) - 16/(1+eps^2) - 8 (correct), the period-2 family is "
                "theta_n in (max(0, 1/2 - 2eps/(1+eps)), (1-eps)^2/(2(1+eps)^2)), v_n = 4 + 8eps(1+eps)/((1-eps)(1+eps^2)); "
                "its multipliers are 1 and eps^4, so it is (marginally) stable for all eps in (0,1); the paper's "
                "eps* (root of its lambda2 formula) is not a bifurcation.");
  return cert.finish();
}
