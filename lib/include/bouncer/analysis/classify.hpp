// Attractor types: what an orbit does in the long run, with the evidence.
// (Implemented in lib/src/analysis/classify.cpp for double and Mpfr.)
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/scalar/precision.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

enum class OrbitClass {
  fixed,               // period 1 (including the paper's marginally stable families)
  periodic,            // period q > 1
  sticking,            // sticking solution with sticking period k
  quasiperiodic,       // bounded, not periodic, exponent ~ 0
  chaotic,             // bounded, positive leading Lyapunov exponent
  unbounded,           // Fermi acceleration (elastic)
  effective_sticking,  // velocity-dependent chatter to the wall's velocity within precision
  undecided,           // the evidence does not decide, or a step was undecided
  transient_chaos,     // chaotic in the window, settled later (re-check): see settled_*
  outside,             // not an orbit: a grid start below the wall's velocity (never from classify)
};
inline constexpr int kOrbitClassCount = static_cast<int>(OrbitClass::outside) + 1;
// The class's name in every output ("fixed", ..., "transient_chaos", "outside"): the one
// spelling of the classes, used by the CSV/JSON writers, the scan's columns and Python.
const char* name(OrbitClass c);
// The class of a name (the inverse of name); nullopt for any other text.
std::optional<OrbitClass> orbit_class_named(std::string_view text);

struct Classification {
  OrbitClass cls = OrbitClass::undecided;
  long period = 0;         // q for fixed/periodic, k for sticking, 0 otherwise
  double lambda = 0;       // leading Lyapunov exponent per collision (NaN if not computed)
  std::string evidence;    // one line: what decided the class
  double alpha = 0;        // unbounded only: growth law v ~ n^alpha of the running max of v

  // transient_chaos only: what the orbit settled on (class and period in `period`) and the
  // step from which it stays there (0 when not sharp: effective sticking, quasiperiodic).
  OrbitClass settled_class = OrbitClass::undecided;
  long settled_at = 0;

  // unbounded only: the shape of the growth (accelerator modes vs diffusion).
  // With an accelerator mode, growth_rate and branches are measured after its capture.
  double growth_rate = 0;         // mean dv per step over the window
  int branches = 0;               // phase clusters on the circle (spokes of the polar portrait); 0: no gap
  long accel_period = 0;          // Q: phases repeat every Q steps while v grows (0: none)
  double accel_gain = 0;          // D: mean velocity gain per Q steps
  long captured_from = 0;         // accelerator: the window's step (0-based) from which it recurs
  std::string growth_kind;        // accelerator | diffusive | irregular

  // classify_many with RecheckRule::recurrence only: the further steps after which the
  // start's re-check joined a known aperiodic set (its evidence says so too); 0 when the
  // re-check ran whole (or there was none).
  long recheck_joined_at = 0;
};

// How classify_many re-checks (rule 7) the aperiodic verdicts of many starts of one map.
enum class RecheckRule {
  // Every start runs the whole re-check, R steps then a window, exactly as classify() alone.
  full,
  // A start whose re-check orbit stays kJoinSteps consecutive steps in the cells of a chaotic
  // set on which an earlier start of the same call stayed chaotic through its whole re-check
  // stops there: its later window is taken at that step, and if it says chaotic that is the
  // label; otherwise the run goes on to the full R. Dissipative maps only (conservative ones
  // re-check in full). docs/guide/dynamics.md, "Re-checks".
  recurrence,
};
const char* name(RecheckRule r);
std::optional<RecheckRule> recheck_rule_named(std::string_view text);

struct ClassifyOptions {
  long transient = 5000;   // steps discarded first (paper: 5000)
  long steps = 500;        // steps examined (paper: 500)
  long max_period = 64;    // longest period looked for
  // A `chaotic` verdict is re-checked after recheck_factor x max(transient, steps) further
  // steps; an orbit that has settled by then is transient_chaos. 0 turns the re-check off.
  long recheck_factor = 20;
  // classify_many only (classify() has no other starts to share with). full: every start's
  // label is classify()'s (basin); scan's requests default to recurrence (`scan --recheck`).
  RecheckRule recheck = RecheckRule::full;
  // An orbit whose state recurs exactly (every bit) before the window, in the transient or the
  // re-check's R steps, is carried along its cycle instead of stepped: a deterministic map
  // repeats it for ever, so the results are the same, bit for bit (tested). False steps every
  // step (tests, benchmarks).
  bool exact_cycles = true;
};

