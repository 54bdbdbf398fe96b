// Global continuation, first step (issue 23): the attractors of find_attractors
// (run/attractors.hpp) at values of one parameter, matched from value to value by the
// distance of their point sets (as Attractors.jl's global continuation matches by set
// distance), so that each attractor is one chain across the range with its basin share at
// each value: where a chain starts or ends, an attractor appears or disappears.
//
//     AttractorsSweepRequest s;  s.point = ...;  s.vary = Parameter::a;  s.lo = 23, s.hi = 23.2;
//     const AttractorsSweepResult r = sweep_attractors(s);
//     r.chains[k].index[i]: chain k's attractor in r.at[i].attractors, or -1 where it is absent
//
// Each periodic chain (and sticking cycle) is then handed to `continue`
// (analysis/continuation.hpp, continue_chains below): its branch is continued from the
// chain's orbit over the range, each border-collision end enclosed on both sides by Krawczyk
// (verify/border_collision.hpp) and each period doubling on the way too, and every
// appearance and disappearance of the chain between two values is tied to the branch event
// whose a* lies between them, or said not to be explained by one.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bouncer/run/attractors.hpp"

namespace bouncer {

struct AttractorsSweepRequest {
  AttractorsRequest point;   // everything but the varied parameter's value
  Parameter vary = Parameter::a;
  Decimal lo = Decimal::from_int(0), hi = Decimal::from_int(1);
  long values = 11;          // 2..10000, equally spaced (rounded to 20 decimals), ends included
  // Two attractors of neighbouring values are one chain when of one kind and period and
  // their point sets lie within this distance (Hausdorff; theta on the circle, v relative to
  // max(1, |v|)).
  double match_distance = 0.05;
  // continue_chains after the sweep: each periodic chain's branch continued (cheap), and
  // with certify_ends the ends and period doublings that explain a chain's appearance or
  // disappearance proved (Krawczyk, about 1 s each).
  bool continue_branches = true;
  bool certify_ends = true;
};

struct AttractorChain {
  int id = 0;
  AttractorKind kind = AttractorKind::undecided;
  long period = 0;
  std::vector<int> index;  // per value: the attractor's index at that value, or -1
  // Values k where the chain was joined across (k, k+1) by its continued branch, not by the
  // match distance (merge_split_chains: the orbit moved farther than the distance allows).
  std::vector<size_t> joined;
};

// One event of a continued branch: an end (the orbit ceases to exist on the branch's piece:
// border collision, fold, ...) or a smooth bifurcation on the way (period doubling,
// Neimark-Sacker, fold: the orbit's stability changes, the branch goes on).
struct BranchEventInfo {
  bool end = false;           // an end of the branch (else a bifurcation on it)
  bool high = false;          // ends: the high end (the orbit exists below a*)
  std::string kind;           // ends: name(EndReason) (border, fold, event_change, lost, ...);
                              // bifurcations: name(SmoothKind) (period_doubling, fold, neimark_sacker)
  double param = 0;           // a*: the continuation's (its scalar's) bracket midpoint
  std::string param_text, bracket_lo, bracket_hi;  // as the continuation's scalar prints them
  std::string detail;         // e.g. "impact 2 reaches the knot theta = 1/2"
  // Krawczyk (border ends: certify_border_collision; period doublings: certify_period_doubling).
  bool tried = false, certified = false;
  Enclosure enclosure;        // a* in [lo, hi] (exact decimals) when certified
  std::string reason;         // why not certified
};

struct ContinuedBranch {
  AttractorKind kind = AttractorKind::periodic;  // periodic | sticking
  long period = 0;
  std::vector<int> chains;    // the chains that are this branch (the first one started it)
  size_t from_value = 0;      // the sweep value it was started at (the chain's largest share)
  bool started = false;
  std::string note;           // why not started
  std::string low_param, high_param;  // its span (the continuation's last points), as printed
  double low = 0, high = 0;           // the same span as doubles (for comparisons)
  std::string events_text;    // event sequence at the start (analysis/continuation.hpp event_text)
  std::vector<BranchEventInfo> events;  // low end, the bifurcations, high end: increasing param
  long corrector_runs = 0;
};

// A chain appears (absent at values[before], present at values[after]) or disappears
// (present at values[before], absent at values[after]); event: the branch event with a* in
// [values[before], values[after]] (widened by 1e-9 relative, the continuation's a* being
// located to ~2^-44) that explains it (an end on the side where the chain is absent,
// preferred, or a bifurcation on the branch), or -1.
struct ChainTransition {
  bool appears = false;
  size_t before = 0, after = 0;
  int branch = -1, event = -1;
};

struct ChainBranches {
  std::vector<ContinuedBranch> branches;
  std::vector<int> chain_branch;                       // per chain: its branch, or -1
  std::vector<std::vector<ChainTransition>> transitions;  // per chain, in increasing value
  double seconds = 0;
};

struct AttractorsSweepResult {
  AttractorsSweepRequest request;
  std::vector<Decimal> values;
  std::vector<AttractorsResult> at;  // per value
  std::vector<AttractorChain> chains;
  std::optional<ChainBranches> branches;  // with request.continue_branches
};

// The Hausdorff distance of two attractors' point sets (infinity if either has none).
double attractor_distance(const FoundAttractor& x, const FoundAttractor& y);

// One attractor split into two chains by the matching (its orbit moved more than the match
// distance between two values): chain x disappears between values k and k+1 and chain y
// appears there, neither explained by a branch event, both lie on one continued branch, and
// that branch spans [values[k], values[k+1]] with no event in it. Then y is x continued: y's
// values join x (x.joined records k) and y is removed; chains are renumbered. Needs
// r.branches (continue_chains); sweep_attractors calls it.
void merge_split_chains(AttractorsSweepResult& r);

// Throws InputError for a bad request ("vary", "range", "values", and find_attractors').
// With r.continue_branches, also continue_chains (r.certify_ends: certify).
AttractorsSweepResult sweep_attractors(const AttractorsSweepRequest& r, const GridOptions& run = {});

// Each periodic or sticking chain of period <= kMaxBranchPeriod = 2000 (analysis/continuation.hpp,
// `continue`'s limit) has its
// branch continued (in the sweep's precision) from the
// chain's orbit at the value of its largest share, over the sweep's range; a chain whose
// orbit at that value lies on a branch already continued (same period, Newton from the
// branch's nearest orbit converging onto the chain's) is that branch, not continued again.
// Each chain's appearances and disappearances inside the range are tied to the branch events;
// with certify, every event of every branch (tied or not) is proved: border ends on both sides of
// a* (verify/border_collision.hpp certify_branch_ends), period doublings
// (certify_period_doubling) and folds (certify_fold); the other ends are reported, not proved.
// The proofs run on `threads` workers (GridOptions::threads); the result does not depend on it.
ChainBranches continue_chains(const AttractorsSweepResult& r, bool certify, int threads = 1);

}  // namespace bouncer
