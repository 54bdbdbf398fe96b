// Parameter families: a period-q orbit of the Newton solver continued in a, eps or c
// (DESIGN.md sec. 6). The map is piecewise smooth; on a region of the parameter where the
// orbit's event sequence (which wall segment each impact is on, corner impacts, sticking or
// not) is fixed, the orbit moves smoothly. A branch therefore ends at a border collision,
// where one of the margins below reaches 0, at a fold (multiplier +1), where the orbit
// meets another and disappears, or at the period doubling of a period-q/2 orbit it is born
// from (also a multiplier +1 of the period-q orbit, told from a fold by the orbit closing
// onto its half-period shift). Period doubling (-1) and Neimark-Sacker (a complex pair on
// the unit circle) are located on the way; the branch goes on through them.
//
// Method: natural-parameter continuation. Predictor: the secant through the last two
// accepted orbits (the last orbit itself for the first step); corrector: find_periodic at
// the new parameter value. A step is accepted when Newton converges, the minimal period is
// still q, the event sequence is unchanged (up to a rotation of the orbit) and the orbit
// did not jump away from the prediction; otherwise the step is halved. It grows by 3/2
// after a step Newton took in at most 3 iterations (to at most range/40). A step inside
// which a margin's secant puts its root aims short of that root. When a refused step falls
// below 1e-4 of the first step, the end is located between the last accepted value and the
// first refused one (the corrector runs at every trial value: secant steps on a vanishing
// margin, else bisection), down to the working precision (2^-44 relative for double,
// 2^-(bits-12) for the others).
// Implemented in lib/src/analysis/continuation.cpp for the analysis scalars
// (scalar/scalar_set.hpp).
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/analysis/end_estimate.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

// Parameter (a | eps | c) and name(Parameter): model/spec.hpp, shared with the certifier
// (verify/periodic_certify.hpp), so that one enum names the varied parameter everywhere.

// with_parameter / parameter_of on a Model<T>: model/model.hpp.

// The margins of one impact that end a branch when they reach 0.
//   knot:      distance of the impact phase to the nearest wall knot (= to the nearer end
//              of its segment), in periods;
//   clearance: the least gap (particle height - wall height) at the knots the flight passes
//              strictly inside it. On each linear segment the gap is concave in time, so
//              this is the least gap over the whole flight away from its two ends; 0 is a
//              grazing (the flight touches a wall corner, e.g. the triangle's top);
//   speed:     relative impact speed |v^- - fdot| (0: touchdown);
//   sticking:  for the constant-eps law, eps*speed - a(1-eps)/2 * (time left in the
//              segment), the test of ImpactMap::collide (<= 0: the collapse completes, the
//              particle sticks); NaN for the other laws.
// A smooth wall (the sine wall) has no knots: knot is NaN; clearance is the least local
// minimum of the gap x(t) - f(t) inside the flight (0: the flight touches the wall
// tangentially, a grazing); speed as above; sticking is 2 out - (1-eps) G (time to the
// release) where the effective gravity G = a + f''(theta) > 0, else 2 out (out: the relative
// rebound speed), the test of ImpactMap::sine_collide (<= 0: the particle sticks).
enum class Margin { knot, clearance, speed, sticking };
constexpr int kMargins = 4;

// The longest period continued (`continue --period`, `attractors --vary`'s branches): 2000,
// as certify-periodic's (verify/periodic_certify.hpp kMaxCertifiedPeriod: the proofs' dense
// preconditioner has (2Q)^2 entries). The border ends of such branches are proved by
// multiple shooting (verify/border_collision.hpp; the period-193 ends at a = 26.799 and
// 26.8001, veldep c = 1000, a few seconds each; the period-1096 ends around a = 21, about
// two minutes each).
constexpr long kMaxBranchPeriod = 2000;
const char* name(Margin);

