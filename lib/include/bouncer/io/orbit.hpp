// `bouncer orbit`: iterate the impact map from one or more initial conditions and stream
// the states with what happened at each step, as CSV, JSON or an aligned table, or (double
// only) as a NumPy .npy array of float64 with its provenance in a JSON file beside it.
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

enum class Format { csv, json, table, npy };

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

// Writes the provenance header, the rows and a final line per orbit (csv, json, table).
std::vector<OrbitOutcome> write_orbits(const OrbitRequest& r, const Provenance& p, std::ostream& out);

// --format npy (--precision double only; orbit_request refuses the others): the CSV's rows
// as a NumPy format 1.0 array of little-endian float64, shape (rows, columns), the columns
// of npy_orbit_columns() in the CSV's order. Numbers are the CSV's doubles bit for bit; a
// cell the CSV leaves empty is NaN; the text columns are codes (orbit_npy_sidecar names
// them). The provenance, the codes and each orbit's end go to the JSON file beside it.
const std::vector<std::string>& npy_orbit_columns();
// Rows when every orbit completes: the start row and each kept step, per orbit.
long long planned_orbit_rows(const OrbitRequest& r);
// The .npy preamble and header for (rows, cols), always 128 bytes (so that it can be
// rewritten in place when an orbit stops early and the row count changes).
std::string npy_header(long long rows, size_t cols);
struct NpyOrbits {
  std::vector<OrbitOutcome> outcomes;
  std::vector<long long> rows;  // rows of each orbit, in order
  long long total_rows = 0;
};
// Writes npy_header(header_rows, ...) and then the rows; the caller rewrites the header
// (rewrite_npy_header) when total_rows differs from header_rows.
NpyOrbits write_orbits_npy(const OrbitRequest& r, long long header_rows, std::ostream& out);
void rewrite_npy_header(int fd, const std::string& name, long long rows, size_t cols);
// The JSON beside PATH.npy: provenance, file name, dtype, shape, columns, codes, and each
// orbit's first row, row count and end (as the CSV's "# end:" lines).
std::string orbit_npy_sidecar(const OrbitRequest& r, const Provenance& p, const NpyOrbits& o, const std::string& npy_name);

}  // namespace bouncer
