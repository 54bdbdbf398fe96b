// Proof: the elastic period-2 "up/up" family (paper sec. II.B.1, eqs. 8, 9, 33).
//
// Paper: for eps = 1, period-2 orbits with both impacts on the upward wall,
// v_n = ap/4 + 4 - 8k/p, theta_n in (0,1/2), where a solves eq. (33); for p = 1, k = 0,
// a = (22 +- 26)/3, i.e. a = 16, and the second eigenvalue is lambda2 = 1/3.
//
// Derivation (by hand), from the paper's own implicit equations for this orbit type, with
// tau1 = Delta theta + k, tau2 = p - tau1 and both impacts on the upward wall (velocity 4):
//   (E1) v tau1 - a tau1^2/2 = 4 Delta theta          (flight 1)
//   (E2) v1 tau2 - a tau2^2/2 = -4 Delta theta        (flight 2)
//   (E3) v1 = 8 - v + a tau1,  v = 8 - v1 + a tau2    (elastic impacts, eps = 1)
// E3 gives v + v1 = 8 + a tau1 = 8 + a tau2, so tau1 = tau2 = p/2 =: tau; E1 + E2 gives
// (v + v1) tau - a tau^2 = 0, i.e. 8 tau = 0. No solution with tau > 0: there is NO elastic
// period-2 orbit with both impacts on the upward wall, for any p and k. (Energy: an elastic
// impact on a wall moving up at speed 4 raises E = v^2/2 + a x by 4 (v+ - v-) > 0, so no
// periodic orbit can have all its impacts on the upward wall.) Eqs. (8)-(9) are satisfied by
// (a, v) = (16, 8), but (E2) is not (residual 4): the reduction to (8)-(9) lost this.
// Admissibility: E1 with k = 0 gives Delta theta = 2(v-4)/a = p/2 = 1/2, so
// theta_{n+1} = theta_n + 1/2 >= 1/2: the paper's condition theta_{n+1} < 1/2 fails.
// What the map does at a = 16 from (theta, 8): v = a/2 so the flight lasts exactly 1 period
// and returns to the same phase with v- = -8: v' = 8 + 8 = 16; then 2 periods, v'' = 24, ...
// (Fermi acceleration at constant phase).
//
// Computation (rigorous): exact rational arithmetic for eq. (33), (8), (9), (E2) and the
// paper's lambda2 formula; ImpactMap<Mpfi> on boxes Theta x {v_n} covering [delta, 1/2-delta]
// for every (p, k) with p <= 3 that eq. (33) admits: two steps never return (the image box
// is disjoint from the start box); thin points: (theta, 8) -> (theta, 16) -> (theta, 24).
// The 2-step Jacobian at (1/4, 8) by interval AD (Dual<Mpfi>), for the record.
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

const char* const kClaim =
    "eqs. (8), (9), (33): elastic (eps = 1) period-2 orbits with both impacts on the upward wall, "
    "theta_n in (0,1/2), v_n = ap/4 + 4 - 8k/p with a from (33); p = 1, k = 0: a = 16, lambda2 = 1/3";
const char* const kMethod =
    "exact rational arithmetic on the paper's equations; ImpactMap<Mpfi> two-step images of boxes "
    "Theta x {v_n} covering [delta, 1/2-delta] (adaptive bisection); interval AD Jacobian";
const char* const kConclusion =
    "There is no elastic period-2 orbit with both impacts on the upward wall (for any p, k): the paper's "
    "implicit equations force 8 tau = 0. At a = 16 (p = 1, k = 0) the start (theta, 8) accelerates "
    "(v = 8, 16, 24, ... at constant phase), and theta_{n+1} = theta_n + 1/2 would violate theta_{n+1} < 1/2.";

// The paper's case p = 1, k = 0: a = 16, v_n = 8 (exact).
const mpq_class kA(16), kV(8), kP(1), kK(0);