// What one step of the orbit was: the smooth piece of the map it went through.
struct StepEvent {
  EventKind kind = EventKind::impact;
  int segment = 0;        // segment of the impact (sticking: of the collision that stuck)
  bool corner = false;    // the impact was exactly at a wall corner
  bool indirect = false;  // the flight rose above the wall's top (reported, not compared:
                          // the map is smooth across apex = top)
  bool smooth_wall = false;  // a smooth wall: segment 0 is the whole period (not printed)
  bool same_piece(const StepEvent& o) const { return kind == o.kind && segment == o.segment && corner == o.corner; }
};

// The event of one step of the map (what same_cycle compares and event_text prints).
template <class T>
StepEvent step_event(const StepResult<T>& r, bool smooth_wall) {
  StepEvent e;
  e.kind = r.kind;
  e.segment = r.kind == EventKind::sticking ? r.stick_segment : r.segment;
  e.corner = r.corner;
  e.indirect = r.indirect == Truth::yes;
  e.smooth_wall = smooth_wall;
  return e;
}
// Compact text: one token per step, I = impact, S = sticking, R = ride, then the segment
// (none on a smooth wall); "c" = at a corner, "^" = indirect flight. E.g. "I0 I1^ S0", and
// "I^ S" on the sine wall.
std::string event_text(const std::vector<StepEvent>& events);
// The same sequences up to a rotation (the same orbit started at another point).
bool same_cycle(const std::vector<StepEvent>& x, const std::vector<StepEvent>& y);

struct ImpactMargins {
  std::array<double, kMargins> value{};  // NaN: not defined (a ride; sticking for other laws)
  int knot = -1;                         // the nearest knot (knot margin)
  int graze_knot = -1;                   // the knot of the least clearance (-1: none passed)
  double graze_theta = std::numeric_limits<double>::quiet_NaN();  // a smooth wall: the phase of the least clearance
};

template <class T>
struct BranchPoint {
  T param;
  PeriodicOrbit<T> orbit;
  std::vector<StepEvent> events;        // events[i]: step from points[i] to points[i+1]
  std::vector<ImpactMargins> margins;   // margins[i]: of the impact ending step i
  std::array<double, kMargins> min_margin{};  // the least of each kind over the orbit
  std::array<int, kMargins> min_impact{};     // and its step (-1: none)
  // Smooth test functions of J = DP^q: det(J - I) (0 at a multiplier +1), det(J + I)
  // (0 at -1), det J - 1 (0 at a complex pair on the unit circle).
  double test_fold = 0, test_pd = 0, test_ns = 0;
  std::string stability;  // stable | unstable | marginal
};

enum class EndReason {
  range_end,        // the range's end was reached
  border,           // a margin reached 0 (border collision, grazing, touchdown, sticking)
  fold,             // det(J - I) -> 0 where the corrector stops converging
  doubling,         // det(J - I) -> 0 as the orbit closes onto a period-q/2 orbit traversed
                    // twice: the branch is born at that orbit's period doubling (its
                    // multiplier -1 is the doubled orbit's +1, so the multiplier test alone
                    // would call it a fold)
  event_change,     // the event sequence changes without an identified margin at 0
  period_collapse,  // the orbit falls onto one of smaller minimal period
  lost,             // the corrector stops converging, no margin or multiplier explains it
  max_points,       // --max-points reached
};
const char* name(EndReason);

// What the period-q orbit Newton finds just beyond an end is to the branch.
enum class BeyondRelation {
  none,          // no period-q orbit found beyond
  continuation,  // next to the branch's last orbit: the branch goes on with other events
  other_branch,  // another orbit, which already exists on the branch side of a*
  mother,        // at a doubling end: the period-q/2 orbit the branch is born from
  unrelated,     // away from the branch, and not found on the branch side: not decided
};
const char* name(BeyondRelation);

