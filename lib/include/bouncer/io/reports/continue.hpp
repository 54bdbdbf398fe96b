// `bouncer continue`'s outputs, from the typed branch (analysis/continuation.hpp) and the
// certificates of its ends (verify/branch_end.hpp): the end sentences, PREFIX.csv (one row
// per branch point), the JSON summary (PREFIX.json, --json), the text summary and the branch
// diagram (PREFIX.png). Instantiated for the analysis scalars (scalar/scalar_set.hpp).
#pragma once

#include <string>

#include "bouncer/analysis/continuation.hpp"
#include "bouncer/io/plot.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/io/requests/continue.hpp"
#include "bouncer/model/model.hpp"
#include "bouncer/verify/border_collision.hpp"

namespace bouncer {

// What the map does beyond an end, in words ("a periodic orbit of period 3", "a chaotic
// attractor (lambda 0.123)", ...).
std::string class_words(const Classification& c);

// Why a branch ended, in words: "a border collision", "a grazing", "a touchdown", "the
// sticking threshold" (border, by its Margin), "a fold", ...; "" for range_end and max_points.
std::string cause_words(EndReason reason, int margin);

// One end of the branch in one sentence: where and why it ends, and what the map does just
// beyond it ("period 2 ends at a* = 0.61 by a grazing (...); beyond it the orbit goes to ...").
template <class T>
std::string branch_end_sentence(const Branch<T>& b, const BranchEnd<T>& e, Parameter vary);

// The statement of a --certify result on one end ("certified (Krawczyk): ..." or "nothing
// certified next to a*").
std::string certified_end_statement(const CertifiedBranchEnd& c, long period, Parameter vary);
// The two-sided certificate of one end in words (its theorem, or why not certified), and
// whether the branch's own bracket of a* contains it.
std::string two_sided_statement(const CertifiedBranchEnd& c);

// PREFIX.csv without its provenance lines: the header, then one row per branch point
// (parameter, stability, the two multipliers, events, the least margins, the residual and
// the orbit points).
template <class T>
std::string branch_csv(const Branch<T>& b, Parameter vary);

// The JSON document {provenance, summary} of PREFIX.json and --json (two-space indent,
// ending in a newline). m: the branch's model (the wall's knots name a border's knot).
template <class T>
std::string branch_json(const ContinueRequest& r, const Model<T>& m, const Branch<T>& b, const CertifiedBranchEnds& certified,
                        const Provenance& p);

// The text summary: provenance lines, the branch, its two end sentences, the certified
// statements and the smooth bifurcations.
template <class T>
std::string branch_text(const ContinueRequest& r, const Branch<T>& b, const CertifiedBranchEnds& certified,
                        const Provenance& p);

// The branch diagram: v (or theta, show_theta) of every orbit point against the parameter,
// by stability, with a vertical line at each located end and bifurcation; zoomed axes for a
// range a double cannot resolve. Carries the provenance as PNG metadata.
template <class T>
Figure branch_figure(const ContinueRequest& r, const Model<T>& m, const Branch<T>& b, bool show_theta, const Provenance& p);

}  // namespace bouncer
