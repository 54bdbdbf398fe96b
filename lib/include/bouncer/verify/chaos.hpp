// A horseshoe for the bouncer's impact map, found from the model alone and proved with MPFI
// (issue 26): a certified lower bound on the topological entropy, and its certificate
// (verify/chaos_certificate.hpp).
//
// The construction (docs/guide/chaos.md, "A horseshoe of the bouncer"). G = F^k, k the period
// of a saddle periodic orbit p of F (Newton, analysis/periodic.hpp, at `search_bits`; the
// first real saddle of period 1, 2, ..., max_period that search_periodic finds), with
// multipliers |lambda_u| > 1 > |lambda_s| and unit eigenvectors e_u, e_s. A homoclinic orbit
// of p is searched numerically (Mpfr at search_bits): the image of the fundamental domain
// {p + t e_u : t in [t0, |lambda_u| t0]} under G^n is followed as a polyline (refined where
// its vertices drift apart, broken where G is discontinuous), until a segment crosses p's
// local stable line {p + s e_s} near p; bisection on t then puts G^n(q0) on that line, and
// further bisections on later iterates make the return deep (|s| small). No fixed start:
// the search fails, and says so, when the model has no saddle or no homoclinic return.
// When nothing is proved, up to `attempts` searches are made, each with t0 and the h-sets'
// cap 4 times smaller than the one before.
//
// Along the homoclinic orbit q_0 = p + t e_u, q_i = G^i(q_0), the h-sets are N_0 around p
// (frame e_u, e_s) and N_i around q_i, i = 1..m (q_m the deep return), with the unstable
// direction carried forward by DG and the stable one backward from e_s at q_{m+1}, and radii
// from the images of a grid of points of the previous h-set with a margin (unstable radii
// capped), and every h-set inside 0 < theta < 1 (so that disjointness in the plane is
// disjointness on the cylinder). The coverings N_0 => N_0, N_0 => N_1, N_i => N_{i+1} and N_m => N_0 of G, each
// under G on the branch at the source h-set's centre (impact_set_map), are checked with
// check_covering at `bits`, the h-sets' disjointness exactly; their graph has the cycles of
// lengths 1 and m + 1, so rho is the largest root of x^(m+1) = x^m + 1 > 1 and the bound
// log(rho)/k is positive. Coverings N_m => N_j, j = 1, 2, ... (the return strip stretched
// across the next sets along W^u too) are tried as well and kept where proved.
#pragma once

#include <string>
#include <vector>

#include "bouncer/model/spec.hpp"
#include "bouncer/verify/chaos_certificate.hpp"
#include "bouncer/verify/covering.hpp"

namespace bouncer {

// How certify_chaos searches and proves.
struct ChaosSearchOptions {
  // MPFI precision of the covering checks (and of the maps' enclosures).
  long bits = 128;
  // Mpfr precision of Newton, the homoclinic search and the design of the h-sets.
  long search_bits = 256;
  // The finest subdivision check_covering tries (pieces per side).
  int max_pieces = 64;
  // Saddles are searched for the periods 1..max_period of F.
  int max_period = 4;
  // The fundamental domain of the unstable manifold starts at t0 = unstable_start (Euclidean
  // distance from p along e_u in (theta, v)), times 3 / |lambda_u| when that is below 1;
  // N_0's unstable radius is about 0.6 |lambda_u| t.
  double unstable_start = 2e-3;
  // The most iterates of G followed from the fundamental domain in the homoclinic search.
  int max_return = 40;
  // The most vertices of the polyline of the unstable manifold.
  long max_vertices = 20000;
  // Largest spacing of the polyline's vertices (Euclidean in (theta, v)).
  double spacing = 0.1;
  // Radius (in e_u, e_s coordinates, which stretch distances where e_u and e_s are nearly
  // parallel) of the neighbourhood of p where a crossing of the polyline with the stable
  // line counts as a return.
  double neighbourhood = 0.5;
  // The largest unstable radius of an h-set (Euclidean; at least twice N_0's): keeps every
  // h-set small, on one branch.
  double cap = 3e-3;
  // Margin of the radii: an image must reach (1 + margin) times past the next h-set's edge.
  double margin = 0.25;
  // Margin of the stable radii: an h-set's stable radius is (1 + stable_margin) times its
  // predecessor's sampled image spread (room for the enclosures' second-order error).
  double stable_margin = 1.0;
  // Significant decimal digits of the h-sets' exact centres and frames.
  int digits = 40;
  // The most homoclinic candidates tried per attempt (each a chain of h-sets checked in full).
  int max_candidates = 4;
  // Attempts: each further one divides unstable_start and cap by 4 (smaller h-sets, nearer
  // p, a longer return), tried when the one before proved nothing.
  int attempts = 3;
};

// The saddle and homoclinic orbit the search found (doubles, for reports).
struct ChaosSearchOrbit {
  // The saddle's period k (G = F^k) and point (theta, v).
  int period = 0;
  double theta = 0, v = 0;
  // Its multipliers lambda_u, lambda_s.
  double lambda_u = 0, lambda_s = 0;
  // q_0 = p + t e_u: the homoclinic orbit's start.
  double t = 0;
  // m: q_m is the deep return; its distance |s_m| from p along e_s.
  int m = 0;
  double return_distance = 0;
};

// One covering checked by certify_chaos.
struct ChaosCovering {
  // N_from => N_to.
  int from = 0, to = 0;
  // check_covering's answer.
  CoveringResult result;
};

// The answer of certify_chaos.
struct ChaosSearchResult {
  // A positive entropy bound is proved: disjoint h-sets and coverings with rho > 1.
  bool proved = false;
  // The certificate (h-sets, proved coverings, k, bits, bound, quotient); filled when proved,
  // and with what was built otherwise (for reports).
  ChaosCertificate certificate;
  // The bound from the proved coverings (entropy_lower_bound).
  EntropyBound entropy;
  // What was proved, or what failed and why (no saddle, no homoclinic return, which
  // covering failed and its condition, h-sets not disjoint).
  std::string message;
  // The saddle and homoclinic orbit used (period 0 when no saddle was found).
  ChaosSearchOrbit orbit;
  // Every covering checked for the candidate reported, in order.
  std::vector<ChaosCovering> coverings;
  // The h-sets are pairwise certainly disjoint.
  bool disjoint = false;
  // Seconds: finding the saddle and homoclinic orbits; building and checking the h-sets
  // (over all attempts).
  double search_seconds = 0, check_seconds = 0;
  // Homoclinic candidates found (over all attempts).
  int candidates = 0;
};

// Searches a horseshoe of the impact map of `spec` and proves its entropy bound (header
// comment). Never guesses: without a proof, `proved` is false and `message` says why. Not
// attempted for the velocity-dependent model with veldep_collapse (its interval step does not
// decide the collapse test over a box: see the message).
ChaosSearchResult certify_chaos(const ModelSpec& spec, const ChaosSearchOptions& options = {});

}  // namespace bouncer