template <class T>
struct BranchEnd {
  EndReason reason = EndReason::range_end;
  T param;            // a*: the bracket's midpoint (range end, max points: the last point)
  T bracket_lo, bracket_hi;
  int margin = -1;    // Margin that reached 0 (border)
  int impact = -1;    // its step
  int knot = -1;      // the knot involved (knot, clearance)
  double graze_theta = std::numeric_limits<double>::quiet_NaN();  // a smooth wall's grazing: its phase
  long mother_period = 0;  // doubling: q/2, the period of the orbit the branch is born from
  std::string detail; // one phrase, e.g. "impact 3 reaches the knot theta = 1/2"
  State<T> last_point;  // the orbit's first point at the branch side of the bracket
  // Just beyond a*: a period-q orbit Newton finds there from the last orbit (if any), and
  // the class of the orbit from the last orbit point.
  bool beyond_done = false;
  T beyond_param;
  std::string beyond_orbit;  // event sequence of the period-q orbit found beyond, or ""
  long beyond_orbit_period = 0;
  BeyondRelation beyond_relation = BeyondRelation::none;
  Classification beyond;
  std::string beyond_note;
  // How far `param` can be trusted (estimate_end_accuracy below; not_estimated until it runs).
  EndEstimate estimate{};
};

enum class SmoothKind { fold, period_doubling, neimark_sacker };
const char* name(SmoothKind);

template <class T>
struct Bifurcation {
  SmoothKind kind;
  T param, bracket_lo, bracket_hi;
  long iterations = 0;
  EndEstimate estimate{};  // how far `param` can be trusted (estimate_end_accuracy)
};

struct ContinuationOptions {
  double step = 0;          // first step (0: range / 100)
  long max_points = 2000;   // accepted points, both directions together (half each)
  NewtonOptions newton{30, 1e-9, 8};
  ClassifyOptions classify{};
  double beyond = 1e-6;     // classify at a* + beyond * max(1, |a*|) past each end
  bool classify_beyond = true;
};

template <class T>
struct Branch {
  Parameter parameter = Parameter::a;
  long period = 0;
  bool started = false;            // the guess converged at the start value
  std::string note;                // why not started
  std::vector<BranchPoint<T>> points;  // in increasing parameter
  size_t start = 0;                // index of the start point
  BranchEnd<T> low, high;
  std::vector<Bifurcation<T>> bifurcations;  // in increasing parameter
  long corrector_runs = 0;
};

// Continues the period-q orbit through `guess` at the model's own value of `p` (which must
// lie in [lo, hi]) in both directions until each end of [lo, hi] or of the branch.
template <class T>
Branch<T> continue_branch(const Model<T>& m, Parameter p, long q, const State<T>& guess, const T& lo, const T& hi,
                          const ContinuationOptions& opt = {});

// Fills the `estimate` of b's two ends and of its bifurcations (analysis/end_estimate.hpp):
// `given` at a range end or --max-points; at a located end or bifurcation, the point
// re-located in Mpfr at p + 64 bits (p: T's mantissa bits) from next to T's bracket, with
// `spec` (the exact model b was computed with, its varied parameter at any value) and the
// options b was computed with; `not_estimated` with a note when the re-location fails. An
// estimate, not a proof.
template <class T>
void estimate_end_accuracy(const ModelSpec& spec, Branch<T>& b, const ContinuationOptions& opt = {});

// One orbit analysed: events, margins, tests (exposed for tests and the CLI).
template <class T>
BranchPoint<T> analyse_orbit(const Model<T>& m, Parameter p, PeriodicOrbit<T> orbit);

// Instantiated in lib/src/analysis/continuation.cpp for the analysis scalars
// (scalar/scalar_set.hpp).
#define BOUNCER_CONTINUATION_EXTERN(T, kind)                                                                           \
  extern template Branch<T> continue_branch<T>(const Model<T>&, Parameter, long, const State<T>&, const T&,       \
                                               const T&, const ContinuationOptions&);                            \
  extern template BranchPoint<T> analyse_orbit<T>(const Model<T>&, Parameter, PeriodicOrbit<T>);                     \
  extern template void estimate_end_accuracy<T>(const ModelSpec&, Branch<T>&, const ContinuationOptions&);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_CONTINUATION_EXTERN)
#undef BOUNCER_CONTINUATION_EXTERN

}  // namespace bouncer