// Confirms the arithmetic of eq. (33) at p = 1, k = 0 (roots 16 and -4/3, v_n = 8), exactly,
// and records the residuals of (8), (9) and of the implicit flight equation (E2) at (16, 8):
// (8) and (9) vanish, (E2) does not, which is where the reduction lost the contradiction.
void check_eq33_arithmetic(SubClaim& sub) {
  const mpq_class &a = kA, &v = kV, &p = kP, &k = kK;
  const bool roots = 3 * a * a / 4 - 11 * a - 16 == 0 && (3 * mpq_class(-4, 3) * mpq_class(-4, 3) / 4 - 11 * mpq_class(-4, 3) - 16) == 0;
  const bool v_ok = a * p / 4 + 4 - 8 * k / p == v;
  const mpq_class eq8 = (v - (8 + a * p) / 2) * (v - (8 + a * p) / 2) - ((v - 4) * (v - 4) + 8 * a * k);
  const mpq_class eq9 = 4 * (v - a * p - 8) + a * p * (a * p - 2 * v) + 4 * ((v - 4) * (v - 4) + 8 * a * k);
  // Paper's implicit equations with Delta theta from E1 (k = 0): Delta theta = 2(v-4)/a.
  const mpq_class dth = 2 * (v - 4) / a, tau1 = dth + k, tau2 = p - tau1;
  const mpq_class v1 = 8 + a * tau1 - v;
  const mpq_class e2 = -a / 2 * tau2 * tau2 + v1 * tau2 + 4 * dth;
  if (roots && v_ok)
    sub.settle(Verdict::confirmed, "3a^2/4 - 11a - 16 = 0 has the roots 16 and -4/3 (exact); v_n = 16/4 + 4 = 8");
  sub.evidence.push_back("eq. (8) residual at (a, v) = (16, 8): " + qs(eq8) + "; eq. (9) residual: " + qs(eq9) +
                         "; implicit flight equation (E2) residual: " + qs(e2) + " (must be 0 for an orbit)");
}

// Refutes admissibility: flight 1 (E1, k = 0) takes Delta theta = 2(v_n - 4)/a, which is
// exactly 1/2 at (16, 8), so theta_{n+1} = theta_n + 1/2 >= 1/2 for every theta_n.
void check_admissibility(SubClaim& sub) {
  if (2 * (kV - 4) / kA == mpq_class(1, 2))
    sub.settle(Verdict::refuted,
               "flight 1 (E1, k = 0) gives Delta theta = 2(v_n-4)/a = 1/2 exactly, so theta_{n+1} = theta_n + 1/2 "
               ">= 1/2 for every theta_n in (0,1/2): the orbit is not admissible");
}

