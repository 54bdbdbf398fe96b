// Real-time trajectories (the paper's fig. realtime, `bouncer trajectory`): the particle's
// height and the wall's against absolute time t, from a state (theta, v) of the impact map,
// over a few wall periods.
//
// The time axis is absolute time t with t = theta_0 at the start state, so the wall is
// f(t mod 1). The map gives each step's start state (theta_n, v_n: on the wall, v_n the
// particle's own velocity, not relative to the wall) and its duration tau. Between them the
// particle is drawn exactly:
//   * a flight (event flight, then impact): the parabola y = f(theta_n) + v_n s - (a/2) s^2,
//     s = t - t_n, up to the impact at t_n + tau;
//   * a ride (event ride): on the wall until t_n + tau;
//   * a sticking step: the flight to the collision where it stuck, then the chatter
//     (bounces of relative launch speed w_k, w_{k+1} the collision law's rebound of w_k, each
//     2 w_k / a long in the wall's frame) until the collapse, then the ride on the wall to
//     the release at t_n + tau (README "Sticking"). The collapses and the ride are the map's
//     own walk (ImpactMap::after_sticking), the bounces its collision law (ImpactMap::rebound).
// Every number is in the point type T. Implemented in lib/src/analysis/trajectory.cpp.
#pragma once

#include <string>
#include <vector>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/scalar/precision.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

struct TrajectoryRequest {
  ModelSpec model;
  InitialCondition start;  // theta_0, v_0 (validated against the model)
  long periods = 3;        // wall periods traced, from t = theta_0
  long samples = 400;      // grid points per period (t_0 + k / samples), besides the events
  Precision precision;     // a point precision; the map is built at its bits
};

enum class TraceEvent : unsigned char { start, flight, impact, chatter, stuck, release, ride };
const char* name(TraceEvent e);

template <class T>
struct TracePoint {
  T t;          // absolute time
  T particle;   // the particle's height
  T wall;       // the wall's height f(t mod 1)
  TraceEvent event = TraceEvent::flight;
  long step = 0;  // the map step being drawn (0: the start)
};

template <class T>
struct Trajectory {
  // By increasing t within each step: the grid times inside the window, the wall's
  // corners, and every impact, collapse and release exactly.
  std::vector<TracePoint<T>> points;
  long steps = 0;           // map steps begun
  long impacts = 0;         // flights ending in an impact within the window
  long sticking_steps = 0;  // steps that stuck
  std::string stopped;      // why the trace stopped before the window's end (empty: it did not)
};

// The trajectory of r.start under `map` (whose model is r.model at r.precision.bits).
template <class T>
Trajectory<T> trace_trajectory(const TrajectoryRequest& r, const ImpactMap<T>& map);
// The same, building the map from the request.
template <class T>
Trajectory<T> trace_trajectory(const TrajectoryRequest& r);

// Instantiated in lib/src/analysis/trajectory.cpp for the analysis scalars (scalar/scalar_set.hpp).
#define BOUNCER_X(T, kind)                                                                          \
  extern template Trajectory<T> trace_trajectory<T>(const TrajectoryRequest&, const ImpactMap<T>&); \
  extern template Trajectory<T> trace_trajectory<T>(const TrajectoryRequest&);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
