// The orbit driver: one loop that follows an orbit of the impact map and hands each kept
// step to a sink as a typed row (the StepResult of the step), for every scalar type. It is
// the loop of `bouncer orbit` (whose sink writes CSV, JSON or a table: io/orbit.cpp) and of
// bouncer.Model.orbit (whose sink fills numpy columns: python/module.cpp), so that the two
// follow the same steps: the same Lohner or box step, the same stop at an undecided step,
// the same phase-loss count, and Ctrl-C (base/cancel.hpp) checked every 256 steps.
#pragma once

#include <string>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/verify/enclosure.hpp"

namespace bouncer {

// How one orbit ended.
struct OrbitOutcome {
  long long steps_done = 0;      // steps completed (rows n = 1..steps_done exist)
  bool undecided = false;        // stopped early at step steps_done + 1
  std::string reason;            // why, when undecided
  long long phase_lost_at = -1;  // first step after which theta had no correct bit, or -1
  long long fallbacks = -1;      // lohner: steps that used the naive box image; -1 otherwise
};

// Which steps, and how an interval orbit is stepped.
struct OrbitSteps {
  long long steps = 10;  // steps to take (0: the start row only)
  long long every = 1;   // keep steps n with n % every == 0, and the last one
  // Interval types only: naive steps the box with ImpactMap<T>; lohner follows Lohner's set
  // c + B r (OrbitEnclosureOf) and each kept row's state is the box around it (tighter than
  // the box image), with the event fields of the interval step over the box before the step.
  // Ignored for point types.
  EnclosureMethod method = EnclosureMethod::naive;
};

// The wall's direction at a step's last contact, an orbit row's `wall` (stuck = true: at the
// collision that stuck, the `sticking` column's): +1 up, -1 down, 0 flat; its segment's, or on
// the smooth wall the sign of the wall's velocity there (of an interval's midpoint). Every
// sink (the CSV, JSON, table and npy writers, Python's Step and Orbit) takes it from here.
template <class T>
int contact_direction(const Model<T>& m, const StepResult<T>& r, bool stuck = false) {
  if (!m.wall.smooth()) return m.wall.direction[static_cast<size_t>(stuck ? r.stick_segment : r.segment)];
  const double u = ScalarTraits<T>::to_double(m.wall.velocity_at(stuck ? r.stuck_theta : r.next.theta));
  return u > 0 ? 1 : u < 0 ? -1 : 0;
}
// Its name in text: up, down or flat.
inline const char* direction_name(int d) { return d > 0 ? "up" : d < 0 ? "down" : "flat"; }

// The numeric codes of a row's text columns, in the npy format (its sidecar lists them) and
// Python's Orbit (bouncer.EVENTS): event 0 for the start row, 1 + EventKind for a step
// (impact, sticking, ride); flight 1 indirect, 0 direct, -1 undecided.
inline constexpr int kStartEventCode = 0;
inline int event_code(EventKind k) { return 1 + static_cast<int>(k); }
inline int flight_code(Truth indirect) { return indirect == Truth::yes ? 1 : indirect == Truth::no ? 0 : -1; }

// Receives the rows of one orbit, in order: start once, then row for each kept step.
template <class T>
class OrbitSink {
 public:
  virtual ~OrbitSink() = default;
  virtual void start(const State<T>& s) = 0;                  // row n = 0
  virtual void row(long long n, const StepResult<T>& r) = 0;  // a kept step n >= 1
  // Called every 4096 steps: a sink may throw here to end a run it cannot use (a stream
  // that failed), instead of after 1e10 rows.
  virtual void check() {}
};

// Follows the orbit from `start` (make_state: knots recognised) for how.steps steps. An
// Undecided step ends it (outcome.undecided, reason); Cancelled and what the sink throws
// propagate.
template <class T>
OrbitOutcome follow_orbit(const ImpactMap<T>& map, const State<T>& start, const OrbitSteps& how, OrbitSink<T>& sink);

}  // namespace bouncer
