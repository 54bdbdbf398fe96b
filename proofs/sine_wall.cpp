// Proof: the paper's headline comparison, feature by feature (abstract: "although our
// piecewise linear bouncer is a simplified version of the sinusoidal model, the former not
// only captures essential features of the latter but also exhibits behavior unique to the
// discontinuous dynamics"), with the sine wall f(theta) = sin(2 pi theta) beside the triangle.
//
// Period-1 orbits of the sine wall, derived by hand (docs/model.md "The sine wall"). A state
// is (theta, v) just after an impact; a period-1 orbit returns after one wall period (tau = 1)
// to the same phase, so v tau - a tau^2 / 2 = 0: v* = a/2, arriving with v- = -a/2. The law
// v+ - u = eps (u - v-) with u = 2 pi cos(2 pi theta*) gives
//     cos(2 pi theta*) = c := a (1 - eps) / (4 pi (eps + 1)),     (exists iff a <= a_SN = 4 pi (1+eps)/(1-eps)).
// The Jacobian (implicit differentiation of g(tau; theta, v) = f(theta) + v tau - a tau^2/2 -
// f(theta + tau) at tau = 1, where g_theta = f'(theta) - f'(theta + 1) = 0, g_v = 1 and
// g_tau = -w, w = a/2 + u = a/(1+eps) the relative impact speed):
//     J = [[1, 1/w], [(1+eps) f'', ((1+eps) f'' + eps a)/w - eps]],   f'' = -4 pi^2 sin(2 pi theta*),
// so det J = eps^2 and tr J = 1 + eps^2 + (1+eps)^2 f''/a. The orbit with sin(2 pi theta*) < 0
// has tr > 1 + eps^2: a saddle. The one with sin > 0 is stable iff tr > -(1 + eps^2): it is
// born at a_SN (tr = 1 + eps^2: multipliers 1, eps^2, a saddle-node) and loses stability in a
// period doubling (tr = -(1 + eps^2)) at
//     a_PD = 1 / sqrt(beta^2 + 1/k^2),  beta = (1-eps)/(4 pi (1+eps)),  k = 2 pi^2 (1+eps)^2 / (1+eps^2).
// The triangle's period-1 orbits are instead a neutral family (multipliers 1 and eps^2) at the
// single value a = 8(1+eps)/(1-eps) (claim row 1).
//
// Fermi acceleration at a = 16 (elastic): the triangle's (theta, 8) -> (theta, 16) -> (theta,
// 24) (claim row 2). The sine wall has the same ladder at theta_acc = acos(2/pi)/(2 pi): with
// v = 8n the flight lasts n periods (8n^2 - 8n^2 = 0) and arrives at v- = -8n; the wall moves
// at u = 2 pi cos(2 pi theta_acc) = 4, so v+ = 2u - v- = 8(n + 1) (Pustylnikov's accelerator
// modes of the gravitational Fermi accelerator).
//
// Chaos: a horseshoe of covering relations of F at eps = 1/2, a = 20, built around the
// period-1 saddle (the closed form's orbit with sin(2 pi theta*) < 0) and its homoclinic
// return by the library's certify_chaos, every covering checked in MPFI; the triangle's
// horseshoes are claims rows 9b, 12 and 18d.
//
// Computation: ImpactMap<Mpfi> (the library's sine step, whose first impact is certified over
// each box); the library's certify_periodic (Krawczyk, the command certify-periodic) for the
// period-1 orbits, checked against the closed forms; MPFI's acos and asin for those.
#include <gmpxx.h>

#include <string>

#include "bouncer/analysis/continuation.hpp"
#include "bouncer/verify/chaos.hpp"
#include "bouncer/verify/periodic_certify.hpp"
#include "certificate.hpp"
#include "proof_util.hpp"

using namespace proofs;
using bouncer::EventKind;
using bouncer::ImpactMap;
using bouncer::Law;
using bouncer::Model;
using bouncer::State;
using bouncer::StepResult;

