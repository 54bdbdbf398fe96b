// Proof: the chaos of the paper's models is real: horseshoes with positive topological
// entropy (issue 26; paper sec. V.B, fig. bifurcation).
//
// Paper: chaotic motion in the velocity-dependent model at c ~ 1000 (sec. V.B: a positive
// Lyapunov exponent, a numerical statement), and "apparently chaotic behavior" in the constant
// restitution model at eps = 0.96 (fig. bifurcation; at a = 28.82 the orbit from the release
// state is a sticking solution of period k > 1000, row 9).
//
// Method (bouncer certify-chaos, verify/chaos.hpp, verify/covering.hpp): from the model alone,
// a saddle periodic orbit p (Newton at 256 bits) and a transverse homoclinic orbit of it
// (the unstable manifold followed until it returns along the stable direction); h-sets
// (parallelograms with exact rational centres and frames) around p and along the homoclinic
// orbit; the covering relations N_0 => N_0, N_0 => N_1, ..., N_m => N_0 of G = F^k (k the
// saddle's period) checked by MPFI enclosures (Lohner's mean-value form from each piece), every
// step of F an impact decided over the whole h-set, so that G is continuous there; the h-sets
// pairwise disjoint (exact). Then (Zgliczynski and Gidea 2004) G restricted to an invariant
// set in the h-sets is semiconjugate onto the subshift of the coverings' graph, and
// h_top(F) >= log(rho)/k, rho >= the exact Collatz-Wielandt quotient. The certificate is then
// replayed by a second interval library, Arb, with its own implementation of the map
// (verify/chaos_certificate.hpp).
//
// Hand-derived check of the combinatorics: the chain's graph has the cycles 0 -> 0 (length
// 1) and 0 -> 1 -> ... -> m -> 0 (length m + 1), so rho is the largest root of
// x^(m+1) = x^m + 1 (> 1), and the bound log(rho)/k is positive.
//
// Default mode: velocity-dependent c = 1000, a = 27. --full adds constant eps = 0.96,
// a = 28.82 (the paper's own "apparently chaotic" point, about 20 s) and c = 1000, a = 25
// (a horseshoe beside the stable period-3 attractor: transient chaos).
#include <cmath>
#include <string>

#include "bouncer/io/scene.hpp"
#include "bouncer/verify/chaos.hpp"
#include "certificate.hpp"

using namespace proofs;

namespace {

const char* const kClaim =
    "the paper's chaotic regimes carry positive topological entropy: veldep c = 1000, a = 27 (sec. V.B); with --full "
    "also constant eps = 0.96, a = 28.82 (fig. bifurcation) and veldep c = 1000, a = 25";
const char* const kMethod =
    "covering relations of h-sets along a homoclinic orbit of a saddle (Zgliczynski-Gidea), MPFI enclosures (Lohner "
    "from each piece, every branch decided over each h-set), exact disjointness and Collatz-Wielandt bound; the "
    "certificate replayed in Arb with an independent implementation of the map";

bouncer::ModelSpec model(const char* law, const char* a, const char* param) {
  bouncer::Options o;
  o.set("model", law);
  o.set("a", a);
  o.set(std::string(law) == "veldep" ? "c" : "eps", param);
  return bouncer::model_from(o);
}

// The largest root of x^(n) = x^(n-1) + 1, by bisection in doubles (only for the hand check).
double chain_root(int n) {
  double lo = 1, hi = 2;
  for (int i = 0; i < 100; ++i) {
    const double x = (lo + hi) / 2;
    (std::pow(x, n) - std::pow(x, n - 1) - 1 > 0 ? hi : lo) = x;
  }
  return lo;
}

// One case: the horseshoe proved with MPFI, its certificate replayed in Arb, the bound > 0 and
// at least log(root of the chain's polynomial)/k (less 1e-12 for the double hand check).
void check_horseshoe(SubClaim& sub, const bouncer::ModelSpec& spec, long bits) {
  bouncer::ChaosSearchOptions o;
  o.bits = bits;
  const bouncer::ChaosSearchResult r = bouncer::certify_chaos(spec, o);
  sub.evidence.push_back(r.message);
  if (!r.proved) return;
  const bouncer::ChaosCertificate& c = r.certificate;
  sub.evidence.push_back("saddle of period " + std::to_string(r.orbit.period) + ", multipliers " +
                         std::to_string(r.orbit.lambda_u) + ", " + std::to_string(r.orbit.lambda_s) + "; " +
                         std::to_string(c.sets.size()) + " h-sets, " + std::to_string(c.coverings.size()) +
                         " coverings of F^" + std::to_string(c.k) + " at " + std::to_string(c.bits) + " bits");
  const bouncer::ReplayResult replay = bouncer::replay_certificate(c, 2 * bits);
  sub.evidence.push_back(std::string("Arb replay at ") + std::to_string(replay.bits) + " bits: " +
                         (replay.valid ? "valid" : "NOT valid: " + replay.problems.front()));
  const double chain = std::log(chain_root(int(c.sets.size()))) / c.k;
  sub.evidence.push_back("the chain alone: log(rho)/k = " + std::to_string(chain) + " (x^" +
                         std::to_string(c.sets.size()) + " = x^" + std::to_string(c.sets.size() - 1) + " + 1)");
  if (replay.valid && r.entropy.bound_double > 0 && r.entropy.bound_double >= chain - 1e-12)
    sub.settle(Verdict::confirmed, "h_top(F) >= " + r.entropy.bound + " per impact (a horseshoe of F^" +
                                       std::to_string(c.k) + "; an invariant set, not necessarily the attractor)");
}

}  // namespace

int main(int argc, char** argv) {
  Certificate cert("horseshoes", kClaim, kMethod, 128, argc, argv);
  SubClaim& veldep27 = cert.add("veldep-c1000-a27", "sec. V.B: chaos at c ~ 1000 (lambda > 0, numerical)");
  check_horseshoe(veldep27, model("veldep", "27", "1000"), cert.bits());
  if (cert.full()) {
    SubClaim& eps096 = cert.add("eps096-a28.82", "fig. bifurcation: apparently chaotic behavior at eps = 0.96");
    check_horseshoe(eps096, model("constant", "28.82", "0.96"), cert.bits());
    SubClaim& veldep25 = cert.add("veldep-c1000-a25", "fig. basin_three: chaos at a = 25, c ~ 1000");
    check_horseshoe(veldep25, model("veldep", "25", "1000"), cert.bits());
  }
  cert.conclude(Verdict::confirmed, "positive topological entropy (horseshoes), replayed in a second interval library");
  return cert.finish();
}
