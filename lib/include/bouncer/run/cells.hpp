// The cells of the point grids (run/basin.hpp, run/scan.hpp) and what they share: the grid
// geometry (cell centres in the run's scalar), the tile plan, the in-memory run, and the
// cells' tile texts.
#pragma once

#include <optional>
#include <utility>

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/run/grid.hpp"
#include "bouncer/scalar/number.hpp"
#include "bouncer/verify/certified_point.hpp"

namespace bouncer {

// One start's answer: its class and period (OrbitClass::outside: below the wall's velocity).
struct AttractorCell {
  OrbitClass cls = OrbitClass::undecided;
  long period = 0;
  friend bool operator==(const AttractorCell&, const AttractorCell&) = default;
};

// One start's certified answer with double's answer of the same start beside it.
struct CertifiedCell {
  CertifiedClass cls = CertifiedClass::undecided;
  long period = 0;
  long long certified_steps = 0;
  std::string scalar;  // the tier that decided it ("interval:double", "mpfi:128"; "" if none)
  OrbitClass double_class = OrbitClass::undecided;
  long double_period = 0;
  Agreement agreement = Agreement::undecided;
  friend bool operator==(const CertifiedCell&, const CertifiedCell&) = default;
  static CertifiedCell outside() {
    return {CertifiedClass::outside, 0, 0, "", OrbitClass::outside, 0, Agreement::outside};
  }
};

// Tile texts of the cells (run/grid.hpp keeps tiles as text): encode, and decode, which
// throws std::runtime_error on a text no encode made (tiles are checksummed: a damaged one
// never gets here).
std::string encode(const AttractorCell& c);
std::string encode(const CertifiedCell& c);
template <class Cell>
Cell decode_cell(std::string_view text);
template <>
AttractorCell decode_cell<AttractorCell>(std::string_view text);
template <>
CertifiedCell decode_cell<CertifiedCell>(std::string_view text);
template <class Cell>
std::vector<Cell> decode_cells(const std::vector<std::string>& items) {
  std::vector<Cell> cells;
  cells.reserve(items.size());
  for (const std::string& t : items) cells.push_back(decode_cell<Cell>(t));
  return cells;
}

// A certified cell from a start's certificate and double's classification of the same start.
CertifiedCell certified_with_twin(const CertifiedPoint& c, const Classification& twin);

// Points of a grid over [lo, hi]: cell centres lo + (hi - lo)(2i + 1)/(2n), in T.
template <class T>
T cell_centre(const T& lo, const T& hi, long i, long n) {
  return lo + (hi - lo) * (2 * i + 1) / (2 * n);
}

// The n values at(0), ..., at(n - 1) of an axis as Numbers.
template <class F>
std::vector<Number> axis(long n, F&& at) {
  std::vector<Number> out;
  out.reserve(static_cast<size_t>(n));
  for (long k = 0; k < n; ++k) out.push_back(number_of(at(k)));
  return out;
}

// A parameter swept over [lo, hi] (bifurcation, exponent curves): eps varies only with
// constant restitution and c only with the velocity-dependent law (InputError "vary"), lo < hi,
// and both ends give a valid model (InputError "range").
void check_varied_range(const ModelSpec& m, Parameter vary, const Decimal& lo, const Decimal& hi);

// The velocities of a grid of starts (basin, attractors): the range given, else the
// trapping region's (model/trapping.hpp). InputError("v-range") where there is none.
std::pair<Decimal, Decimal> starts_v_range(const ModelSpec& m, const std::optional<std::pair<Decimal, Decimal>>& given);

// The tiles of a point grid of `items` cells: about items/64 each, at most max_tile.
GridPlan point_grid_plan(long items, long max_tile);

// Runs a plan in this process (threads and progress from `run`, no tile directory) and
// returns every item's text; rethrows what an item threw (Cancelled, InputError, ...).
std::vector<std::string> run_in_memory(const GridPlan& plan, const std::function<std::string(long)>& item,
                                       const GridOptions& run);

}  // namespace bouncer
