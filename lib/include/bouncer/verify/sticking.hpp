// Certified sticking periods (constant restitution; paper sec. II.B.3 and IV).
//
// From the release state (1/2, 4) (or a given start) the orbit is followed in intervals
// (verify/enclosure.hpp, Lohner by default) with precision escalation until the first
// sticking step. The sticking period is the number of steps from the start to the next
// release: the number of ImpactMap::step calls until one returns kind == sticking (the
// sticking step itself counts as one).
//
// Outcomes:
//   sticks                        certified: the first sticking is at step `period`;
//   never_sticks                  certified: the orbit never sticks. Proof: after step n it
//                                 lies in a parallelogram K = z + E [-rho, rho]^2 (E: the
//                                 eigenvectors of DF^p, else the axes) with F^q(K) inside K
//                                 (q a multiple of the period p of the periodic attractor it
//                                 falls onto; F^q(K) enclosed by the Lohner method, the
//                                 inclusion checked in interval arithmetic), and no point of
//                                 F^i(K), 0 <= i < q, sticks; by induction no later step
//                                 sticks. (A period-p orbit in K follows by Brouwer, but is
//                                 not needed.)
//   no_sticking_within_max_steps  certified: steps 1..max_steps do not stick;
//   undecided                     no run finished: steps 1..steps_checked do not stick
//                                 (certified), step steps_checked + 1 was undecided at
//                                 every precision of the schedule.
// With an interval parameter a = [A0, A1] every certified statement holds for every a in it.
#pragma once

#include <gmpxx.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bouncer/model/spec.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "bouncer/verify/escalation.hpp"

namespace bouncer {

enum class StickingOutcome { sticks, never_sticks, no_sticking_within_max_steps, undecided };
const char* name(StickingOutcome o);

struct StickingQuestion {
  ModelSpec model;                 // constant law
  InitialCondition start{Decimal::parse("0.5").value(), Decimal::from_int(4)};
  // Start at the wall's release state (theta_r, u(theta_r)) instead of `start`: a smooth
  // wall's theta_r = asin(a/(4 pi^2))/(2 pi) is irrational, so the run's interval model
  // encloses it (and a range of a moves it). Smooth walls only: a piecewise wall's release is
  // an exact knot, given as `start` (the triangle's (1/2, 4)).
  bool from_release = false;
  std::optional<std::pair<mpq_class, mpq_class>> a_range;  // a as the interval [lo, hi]
  long long max_steps = 100000;
  // interval:double first, then MPFI at 64, 128, ... 4096 bits.
  EscalationSchedule schedule{64, 4096, false, true};
  EnclosureMethod method = EnclosureMethod::lohner;
  bool prove_attractor = true;     // try to prove never_sticks when no sticking is found
  long max_attractor_period = 2000;
};

// The trapping-box proof of never_sticks.
struct AttractorProof {
  long period = 0;           // p: period of the attractor (recurrence of the enclosures)
  long iterate = 0;          // q = m p with F^q(K) inside K
  long long entered_at = 0;  // the orbit's enclosure lies in K after this step
  std::string box;           // K: z, rho, E, and the box enclosing F^q(K)
};

struct StickingCertificate {
  StickingOutcome outcome = StickingOutcome::undecided;
  bool certified = false;            // the outcome's statement is proved (all but undecided)
  std::optional<long long> period;   // sticks only
  long bits = 0;                     // bits of the run that certified it (0: none)
  std::string scalar;                // its scalar: "interval:double" or "interval:BITS"
  long long steps_checked = 0;       // steps certified free of sticking (period - 1 if sticks)
  std::string reason;                // why it stopped (undecided) or extra detail
  std::vector<Attempt> attempts;
  double seconds = 0;
  long long fallbacks = 0;           // Lohner steps that used the naive box (certifying run)
  std::optional<AttractorProof> attractor;
  // sticks: the release state after the sticking step (exact decimals), when its enclosure
  // is a single number (it is a wall corner and the wall's velocity there); else empty.
  std::string release_theta, release_v;
};

// Certified long-run answers (certify_sticking, and the certified grids through
// certified_point.hpp) exist for constant restitution (the certified collapse test) and for
// velocity-dependent restitution without collapse (no orbit collapses in finitely many steps
// there: eps(v) -> 1 as the relative speed -> 0; the run certifies the orbit and looks for a
// trapping set). Returns "" for those models, else why not, for an error message.
std::string why_no_certified_answers(const ModelSpec& model);

// Throws InputError("model", ...) for a model why_no_certified_answers refuses.
StickingCertificate certify_sticking(const StickingQuestion& q);

// The certified orbit alone, in any model but velocity-dependent collapse (the elastic one
// too): certify_sticking's run without the model check and without the attractor search
// (prove_attractor is ignored).
// Outcomes: no_sticking_within_max_steps (steps 1..max_steps certified), sticks (a certified
// collapse, as in certify_sticking) or undecided (certified through steps_checked). The
// certified grids use it for the elastic model, whose points can state no more: an
// area-preserving map has no trapping set (certified_point.hpp).
StickingCertificate certify_orbit_steps(const StickingQuestion& q);

// What a plain (non-interval) run computes for the same question: the step of the first
// sticking within max_steps, or nullopt. `undecided` when a step failed (NaN/overflow).
struct PlainSticking {
  std::optional<long long> period;
  long long steps_run = 0;
  bool failed = false;
};
// T a point scalar (scalar/scalar_set.hpp); bits used by Mpfr only. With a_range the
// midpoint of the range is used (as a decimal).
// from_release: from the wall's release state, as StickingQuestion::from_release.
template <class T>
PlainSticking plain_sticking_period(const ModelSpec& model, const InitialCondition& start, long bits,
                                    long long max_steps, bool from_release = false);

// The start of a question in words: "(theta, v) = (0.5, 4)", or the release state.
std::string start_text(const StickingQuestion& q);

// Adaptive bisection of a parameter interval a in [lo, hi].
struct RangeOptions {
  int max_depth = 10;        // at most 2^max_depth pieces of the smallest size
  int max_pieces = 400;      // stop bisecting after this many runs
};

struct RangePiece {
  mpq_class lo, hi;
  StickingCertificate cert;
};

struct RangeReport {
  mpq_class lo, hi;
  std::vector<RangePiece> pieces;      // in order, covering [lo, hi]
  mpq_class uncertified_length;        // total length of undecided pieces
  std::string theorem;                 // the computer-assisted theorem, one paragraph
  double seconds = 0;
};

RangeReport certify_sticking_range(const StickingQuestion& q, const RangeOptions& opt);

// One-line statement of a certificate ("sticks with period 7", ...).
std::string describe(const StickingCertificate& c, long long max_steps);

// Is a plain run's answer consistent with what was certified? sticks: the same period;
// never_sticks, no_sticking_within_max_steps: no sticking and no failed step; undecided:
// no sticking within the steps certified free of it.
bool plain_agrees(const StickingCertificate& c, const PlainSticking& d);

// The double run (plain_sticking_period<double>, 53 bits) of each piece of a range at the
// piece's midpoint, a = (lo + hi) / 2 as an exact decimal: in the order of rep.pieces.
std::vector<PlainSticking> double_sticking_at_midpoints(const StickingQuestion& q, const RangeReport& rep);

}  // namespace bouncer
