// The bouncer's impact map as a box map for covering relations (verify/covering.hpp): the
// enclosure of F^k over a box of states (theta, v), every event of every step decided for the
// whole box by the certified enclosures of verify/enclosure.hpp (naive boxes, or Lohner's
// mean-value form started from the box), and the same smooth piece of F^k for every box.
//
// Covering relations need F^k continuous on each h-set. The impact map is piecewise smooth,
// and not continuous everywhere (a flight that grazes the wall). So the map is tied to one
// branch, the sequence of pieces of the k steps (per step: the event kind, the wall segment
// of the impact, whether it is at a corner, and the whole wall periods begun, so that theta's
// wrap to [0, 1) is the same too), given by impact_branch at a point of the h-set (its
// centre). On every box it answers, F^k is that branch's one smooth formula, so on an h-set
// all of whose pieces are answered F^k is continuous.
//
// Nothing (std::nullopt) when a step is undecided over the box (a branch point of the map,
// a wall corner, a wrap of theta inside it), when the box's branch is not the given one, when
// a step is not an impact (a sticking collapse or a ride), or when an enclosure is not finite.
#pragma once

#include <string>
#include <vector>

#include "bouncer/analysis/continuation.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/verify/covering.hpp"
#include "bouncer/verify/enclosure.hpp"

namespace bouncer {

// One step of a branch of F^k: its smooth piece and the wall periods it begins.
struct BranchStep {
  // The event kind, the impact's segment, corner (analysis/continuation.hpp).
  StepEvent event;
  // Whole wall periods begun during the step (theta's wraps).
  long long periods = 0;
  // The same piece and the same wraps.
  bool operator==(const BranchStep& o) const { return event.same_piece(o.event) && periods == o.periods; }
};

// The branch of F^k through the state (theta, v) (exact rationals, enclosed at `bits`),
// decided by the interval step; empty if a step is undecided there even at a point.
std::vector<BranchStep> impact_branch(const ModelSpec& spec, long k, long bits, const mpq_class& theta,
                                      const mpq_class& v);

// Text of a branch: event_text's tokens with the wraps, e.g. "I0+1 I1+0".
std::string branch_text(const std::vector<BranchStep>& branch);

// F^k of the model `spec` (parameters enclosed at `bits`) as a box map over (theta, v),
// answering only boxes whose k steps are all impacts along `branch` (its size is k).
BoxMap2 impact_box_map(const ModelSpec& spec, const std::vector<BranchStep>& branch, long bits,
                       EnclosureMethod method = EnclosureMethod::lohner);

// The same on parallelograms (SetMap2): Lohner's enclosure started from the piece c + B r
// itself (no box around it), returning its final c' + B' r'.
SetMap2 impact_set_map(const ModelSpec& spec, const std::vector<BranchStep>& branch, long bits);

}  // namespace bouncer