// Two steps of the map from (theta, v_n) never come back to the start box, for every theta in
// [delta, 1/2 - delta] (cover with bisection); and the thin points (j/8, v_n) accelerate:
// v -> 2v -> 3v at the same phase. Appends one evidence line; false if the cover is incomplete.
bool check_no_return(SubClaim& sub, int p, int k, const mpq_class& a, const mpq_class& v, const CoverPlan& plan,
                     long bits) {
  const Mpfi A = qi(a, bits), V = qi(v, bits);
  ImpactMap<Mpfi> map(triangle_model(Law::elastic, A, Mpfi(1, bits), Mpfi(1, bits), bits));
  auto step = [&](const Mpfi& th, const Mpfi& vv, StepResult<Mpfi>& res) {
    return try_step(map, State<Mpfi>{th, vv}, res);
  };
  auto no_return = [&](const Mpfi& box) -> std::string {
    StepResult<Mpfi> r1, r2;
    std::string why = step(box, V, r1);
    if (!why.empty()) return why;
    why = step(r1.next.theta, r1.next.v, r2);
    if (!why.empty()) return why;
    if (disjoint(r2.next.theta, box) || disjoint(r2.next.v, V)) return "";
    return "two-step image overlaps the start box";
  };
  Cover c;
  cover(qr(plan.delta, bits), qr(mpq_class(1, 2) - plan.delta, bits), plan.initial, plan.depth, no_return, c);
  // Thin points: the exact orbit (theta, v) -> (theta, 2v) -> (theta, 3v) (a = 16/p, v = 8).
  std::string pts;
  bool accel = true;
  for (int j = 1; j <= 3; ++j) {
    const Mpfi th = qi(mpq_class(j, 8), bits);
    StepResult<Mpfi> r1, r2;
    if (!step(th, V, r1).empty() || !step(r1.next.theta, r1.next.v, r2).empty()) { accel = false; continue; }
    const bool ok = r1.next.v.contains(2 * V) && r2.next.v.contains(3 * V) && r2.next.theta.contains(th);
    accel = accel && ok;
    if (j == 2) pts = "(1/4, " + qs(v) + ") -> (" + s(r1.next.theta) + ", " + s(r1.next.v) + ") -> (" +
                      s(r2.next.theta) + ", " + s(r2.next.v) + ")";
  }
  sub.evidence.push_back("p=" + std::to_string(p) + " k=" + std::to_string(k) + ": a = " + qs(a) + ", v_n = " + qs(v) +
                         ": two steps never return on [delta, 1/2-delta]: " + describe(c) + "; thin point " + pts +
                         (accel ? " (v grows by 8 per impact at constant phase: Fermi acceleration)" : ""));
  return c.complete();
}

// Refutes the orbit's existence. By hand (header): eps = 1 forces tau1 = tau2 = p/2 and then
// 8 tau = 0. By the map: for every (p <= 3, k) whose eq. (33) has a rational root a > 0 with
// v_n > 4, two steps from (theta, v_n) never return (check_no_return). Irrational roots and
// unphysical ones are listed, not checked.
void check_no_up_up_orbit(SubClaim& sub, const CoverPlan& plan, long bits) {
  bool map_ok = true;
  int families = 0;
  for (int p = 1; p <= 3; ++p) {
    for (int k = 0; k <= p; ++k) {
      const std::string pk = "p=" + std::to_string(p) + " k=" + std::to_string(k);
      const mpz_class D = 169 * p * p - 608 * k * p + 256 * k * k;
      if (D < 0) {
        sub.evidence.push_back(pk + ": discriminant " + D.get_str() + " < 0, no real a");
        continue;
      }
      if (!mpz_perfect_square_p(D.get_mpz_t())) {
        sub.evidence.push_back(pk + ": irrational a, not checked");
        continue;
      }
      const mpz_class r = sqrt(D);
      for (int sign : {1, -1}) {
        mpq_class a = mpq_class(22 * p - 64 * k + 2 * sign * r, 3 * p * p);
        a.canonicalize();
        mpq_class v = a * p / 4 + 4 - mpq_class(8 * k, p);
        v.canonicalize();
        if (a <= 0 || v <= 4) {
          sub.evidence.push_back(pk + ": a = " + qs(a) + ", v = " + qs(v) + " (a <= 0 or v <= 4: not physical)");
          continue;
        }
        ++families;
        if (!check_no_return(sub, p, k, a, v, plan, bits)) map_ok = false;
      }
    }
  }
  if (map_ok && families > 0)
    sub.settle(Verdict::refuted,
               "no such orbit exists: with eps = 1 the implicit equations give tau1 = tau2 = p/2 and then 8 tau = 0 "
               "(no elastic periodic orbit has all impacts on the upward wall: each raises the energy); at the "
               "paper's a = 16/p the start (theta, 8) is certified not to return after two steps for every theta "
               "in [delta, 1/2-delta]: (theta, 8) -> (theta, 16) -> (theta, 24)");
}

