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
  // --confirm, for a start of the sample inside the phase space: the verdict of the check at
  // higher precision (analysis/classify.hpp check_precision) and the class and period at its
  // first precision (mpfr:B). None: not confirmed.
  std::optional<PrecisionVerdict> confirm;
  OrbitClass check_cls = OrbitClass::undecided;
  long check_period = 0;
  // What differs between the run's class and the check's (analysis/classify.hpp
  // behaviour_difference), "" where they agree: it says why an artefact whose classes and
  // periods read the same (an accelerator mode of another period) is one.
  std::string differs_in;
  friend bool operator==(const AttractorCell&, const AttractorCell&) = default;
};
// A cell with its class and period and no --confirm verdict.
inline AttractorCell attractor_cell(OrbitClass cls, long period) {
  AttractorCell c;
  c.cls = cls;
  c.period = period;
  return c;
}

// --confirm of a grid of starts (basin, scan): the starts of a sample classified again at
// mpfr:B, B = max(bits, 2 x the run's bits), and at mpfr:2B when they differ, as a single-point
// classify does (classify_checked). The sample is a lattice of the grid's units (starts of a
// basin; parameter points of a scan, each with all its starts): every `stride`-th unit in x and
// in y, the one at offset (min(stride, n) - 1) / 2 of each block, so it depends on the grid alone.
struct GridConfirm {
  bool on = false;
  long bits = 256;  // 64..kMaxBits
  long sample = 0;  // at most this many starts (0: every start); at least one unit is confirmed
};
// InputError "confirm" (bits outside [64, kMaxBits]) or "confirm-sample" (negative).
void check_confirm(const GridConfirm& c);
// The smallest stride whose lattice over ux x uy units of per_unit starts holds at most
// `sample` starts (1 for sample 0; at most max(ux, uy): a single unit).
long confirm_stride(long ux, long uy, long per_unit, long sample);
// Whether unit (x, y) of an ux x uy grid is in the lattice of `stride`; how many units are.
bool in_confirm_sample(long x, long y, long ux, long uy, long stride);
long confirm_sample_units(long ux, long uy, long stride);
// The confirmation of a start: its class, and check.verdict with the first check's class.
AttractorCell confirmed_cell(const CheckedClassification& check);

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
// The same with items computed in groups of at most `group` (run_grid's grouped form).
std::vector<std::string> run_in_memory(const GridPlan& plan, long group,
                                       const std::function<void(long, long, std::string*)>& items, const GridOptions& run);

}  // namespace bouncer
