// Every attractor at a parameter point (`bouncer attractors`): many starts over the trapping
// region, each followed until it recurs onto something already seen, in the spirit of
// Attractors.jl's recurrence-based mapper (AttractorsViaRecurrences; Datseris & Wagemakers,
// "Effortless estimation of basins of attraction", Chaos 32, 023104, 2022):
//
//   * a grid of cells over the state space theta in [0, 1) x v in [lowest wall velocity,
//     trapping top]; each cell is unlabelled or belongs to one attractor found so far;
//   * a start's orbit walks the cells. It is decided
//       - exactly, when a step sticks and a sticking cycle is known (every sticking ends in
//         the release state (1/2, 4), whose future is one orbit),
//       - when it comes within `near` of a point of a known periodic attractor (checked on
//         that attractor's cells; a stable orbit attracts such a neighbourhood, unlike a cell,
//         which may hold points of two basins),
//       - after `consecutive_hits` consecutive steps on the cells of one aperiodic attractor
//         (chaotic set, family, ...);
//     it is a new attractor when it lands on cells it visited itself `consecutive_recurrences`
//     times in a row: then it is followed `attractor_steps` further steps, its cells
//     recorded, and the attractor characterized (below); leaving the grid above the trapping
//     top for `lost_steps` steps is an escape; `max_steps` steps without a decision:
//     undecided;
//   * a new attractor is matched with those already found (a periodic orbit by its points,
//     a sticking cycle by its release, a family by its velocities, an aperiodic set by the
//     overlap of its cells), so that one attractor found twice is one.
//
// Characterization: a sticking step in the recorded run -> sticking cycle (period k, the
// release state recurring exactly); the run repeating with period q <= max_period -> Newton
// (analysis/periodic.hpp find_periodic) gives the orbit and its multipliers (a multiplier 1:
// a family of periodic points, e.g. the paper's eq. 5 fixed points); otherwise classify
// (analysis/classify.hpp) decides: chaotic and quasiperiodic sets get their Lyapunov
// exponent (analysis/lyapunov.hpp) over `lyapunov_steps` steps; growth is an accelerator
// mode (phases recurring while v grows) or an escape. Each periodic attractor (and sticking
// cycle) is then proved by Krawczyk (verify/periodic_certify.hpp certify_periodic), with
// enclosures of its multipliers.
//
// Determinism: starts are taken in a fixed scrambled order in batches of fixed sizes (1, 1,
// 2, 4, ... up to 256); the starts of a batch are followed in parallel against the labels
// known before the batch, and their findings merged in start order. The result does not
// depend on the number of threads.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/run/grid.hpp"
#include "bouncer/scalar/decimal.hpp"
#include "bouncer/scalar/number.hpp"
#include "bouncer/scalar/precision.hpp"
#include "bouncer/verify/periodic_certify.hpp"