// Refutes lambda2 = 1/3 as a multiplier: the formula does give exactly 1/3 at a = 16, but
// there is no orbit (needs `orbit_refuted`); the interval-AD Jacobian shows 1/3 is the
// one-step dv'/dv at (1/4, 8), the start of an accelerating orbit.
void check_lambda2_not_a_multiplier(SubClaim& sub, bool orbit_refuted, long bits) {
  // lambda2 formula at a = 16, p = 1, k = 0: (16)^2/(16 sqrt(256 + 2048)) = 256/(16*48) = 1/3.
  const mpq_class& a = kA;
  const mpq_class rad = a * a + 128 * a;  // a^2 p^4 + 128 a p^3 - 64 a k p^2 + 1024 k^2 at p=1,k=0
  const mpq_class lam2 = (a * a) / (a * 48);
  const bool formula_one_third = rad == 2304 && lam2 == mpq_class(1, 3);
  if (formula_one_third)
    sub.evidence.push_back("the formula evaluates to exactly 1/3 at a = 16 (radicand 2304 = 48^2), but there is no orbit");
  try {
    const Mpfi A(16, bits);
    ImpactMap<IDual> dmap(lift(triangle_model(Law::elastic, A, Mpfi(1, bits), Mpfi(1, bits), bits, 1L << 20)));
    LinearizedSteps L = linearize(dmap, qi(mpq_class(1, 4), bits), Mpfi(8, bits), 2);
    auto ev = eigenvalues(L.J);
    sub.evidence.push_back("Jacobian of two steps of the real map at (1/4, 8), a = 16 (not a periodic point): " +
                           describe(L.J) + (ev ? ", eigenvalues in " + s(ev->hi) + ", " + s(ev->lo) : ""));
    LinearizedSteps L1 = linearize(dmap, qi(mpq_class(1, 4), bits), Mpfi(8, bits), 1);
    sub.evidence.push_back("one step at (1/4, 8), a = 16: J in " + describe(L1.J) +
                           ": dv'/dv = a s'(v) - 1 = 16/12 - 1 = 1/3 (hand), i.e. the formula's 1/3 coincides with the "
                           "one-step derivative at the start of an accelerating orbit, not with a periodic-orbit multiplier");
    const bool one_third = L1.J.a22.contains(qi(mpq_class(1, 3), bits));
    if (formula_one_third && orbit_refuted && one_third)
      sub.settle(Verdict::refuted,
                 "the value 1/3 is the formula's arithmetic, but it is not a multiplier of any orbit: the orbit does not exist");
  } catch (const bouncer::Undecided& u) {
    sub.evidence.push_back(std::string("AD step undecided: ") + u.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  Certificate cert("elastic_period2", kClaim, kMethod, 128, argc, argv);
  const CoverPlan plan = cover_plan(cert.full(), 12, 14, 24, 36);
  cert.note(plan.text());
  SubClaim& arithmetic = cert.add("eq33-arithmetic", "eq. (33) for p = 1, k = 0: a = (22 +- 2*13)/3 = 16 or -4/3; v_n = 8");
  SubClaim& orbit = cert.add("orbit", "eqs. (8), (9): a period-2 up/up orbit exists with v_n = ap/4 + 4 - 8k/p");
  SubClaim& admissible = cert.add("admissibility", "theta_n, theta_{n+1} < 1/2 (both impacts on the upward wall)");
  SubClaim& lambda2 = cert.add("lambda2", "lambda2 = (ap^2-32k)^2/((ap^2+32k) sqrt(a^2p^4+128ap^3-64akp^2+1024k^2)) = 1/3 at p=1, k=0");

  check_eq33_arithmetic(arithmetic);
  check_admissibility(admissible);
  check_no_up_up_orbit(orbit, plan, cert.bits());
  check_lambda2_not_a_multiplier(lambda2, orbit.verdict == Verdict::refuted, cert.bits());

  cert.conclude(Verdict::refuted, kConclusion);
  return cert.finish();
}