namespace {

const char* const kClaim =
    "abstract: the piecewise linear bouncer captures essential features of the sinusoidal one and also "
    "exhibits behavior unique to the discontinuous dynamics (sec. I, IV)";
const char* const kMethod =
    "the sine wall through bouncer's certified step (ImpactMap<Mpfi>, first impacts certified over each box); "
    "certify_periodic (Krawczyk, as certify-periodic) for the period-1 orbits; closed forms enclosed by MPFI";

// The sine wall's validated model: its spec (for the library's certificates) and its MPFI
// model at `bits`.
bouncer::ModelSpec sine_spec(Law law, const std::string& a, const std::string& eps) {
  bouncer::ModelSpec spec;
  spec.law = law;
  spec.wall = bouncer::parse_wall("wall", "sine");
  spec.a = bouncer::parse_decimal("a", a);
  spec.eps = bouncer::parse_decimal("eps", eps);
  bouncer::validate(spec);
  return spec;
}
Model<Mpfi> sine_model(Law law, const std::string& a, const std::string& eps, long bits) {
  return bouncer::make_model<Mpfi>(sine_spec(law, a, eps), bits);
}

Mpfi pi_of(long bits) {
  Mpfi p(bits);
  mpfi_const_pi(p.get());
  return p;
}
Mpfi acos_of(const Mpfi& x) {
  Mpfi r(x.bits());
  mpfi_acos(r.get(), x.get());
  return r;
}
Mpfi asin_of(const Mpfi& x) {
  Mpfi r(x.bits());
  mpfi_asin(r.get(), x.get());
  return r;
}

// The stable period-1 orbit's closed form (sin(2 pi theta*) > 0): theta* = acos(c)/(2 pi).
struct Period1 {
  Mpfi theta, v, trace;
};
Period1 closed_form(const Mpfi& a, const Mpfi& eps) {
  const long bits = a.bits();
  const Mpfi pi = pi_of(bits);
  const Mpfi c = a * (1 - eps) / (4 * pi * (eps + 1));
  const Mpfi theta = acos_of(c) / (2 * pi);
  const Mpfi sin_part = sqrt(1 - c * c);  // sin(2 pi theta*) > 0
  const Mpfi trace = eps * eps + 1 - (eps + 1) * (eps + 1) * 4 * pi * pi * sin_part / a;
  return {theta, a / 2, trace};
}

// The library's certificate of the period-1 orbit near the closed form (certify_periodic, the
// command certify-periodic: Krawczyk over a box around Newton's point, interval-dual
// Jacobian, precision escalation), read back as intervals: the orbit point's box, the
// Jacobian's trace and determinant, the multipliers.
struct Certified1 {
  bool ok = false;
  std::string why;
  Mpfi theta, v, trace, det;
  bool complex = false;
  Mpfi mu_hi, mu_lo, modulus;  // real: the larger and the smaller; complex: |mu|
};
Mpfi from_enclosure(const bouncer::Enclosure& e, long bits) {
  return Mpfi(Tr::from_decimal(e.lo, bits).lower(), Tr::from_decimal(e.hi, bits).upper());
}
Certified1 certify_period1(const bouncer::ModelSpec& spec, const Period1& cf, long bits) {
  bouncer::PeriodicQuestion q;
  q.model = spec;
  q.period = 1;
  q.family = bouncer::FamilyMode::isolated;
  q.guess = bouncer::InitialCondition{bouncer::parse_decimal("guess", s(cf.theta.mid())),
                                      bouncer::parse_decimal("guess", s(cf.v.mid()))};
  q.schedule = {bits, 4 * bits, false};
  const bouncer::PeriodicCertificate c = bouncer::certify_periodic(q);
  if (!c.certified) return {false, c.reason, {}, {}, {}, {}, {}, {}, {}, {}};
  if (c.outcome != bouncer::PeriodicOutcome::isolated || c.events.size() != 1 || c.events[0].rfind("impact", 0) != 0 ||
      c.wall_periods[0] != 1)
    return {false, "certified, but not one flight of one period: " + c.statement, {}, {}, {}, {}, {}, {}, {}, {}};
  const long b = c.bits;
  Certified1 out{true, "", from_enclosure(c.points[0].theta, b), from_enclosure(c.points[0].v, b),
                 from_enclosure(c.multipliers.trace, b), from_enclosure(c.multipliers.det, b), false, {}, {}, {}};
  if (c.multipliers.kind == "real") {
    out.mu_hi = from_enclosure(c.multipliers.mu[0], b);
    out.mu_lo = from_enclosure(c.multipliers.mu[1], b);
    out.modulus = Mpfi(std::max(abs(out.mu_hi).upper(), abs(out.mu_lo).upper()), std::max(abs(out.mu_hi).upper(), abs(out.mu_lo).upper()));
  } else if (c.multipliers.kind == "complex") {
    out.complex = true;
    out.modulus = from_enclosure(c.multipliers.modulus, b);
  } else {
    return {false, "multipliers not separated (discriminant undecided)", {}, {}, {}, {}, {}, {}, {}, {}};
  }
  return out;
}

std::string dec(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6f", x);
  return b;
}

void period_one(Certificate& cert, SubClaim& sub) {
  const long bits = cert.bits();
  const Mpfi eps = Mpfi(1, bits) / 2;
  const Mpfi pi = pi_of(bits);
  const Mpfi beta = (1 - eps) / (4 * pi * (eps + 1));
  const Mpfi k = 2 * pi * pi * (eps + 1) * (eps + 1) / (eps * eps + 1);
  const Mpfi a_pd = 1 / sqrt(beta * beta + 1 / (k * k));
  const Mpfi a_sn = 4 * pi * (eps + 1) / (1 - eps);
  sub.evidence.push_back("closed forms at eps = 1/2: a_PD = " + s(a_pd) + ", a_SN = 12 pi = " + s(a_sn));
  // Certified orbits at a = 20 (below a_PD), 30 (between), and a_PD -+ 0.01.
  const double apd = d(a_pd);
  struct Case {
    std::string a;
    bool stable;
  };
  const Case cases[] = {{"20", false}, {dec(apd - 0.01), false}, {dec(apd + 0.01), true}, {"30", true}, {"37.6", true}};
  bool all = true;
  for (const Case& c : cases) {
    const Model<Mpfi> m = sine_model(Law::constant, c.a, "0.5", bits);
    const Period1 cf = closed_form(m.a, m.eps);
    const Certified1 r = certify_period1(sine_spec(Law::constant, c.a, "0.5"), cf, bits);
    if (!r.ok) {
      sub.evidence.push_back("a = " + c.a + ": not certified: " + r.why);
      all = false;
      continue;
    }
    const bool at_closed_form = !disjoint(r.theta, cf.theta) && !disjoint(r.v, cf.v);
    const bool tr_ok = !disjoint(r.trace, cf.trace), det_ok = !disjoint(r.det, eps * eps);
    const bool stable = lt(r.modulus, Mpfi(1, bits));
    const bool flip = !r.complex && (lt(r.mu_hi, Mpfi(-1, bits)) || lt(r.mu_lo, Mpfi(-1, bits)));
    const bool as_said = c.stable ? stable : flip;
    all = all && at_closed_form && tr_ok && det_ok && as_said;
    const std::string mult = r.complex ? "a complex pair of modulus " + s(r.modulus) : s(r.mu_hi) + ", " + s(r.mu_lo);
    sub.evidence.push_back("a = " + c.a + ": certify_periodic (Krawczyk) proves a unique period-1 point in the box (" + s(r.theta) + ", " +
                           s(r.v) + "), which meets the closed form (theta*, a/2), cos(2 pi theta*) = a(1-eps)/(4 pi (1+eps)): " +
                           (at_closed_form ? "yes" : "NO") + "; multipliers " + mult +
                           (stable ? " (stable)" : flip ? " (one below -1: unstable, flip)" : " (?)") +
                           "; trace and det meet the closed forms: " + (tr_ok && det_ok ? "yes" : "NO"));
  }
  if (all)
    sub.settle(Verdict::refuted,
               "not captured: the sine wall's period-1 orbits are isolated and exist for every a < a_SN = 4 pi (1+eps)/(1-eps); "
               "the stable one is born in a saddle-node at a_SN and period-doubles at a_PD = 1/sqrt(beta^2 + 1/k^2) (25.857 at eps = 1/2), "
               "the start of a period-doubling route. The triangle's period-1 orbits are a neutral family (multipliers 1, eps^2) at the "
               "single value a = 8(1+eps)/(1-eps) (row 1): no period doubling from them");
}

void sticking(Certificate& cert, SubClaim& sub) {
  const long bits = cert.bits();
  const Model<Mpfi> m = sine_model(Law::constant, "20", "0.5", bits);
  ImpactMap<Mpfi> map(m);
  State<Mpfi> st{Tr::from_decimal("0.1", bits), Mpfi(8, bits)};
  const Mpfi pi = pi_of(bits);
  const Mpfi theta_r = asin_of(m.a / (4 * pi * pi)) / (2 * pi);
  const Mpfi v_r = 2 * pi * sqrt(1 - (m.a / (4 * pi * pi)) * (m.a / (4 * pi * pi)));
  for (int n = 1; n <= 200; ++n) {
    StepResult<Mpfi> r;
    if (std::string e = try_step(map, st, r); !e.empty()) {
      sub.evidence.push_back("sine wall, eps = 1/2, a = 20, from (0.1, 8): step " + std::to_string(n) + " " + e);
      return;
    }
    if (r.kind == EventKind::sticking) {
      const bool at_release = !disjoint(r.next.theta, theta_r) && !disjoint(r.next.v, v_r);
      sub.evidence.push_back("sine wall, eps = 1/2, a = 20, from (0.1, 8): step " + std::to_string(n) + " sticks at theta = " +
                             s(r.stuck_theta) + " and is released at " + s(r.next.theta) + ", v = " + s(r.next.v) +
                             "; the closed form theta_r = asin(a/(4 pi^2))/(2 pi) = " + s(theta_r) + ": " + (at_release ? "met" : "NOT met"));
      if (at_release)
        sub.settle(Verdict::confirmed,
                   "captured: both walls have sticking (a collapse of the chatter) and release where the wall's downward acceleration "
                   "reaches the particle's: the triangle at its corner theta = 1/2 (v = 4), the sine wall at theta_r = asin(a/(4 pi^2))/(2 pi)");
      return;
    }
    st = r.next;
  }
  sub.evidence.push_back("no sticking within 200 steps");
}

void fermi(Certificate& cert, SubClaim& sub) {
  const long bits = cert.bits();
  const Mpfi pi = pi_of(bits);
  const Mpfi theta_acc = acos_of(2 / pi) / (2 * pi);
  const Model<Mpfi> sine = sine_model(Law::elastic, "16", "1", bits);
  const Model<Mpfi> tri = triangle_model(Law::elastic, Mpfi(16, bits), Mpfi(1, bits), Mpfi(1, bits), bits);
  bool ok = true;
  for (int wall = 0; wall < 2; ++wall) {
    ImpactMap<Mpfi> map(wall == 0 ? tri : sine);
    const Mpfi theta0 = wall == 0 ? Mpfi(1, bits) / 4 : theta_acc;
    State<Mpfi> st{theta0, Mpfi(8, bits)};
    std::string seen;
    for (int n = 1; n <= 4; ++n) {
      StepResult<Mpfi> r;
      if (std::string e = try_step(map, st, r); !e.empty()) {
        sub.evidence.push_back(std::string(wall == 0 ? "triangle" : "sine") + ": " + e);
        ok = false;
        break;
      }
      const bool ladder = !disjoint(r.next.v, Mpfi(8 * (n + 1), bits)) && !disjoint(r.next.theta, theta0) && r.periods == n;
      ok = ok && ladder;
      seen += (n > 1 ? ", " : "") + s(r.next.v);
      st = r.next;
    }
    sub.evidence.push_back(std::string(wall == 0 ? "triangle from (1/4, 8)" : "sine from (acos(2/pi)/(2 pi), 8)") +
                           ": v after 1..4 impacts encloses " + seen + " at the starting phase, flights of 1..4 periods");
  }
  if (ok)
    sub.settle(Verdict::confirmed,
               "captured: at a = 16 both walls have the exact accelerating orbit v = 8, 16, 24, 32, ... at a constant phase "
               "(triangle: theta = 1/4 on its rise; sine: theta = acos(2/pi)/(2 pi), where the wall rises at speed 4)");
}

void border(Certificate& cert, SubClaim& sub, const SubClaim& p1) {
  // The sine wall has no corner; the stable period-1 branch's ends are the closed forms'
  // saddle-node (multiplier 1 at a_SN) and period doubling (-1 at a_PD), certified on either
  // side in p1.
  const long bits = cert.bits();
  const Model<Mpfi> m = sine_model(Law::constant, "37.699", "0.5", bits);  // just below a_SN = 37.6991...
  const Period1 cf = closed_form(m.a, m.eps);
  const Certified1 r = certify_period1(sine_spec(Law::constant, "37.699", "0.5"), cf, bits);
  if (!r.ok || r.complex) {
    sub.evidence.push_back("a = 37.699 (just below a_SN): " + (r.ok ? std::string("a complex pair of multipliers") : r.why));
    return;
  }
  if (p1.verdict == Verdict::not_proved) {
    sub.evidence.push_back("the period-1 sub-claim is not proved: nothing concluded");
    return;
  }
  sub.evidence.push_back("a = 37.699, 1e-4 below a_SN = 12 pi: certified period-1 orbit with multipliers " + s(r.mu_hi) + ", " +
                         s(r.mu_lo) + " (the saddle-node's 1 and eps^2 = 1/4 as a -> a_SN)");
  const bool near_one = lt(r.mu_hi, Mpfi(1, bits)) && lt(Mpfi(99, bits) / 100, r.mu_hi);
  if (!near_one) return;
  // The saddle (sin(2 pi theta*) < 0) going down in a: a certified orbit at a = 15.77; at
  // a = 15.76 the closed form's flight meets the wall before one period (a certified first
  // impact), so the closed form is no orbit there: the branch ends in between, where its
  // flight touches the wall (a grazing). continue_branch locates it (an estimate).
  const auto saddle = [&](const std::string& a) {
    const Model<Mpfi> ms = sine_model(Law::constant, a, "0.5", bits);
    Period1 c = closed_form(ms.a, ms.eps);
    c.theta = 1 - c.theta;
    return std::pair<Model<Mpfi>, Period1>(ms, c);
  };
  const auto [m_above, cf_above] = saddle("15.77");
  const Certified1 above = certify_period1(sine_spec(Law::constant, "15.77", "0.5"), cf_above, bits);
  const bool above_ok = above.ok && !disjoint(above.theta, cf_above.theta) && !disjoint(above.v, cf_above.v);
  sub.evidence.push_back("the saddle branch (sin(2 pi theta*) < 0) at a = 15.77: " +
                         (above.ok ? "certify_periodic proves a unique period-1 point in (" + s(above.theta) + ", " + s(above.v) +
                                         "), which meets the closed form: " + (above_ok ? "yes" : "NO")
                                   : "not certified: " + above.why));
  const auto [m_below, cf_below] = saddle("15.76");
  bool early = false;
  try {
    const StepResult<Mpfi> st = ImpactMap<Mpfi>(m_below).step(State<Mpfi>{cf_below.theta, cf_below.v});
    early = lt(st.tau, Mpfi(1, bits));
    sub.evidence.push_back("at a = 15.76 the closed form's saddle point (" + s(cf_below.theta) + ", " + s(cf_below.v) +
                           ") meets the wall after tau in " + s(st.tau) + (early ? " < 1 (certified first impact): no orbit" : ""));
  } catch (const bouncer::Undecided& u) {
    sub.evidence.push_back(std::string("at a = 15.76 the closed form's first impact is undecided: ") + u.what());
  }
  const Model<double> md = bouncer::make_model<double>(sine_spec(Law::constant, "30", "0.5"), 53);
  const double th = 1 - std::acos(30 * 0.5 / (4 * M_PI * 1.5)) / (2 * M_PI);
  bouncer::ContinuationOptions co;
  co.classify_beyond = false;
  const bouncer::Branch<double> br = bouncer::continue_branch(md, bouncer::Parameter::a, 1, State<double>{th, 15.0}, 5.0, 39.0, co);
  const bool grazing = br.started && br.low.reason == bouncer::EndReason::border &&
                       br.low.margin == static_cast<int>(bouncer::Margin::clearance) && br.low.param > 15.76 && br.low.param < 15.77;
  char where[160];
  std::snprintf(where, sizeof where, "continue (double) from a = 30: the saddle branch ends below at a* = %.10f by %s", br.low.param,
                bouncer::name(br.low.reason));
  sub.evidence.push_back(std::string(where) + " (" + br.low.detail + "), above at a* = " + std::to_string(br.high.param) + " (" +
                         bouncer::name(br.high.reason) + ")");
  if (above_ok && early && grazing)
    sub.settle(Verdict::corrected,
               "corner collisions are unique to the triangle, border collisions are not: the sine wall's stable period-1 branch ends "
               "in smooth bifurcations (a saddle-node at a_SN, a period doubling at a_PD) with the relative impact speed a/(1+eps) > 0 "
               "along it, but its saddle branch ends in a grazing (its flight touches the wall, between a = 15.76 and 15.77), the "
               "border collision of smooth impact oscillators; the triangle's branches end where an impact reaches a corner "
               "(continue, rows 16-18), which a smooth wall has not");
}

// Chaos on the sine wall: a horseshoe of covering relations (the library's certify_chaos, the
// search and MPFI proof behind the command certify-chaos) at eps = 1/2, a = 20, around the
// period-1 saddle of the closed form (sin(2 pi theta*) < 0, row period-1 above).
void chaos(Certificate& cert, SubClaim& sub) {
  bouncer::ChaosSearchOptions options;
  options.bits = cert.bits();
  const bouncer::ChaosSearchResult r = bouncer::certify_chaos(sine_spec(Law::constant, "20", "0.5"), options);
  sub.evidence.push_back("sine wall, eps = 1/2, a = 20: " + r.message);
  if (!r.proved) return;
  sub.evidence.push_back("the horseshoe is proved with MPFI only: certify-chaos's second, independent replay (Arb) has its own "
                         "impact map for piecewise walls alone, so this certificate is not replayed");
  sub.settle(Verdict::confirmed,
             "captured: both walls have proved chaos, an invariant set with positive topological entropy (a horseshoe of "
             "covering relations): the sine wall at eps = 1/2, a = 20 (h_top >= " + r.entropy.bound + " per collision, at its "
             "period-1 saddle), the triangle in rows 9b, 12 and 18d. This is chaos on an invariant set, not a chaotic attractor: "
             "on either wall the chaotic bands of the bifurcation diagrams rest on numerical Lyapunov exponents");
}

}  // namespace

int main(int argc, char** argv) {
  Certificate cert("sine_wall", kClaim, kMethod, 128, argc, argv);
  SubClaim& p1 = cert.add("period-1", "the triangle's period-1 orbits (eq. 5) stand for the sinusoidal bouncer's");
  period_one(cert, p1);
  SubClaim& st = cert.add("sticking", "sticking and release (sec. II.B.3) are features of both");
  sticking(cert, st);
  SubClaim& fa = cert.add("fermi", "Fermi acceleration of the elastic model (sec. II.B.1, row 2)");
  fermi(cert, fa);
  SubClaim& bc = cert.add("border-collisions", "border collisions are behavior unique to the discontinuous dynamics");
  border(cert, bc, p1);
  SubClaim& ch = cert.add("chaos", "chaotic dynamics is a feature of both walls");
  chaos(cert, ch);
  cert.conclude(Verdict::corrected,
                "Sticking, release, Fermi acceleration and chaos (a horseshoe) are captured; the period-1 structure is not (the sine wall's period-1 orbits "
                "are isolated and period-double; the triangle's are a neutral family at one a); corner collisions are the "
                "triangle's alone, grazing border collisions happen on both walls");
  return cert.finish();
}