namespace bouncer {

enum class StartSampling {
  grid,    // nx x ny cell centres (as `bouncer basin`: the same starts)
  halton,  // nx * ny points of the Halton sequence (bases 2 and 3), a low-discrepancy set
};
const char* name(StartSampling s);

struct AttractorsRequest {
  ModelSpec model;
  long nx = 100, ny = 100;  // starts: 1..8192 each, at most 4e6 in all
  StartSampling sampling = StartSampling::grid;
  Decimal theta_lo = Decimal::from_int(0), theta_hi = Decimal::from_int(1);  // within [0, 1]
  // The starts' velocities; none: the trapping region (model/trapping.hpp), which the
  // elastic model and eps = 1 do not have (InputError "v-range").
  std::optional<std::pair<Decimal, Decimal>> v_range;
  // The recurrence grid: cells_theta x cells_v cells over theta in [0, 1) and v from the
  // lowest wall velocity to the trapping top (or the top of v_range, if higher), 16..4096.
  long cells_theta = 512, cells_v = 512;
  long consecutive_recurrences = 100;  // own cells revisited in a row: a new attractor (1..1e6)
  long attractor_steps = 1000;         // a new attractor followed further, its cells recorded (10..1e7)
  long consecutive_hits = 8;           // steps in a row on an aperiodic attractor's cells (1..1e6)
  long lost_steps = 20;                // steps in a row above the grid: an escape (1..1e6)
  long max_steps = 200000;             // per start: then undecided (100..1e9)
  long max_period = 64;                // longest period read off a recurrence (1..4096)
  long lyapunov_steps = 100000;        // exponent of an aperiodic attractor (100..1e9)
  ClassifyOptions classify;            // attractors that do not repeat within max_period
  bool certify = true;                 // Krawczyk for periodic attractors and sticking cycles
  long max_bits = 1024;                // the certificate's last MPFI precision (64..4096)
  Precision precision;                 // an analysis scalar
};

enum class AttractorKind {
  periodic,            // an isolated period-q orbit (q = 1: a fixed point)
  family,              // a family of period-q points (a multiplier 1: eq. 5), one attractor
  sticking,            // a sticking cycle: sticks to the wall, released at (1/2, 4), period k
  chaotic,             // a bounded aperiodic set with a positive exponent
  quasiperiodic,       // a bounded aperiodic set with exponent ~ 0
  effective_sticking,  // velocity-dependent chatter to the wall's velocity within precision
  accelerator,         // escape with growth: phases recur every Q steps while v grows
  escape,              // escape above the trapping top without an accelerator mode
  undecided,           // a recurrence the characterization could not name
};
const char* name(AttractorKind k);

struct AttractorPoint {
  Number theta, v;
};

struct FoundAttractor {
  int id = 0;                  // index in AttractorsResult::attractors (largest basin first)
  AttractorKind kind = AttractorKind::undecided;
  long period = 0;             // q (periodic, family), k (sticking), Q (accelerator), else 0
  std::vector<AttractorPoint> points;  // the orbit (periodic; sticking: from the release, at most 1000);
                                       // family: one member; aperiodic: a sample of <= 64 points
  // Periodic and family: the multipliers of the Newton orbit (Newton in the run's scalar):
  // re, im of each, larger modulus first.
  std::vector<std::pair<Number, Number>> multipliers;
  std::vector<double> multiplier_moduli;
  bool stable = false;          // |mu| < 1 (periodic), or the transverse one (family); sticking: true
  // Family: the range of theta of the members that starts reached (in double).
  double family_theta_min = 0, family_theta_max = 0;
  long family_members = 0;
  // Krawczyk (periodic, family, sticking, with AttractorsRequest::certify).
  std::optional<PeriodicCertificate> certificate;
  // Aperiodic sets: the leading exponent per collision and its standard error; steps
  // followed from the recurrence (recording + classification + exponent).
  double lambda = 0, lambda_stderr = 0;
  long lyapunov_steps = 0;
  long long followed_steps = 0;
  // Accelerator: the mean velocity gain per Q steps.
  double accel_gain = 0;
  std::string evidence;         // one line: what decided the kind
  long cells = 0;               // cells of the recurrence grid labelled with it
  long starts = 0;              // starts in its basin
  double fraction = 0, fraction_stderr = 0;  // of the starts in the phase space, binomial
  long first_start = -1;        // the first start (in start order) that found it
};

struct AttractorsResult {
  AttractorsRequest request;      // v_range filled in
  std::vector<Number> theta, v;   // per start (start i: grid column i mod nx, row i / nx)
  // Per start: attractor id, or kUndecidedStart (no decision in max_steps), or kOutside
  // (below the wall's velocity: not a state).
  std::vector<int> label;
  static constexpr int kUndecidedStart = -1, kOutside = -2;
  std::vector<FoundAttractor> attractors;
  long inside = 0, outside = 0, undecided = 0;
  double undecided_fraction = 0, undecided_stderr = 0;
  double cell_theta = 0, cell_v = 0;  // cell sizes of the recurrence grid
  double grid_v_lo = 0, grid_v_hi = 0;
  long candidates = 0;            // recurrences characterized (found again: matched)
  long long steps = 0;            // map steps taken by all starts
  double seconds = 0;             // wall time of the mapping (without certificates)
  double certify_seconds = 0;
};

// The velocity window of the starts: the request's own, or the trapping region.
std::pair<Decimal, Decimal> attractors_v_range(const AttractorsRequest& r);

// Throws InputError for a bad request (naming the field and the allowed range), Cancelled
// when the caller's cancellation flag is set (base/cancel.hpp). GridOptions: threads and
// progress (tiles are not used: the starts share what they found).
AttractorsResult find_attractors(const AttractorsRequest& r, const GridOptions& run = {});

// The binomial standard error of a share k/n: sqrt(p (1 - p) / n) (0 for n = 0).
double share_stderr(long k, long n);

// Global continuation (`attractors --vary a|eps|c`) builds on this call:
// run/attractors_sweep.hpp runs it at each value and chains the attractors by the distance
// of their point sets, and hands each periodic chain to continue (continue_chains there),
// tying its appearances and disappearances to its branch's (certified) events. Still to do:
// seeding a value's cells with the previous value's attractors, which would save most
// recurrences.

}  // namespace bouncer
