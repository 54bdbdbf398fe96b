// Basins of attraction (`bouncer basin`, the paper's figs. basin1 and basin2): every point of
// an nx x ny grid of starts (cell centres of the theta and v windows) classified by
// bouncer::classify in the request's scalar type, or, certified (`basin --certify`), by
// certify_point for the exact start with double's class beside it.
//
//     BasinRequest r;  r.model = ...;  r.nx = r.ny = 100;
//     const BasinResult b = basin(r);          // all cores, in memory
//     b.cells[i]: class and period of item i (column i mod nx, row i / nx from the bottom)
//
// The command line runs the same BasinGrid through its tile files (resume, shards, mpirun).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/run/cells.hpp"
#include "bouncer/run/grid.hpp"
#include "bouncer/scalar/number.hpp"
#include "bouncer/scalar/precision.hpp"
#include "bouncer/verify/certified_point.hpp"

namespace bouncer {

struct BasinRequest {
  ModelSpec model;
  long nx = 100, ny = 100;  // 1..8192 each
  Decimal theta_lo = Decimal::from_int(0), theta_hi = Decimal::from_int(1);  // within [0, 1]
  // The starting velocities; none: the trapping region (model/trapping.hpp), which the
  // elastic model and eps = 1 do not have (InputError "v-range").
  std::optional<std::pair<Decimal, Decimal>> v_range;
  ClassifyOptions classify;
  Precision precision;  // an analysis scalar; certified: double, the twin run
  // certified_basin only: the certificate's schedule (max_steps, max_bits, attractor period).
  CertifyPointOptions cert;
  // basin only: the starts of a sample classified again at higher precision (run/cells.hpp).
  GridConfirm confirm;
};

// The velocity window a request means: its own, or the trapping region.
std::pair<Decimal, Decimal> basin_v_range(const BasinRequest& r);

struct BasinResult {
  BasinRequest request;         // v_range filled in
  std::vector<Number> theta, v;  // the nx column and ny row centres, in the run's scalar
  std::vector<AttractorCell> cells;  // nx * ny: item i at column i mod nx, row i / nx
};
struct CertifiedBasinResult {
  BasinRequest request;
  std::vector<Number> theta, v;  // in double (the exact starts are these dyadic numbers)
  std::vector<CertifiedCell> cells;
};

// The grid of a basin request, cell by cell (any thread): what the library call and the
// command line's tiled runs compute. `certified` selects certified cells.
class BasinGrid {
 public:
  BasinGrid(const BasinRequest& r, bool certified);
  ~BasinGrid();
  BasinGrid(const BasinGrid&) = delete;
  BasinGrid& operator=(const BasinGrid&) = delete;
  const BasinRequest& request() const;
  GridPlan plan() const;          // nx * ny items in tiles
  std::string item(long i) const;  // encode(cell i)
  // Items computed in groups (run_grid's grouped form): item(i) for i in [begin, end), the
  // cells outside the --confirm sample classified side by side (classify_many: in double,
  // the batched step), the same texts as item(i) one by one. group(): at most how many.
  long group() const;
  void items(long begin, long end, std::string* out) const;
  AttractorCell cell(long i) const;  // with --confirm, confirmed where i is in the sample
  long confirm_stride() const;       // --confirm: the sample's lattice (run/cells.hpp); else 1
  CertifiedCell certified_cell(long i) const;
  BasinResult result(std::vector<AttractorCell> cells) const;
  CertifiedBasinResult certified_result(std::vector<CertifiedCell> cells) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The library calls: every cell computed in this process (GridOptions: threads, progress;
// no tile directory is needed). Throws InputError for a bad request, Cancelled when the
// caller's cancellation flag is set (base/cancel.hpp).
BasinResult basin(const BasinRequest& r, const GridOptions& run = {});
CertifiedBasinResult certified_basin(const BasinRequest& r, const GridOptions& run = {});

}  // namespace bouncer
