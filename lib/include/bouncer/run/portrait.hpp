// Phase portraits (`bouncer portrait`, the paper's fig. fermi19): the orbits (theta_n, v_n)
// of several starts in the request's scalar type, each after `transient` steps for the next
// `steps` (with the start itself as point 0 when there is no transient). Each start is one
// grid item, computed on its own; a step the scalar cannot decide stops that orbit there.
//
//     PortraitRequest r;  r.model = ...;  r.starts = {{theta0, v0}, ...};  r.steps = 1000;
//     for (const PortraitOrbit& o : portrait(r).orbits) ... o.points[j].theta.value
//
// The command line runs the same PortraitGrid through its tile files (resume, shards, mpirun);
// its pictures are io/curve_figures.hpp.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/run/cells.hpp"
#include "bouncer/run/grid.hpp"
#include "bouncer/scalar/number.hpp"
#include "bouncer/scalar/precision.hpp"

namespace bouncer {

struct PortraitRequest {
  ModelSpec model;
  std::vector<InitialCondition> starts;  // 1..1000, each valid for the model
  long steps = 1000;                     // points per orbit, 1..1e7; starts x steps <= 2e7
  long transient = 0;                    // steps discarded first, 0..1e8
  Precision precision;                   // an analysis scalar (interval precisions are refused)
};

struct PortraitPoint {
  long n = 0;  // the step (0: the start)
  Number theta, v;
  std::optional<EventKind> event;  // how the step ended; none for the start
};

// The orbit of one start: its points, and where a step could not be decided (the orbit
// stops there).
struct PortraitOrbit {
  std::vector<PortraitPoint> points;
  std::optional<long> undecided_step;
  std::string undecided_reason;
};
// The tile text of an orbit (one record a line: "S n,theta,v,event" per point, "U step
// reason" when undecided) and back; decode throws std::runtime_error on a text no encode made.
std::string encode(const PortraitOrbit& o);
template <>
PortraitOrbit decode_cell<PortraitOrbit>(std::string_view text);

struct PortraitResult {
  PortraitRequest request;
  std::vector<PortraitOrbit> orbits;  // one per start, in order
};

// The orbits of a request, one item per start (any thread).
class PortraitGrid {
 public:
  explicit PortraitGrid(const PortraitRequest& r);  // validates r (InputError naming the option)
  ~PortraitGrid();
  PortraitGrid(const PortraitGrid&) = delete;
  PortraitGrid& operator=(const PortraitGrid&) = delete;
  const PortraitRequest& request() const;
  GridPlan plan() const;  // one start per tile
  std::string item(long k) const;  // encode(orbit(k))
  PortraitOrbit orbit(long k) const;
  // About how many bytes one orbit's tile text takes (the grid's memory estimate).
  double item_bytes() const;
  PortraitResult result(std::vector<PortraitOrbit> orbits) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The library call: every orbit computed in this process (GridOptions: threads, progress).
// Throws InputError for a bad request, Cancelled when the caller's flag is set (base/cancel.hpp).
PortraitResult portrait(const PortraitRequest& r, const GridOptions& run = {});

}  // namespace bouncer
