// `bouncer orbit`: iterate the impact map from one or more initial conditions and stream
// the states with what happened at each step, as CSV, JSON or an aligned table.
// Memory is constant in the number of steps. The loop is the orbit driver's
// (run/orbit.hpp follow_orbit); this file is its request and its text sink.
#pragma once

#include <iosfwd>
#include <set>
#include <string>
#include <vector>

#include "bouncer/io/provenance.hpp"
#include "bouncer/io/scene.hpp"
#include "bouncer/run/orbit.hpp"

namespace bouncer {

enum class Format { csv, json, table };

struct OrbitRequest {
  ModelSpec model;
  std::vector<InitialCondition> initial;
  long long steps = 10;
  long long every = 1;
  Precision precision;
  Format format = Format::csv;
  // Interval runs only: naive iterates the interval box with ImpactMap<Mpfi>; lohner
  // (the default for interval runs, as in the certified commands) follows Lohner's set
  // c + B r (verify/enclosure.hpp) and prints the box around it.
  EnclosureMethod method = EnclosureMethod::naive;
};

const std::set<std::string>& orbit_keys();
// All validation of an orbit scene; throws InputError naming the option.
OrbitRequest orbit_request(const Options& o);

// The driver's settings of the request (run/orbit.hpp).
inline OrbitSteps orbit_steps(const OrbitRequest& r) { return {r.steps, r.every, r.method}; }

// Writes the provenance header, the rows and a final line per orbit.
std::vector<OrbitOutcome> write_orbits(const OrbitRequest& r, const Provenance& p, std::ostream& out);

}  // namespace bouncer