template <class T>
Classification classify(const ImpactMap<T>& map, State<T> start, const ClassifyOptions& opt);

// classify() of each start, for many starts of one map at once, faster. With opt.recheck =
// full (the default) the same results as classify(), bit for bit (tested); with recurrence
// (the scan's default), a start re-checked on an aperiodic set that earlier starts of the call
// have already followed through whole re-checks stops early (RecheckRule; its evidence says so). The first
// windows' steps go four orbits side by side, so that the processor overlaps their chains of
// dependent operations (bench_grid: scan).
template <class T>
std::vector<Classification> classify_many(const ImpactMap<T>& map, const std::vector<State<T>>& starts,
                                          const ClassifyOptions& opt);

// The distance of two states of the section, the one metric of the recurrence tests
// (classify, attractors) and of continuation's orbit comparisons: theta compared modulo 1
// (in wall periods), v relative to max(1, |x.v|); the larger of the two.
template <class T>
double state_distance(const State<T>& x, const State<T>& y) {
  using Tr = ScalarTraits<T>;
  double dt = std::fabs(Tr::to_double(x.theta - y.theta));
  dt -= std::floor(dt);
  dt = std::min(dt, 1.0 - dt);
  const double scale = std::max(1.0, std::fabs(Tr::to_double(x.v)));
  return std::max(dt, std::fabs(Tr::to_double(x.v - y.v)) / scale);
}

// One start of a model point at a precision (an analysis precision: double, long, dd, quad,
// mpfr:BITS), in the scalar type it names.
Classification classify_start(const ModelSpec& spec, const Precision& precision, const InitialCondition& start,
                              const ClassifyOptions& opt);

// Whether two classifications describe the same behaviour: the same class and period (for
// transient chaos also what it settles on; for unbounded orbits the same growth kind and
// accelerator period). Exponents and evidence may differ: two precisions of a chaotic orbit
// follow different orbits of the same attractor.
bool same_behaviour(const Classification& x, const Classification& y);
// What differs between them, in a few words, "" when same_behaviour: "class", "period",
// "growth kind accelerator vs diffusive", "accelerator period 33 vs 11", "settles on periodic
// vs sticking" (x's first). No commas: a CSV field as it stands (basin --confirm).
std::string behaviour_difference(const Classification& x, const Classification& y);

// "classify knows when double lies": the start classified at the run's precision, then again
// at MPFR precisions that follow the exact orbit longer.
enum class PrecisionVerdict {
  agrees,               // the first check gives the same behaviour
  artefact,             // the first check differs, and a second at twice its bits agrees with it
  precision_dependent,  // the two checks differ too: not decided at these precisions
};
const char* name(PrecisionVerdict v);

struct PrecisionCheck {
  Precision precision;
  Classification result;
};

struct CheckedClassification {
  Classification result;               // at the requested precision
  std::vector<PrecisionCheck> checks;  // at mpfr:B; if it differs, also at mpfr:2B
  PrecisionVerdict verdict = PrecisionVerdict::agrees;
  std::string summary;                 // one line, e.g. "double's class is an artefact here: ..."
};

// B = max(check_bits, 2 x the run's bits) (check_bits >= 64). Same windows in every run.
CheckedClassification classify_checked(const ModelSpec& spec, const Precision& precision, const InitialCondition& start,
                                       const ClassifyOptions& opt, long check_bits);

// The two precisions of a check of a run at `run`: mpfr:B, B = max(check_bits, 64, 2 x the
// run's bits), and mpfr:2B (both at most kMaxBits).
std::pair<Precision, Precision> check_precisions(const Precision& run, long check_bits);
// The check itself, for a run's `result` at `run`, where `at(p)` classifies the same start with
// the same windows at precision p: classify_checked, and the grids' --confirm (run/basin.hpp,
// run/scan.hpp), whose starts are cell centres rather than decimals.
CheckedClassification check_precision(const Classification& result, const Precision& run, long check_bits,
                                      const std::function<Classification(const Precision&)>& at);

// Instantiated in lib/src/analysis/classify.cpp for the analysis scalars (scalar/scalar_set.hpp).
#define BOUNCER_X(T, kind) \
  extern template Classification classify<T>(const ImpactMap<T>&, State<T>, const ClassifyOptions&); \
  extern template std::vector<Classification> classify_many<T>(const ImpactMap<T>&, const std::vector<State<T>>&, \
                                                               const ClassifyOptions&);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
