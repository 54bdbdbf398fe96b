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
// Not yet: the command (`attractors --vary`), the stacked share figure, and the hand-over
// of each appearance and disappearance to `continue` (analysis/continuation.hpp).
#pragma once

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
};

struct AttractorChain {
  int id = 0;
  AttractorKind kind = AttractorKind::undecided;
  long period = 0;
  std::vector<int> index;  // per value: the attractor's index at that value, or -1
};

struct AttractorsSweepResult {
  AttractorsSweepRequest request;
  std::vector<Decimal> values;
  std::vector<AttractorsResult> at;  // per value
  std::vector<AttractorChain> chains;
};

// The Hausdorff distance of two attractors' point sets (infinity if either has none).
double attractor_distance(const FoundAttractor& x, const FoundAttractor& y);

// Throws InputError for a bad request ("vary", "range", "values", and find_attractors').
AttractorsSweepResult sweep_attractors(const AttractorsSweepRequest& r, const GridOptions& run = {});

}  // namespace bouncer
