// A certificate of chaos (issue 26): the h-sets and coverings of a horseshoe, with the map they
// are coverings of, written to a file and replayed by a second, independent interval library.
//
// The file form (JSON) is io/chaos_certificate.hpp's.
//
// What a certificate states: the h-sets N_0..N_{m-1} (exact rational centres and frames, as in
// verify/covering.hpp) are pairwise disjoint, and each listed covering N_i => N_j holds for
// G = F^k, F the map named in the certificate. From those facts alone the entropy bound
// h_top(F) >= log(rho(A)) / k follows (A the 0/1 matrix of the listed coverings; covering.hpp's
// header comment gives the theorem). The certificate also states the bound; a replay recomputes
// it from the coverings it has itself proved and rejects the certificate if the stated bound is
// above the recomputed one.
//
// The replay (replay_certificate) shares no arithmetic with the code that made the certificate:
// it evaluates the map in Arb (FLINT's ball arithmetic, libflint-arb) with its own
// implementation of the map written from the model's physics (docs/model.md), decides every
// branch of every step in Arb, takes images to local coordinates in Arb, checks disjointness in
// exact rationals with its own code, and bounds rho(A) by its own Collatz-Wielandt quotient. So a
// bug in MPFI, in bouncer's impact map or in its covering checks cannot make a false
// certificate pass the replay: both would have to be wrong the same way.
#pragma once

#include <gmpxx.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "bouncer/model/spec.hpp"
#include "bouncer/verify/covering.hpp"

namespace bouncer {

// The map a certificate is about.
enum class ChaosMap {
  // The bouncer's impact map of `model` (triangle or any piecewise-linear wall; every step an
  // impact, no sticking or riding on the h-sets).
  impact,
  // The Henon map (x, y) -> (1 - a x^2 + y, b x) with exact decimal a, b: a test map with a
  // published horseshoe, so that the replay and the tamper tests run in milliseconds.
  henon,
};

// The name of a map ("impact", "henon").
const char* name(ChaosMap m);

// One covering N_from => N_to of G = F^k, as stated in a certificate.
struct CertifiedCovering {
  // The h-set covered from and the h-set covered (0-based indices into `sets`).
  int from = 0;
  int to = 0;
  // +1: N_from's left edge maps to the left of N_to; -1: swapped.
  int sign = 0;
  // The subdivision (pieces per side of N_from, in its local coordinates) that proved it.
  int pieces = 1;
  // The branch of F^k on N_from, as covering_impact.hpp's branch_text (documentation only:
  // the replay decides every branch itself and requires one branch over the whole h-set).
  std::string branch;
};

// A horseshoe: everything a replay needs, in exact numbers.
struct ChaosCertificate {
  // Which map.
  ChaosMap map = ChaosMap::impact;
  // The model (map impact): law, a, eps or c, wall, as exact decimals.
  ModelSpec model;
  // The Henon parameters (map henon), exact decimals.
  Decimal henon_a = Decimal::from_int(0);
  Decimal henon_b = Decimal::from_int(0);
  // Iterates of F per covering: G = F^k.
  int k = 1;
  // The precision (bits) at which the maker proved the coverings (the replay picks its own).
  long bits = 128;
  // The h-sets, pairwise disjoint.
  std::vector<HSet2> sets;
  // The coverings proved (each pair at most once).
  std::vector<CertifiedCovering> coverings;
  // The stated bound: log(q)/k rounded down as an exact decimal text (EntropyBound::bound), q
  // the Collatz-Wielandt quotient (EntropyBound::quotient), an exact rational.
  std::string entropy_bound;
  mpq_class quotient;
  // Provenance: the command (or call) that made it, bouncer's version and commit.
  std::string made_by;
};

// What one covering's replay found.
struct ReplayedCovering {
  // Proved by the replay, with the certificate's sign.
  bool proved = false;
  // A sentence: what held, or which condition failed where.
  std::string message;
};

// The verdict of replay_certificate.
struct ReplayResult {
  // Every check below held: the certificate is a proof (by Arb) of its stated bound.
  bool valid = false;
  // The h-sets are pairwise disjoint (exact rational test).
  bool disjoint = false;
  // One entry per covering of the certificate, in its order.
  std::vector<ReplayedCovering> coverings;
  // The bound recomputed from the coverings the replay proved (decimal text, rounded down),
  // and whether the certificate's stated bound is at most it.
  std::string recomputed_bound;
  bool bound_holds = false;
  // The Arb precision used.
  long bits = 0;
  // Sentences: every failure, or "valid".
  std::vector<std::string> problems;
};

// Replays a certificate with Arb at `bits` (each covering at its stated subdivision, then 4
// and 16 times finer where that fails, up to 256 pieces per side) (independent of MPFI and of bouncer's impact map;
// see the header comment). Never throws on a false certificate: it says what failed.
ReplayResult replay_certificate(const ChaosCertificate& c, long bits = 256);

// The version of the Arb library the replay was built with ("2.23.0"), for provenance.
std::string arb_library_version();

// The replay's own map at a point, for tests against bouncer's map: G = F^k of the
// certificate's map at (x0, x1) (exact), enclosed in Arb at `bits`, as [lo, hi] per
// coordinate (exact rationals); nullopt if a branch is not decided there.
std::optional<std::array<std::array<mpq_class, 2>, 2>> replay_iterate(const ChaosCertificate& c, const mpq_class& x0,
                                                                       const mpq_class& x1, long bits = 256);

}  // namespace bouncer
