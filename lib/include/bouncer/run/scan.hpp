// Parameter-space scans (`bouncer scan`, the paper's figs. paramspace1 and paramspace2): over
// a p x q grid of (a, eps) (constant model) or (a, c) (velocity-dependent model), k x k starts
// per parameter point (paper: 10 x 10, in the trapping region) are classified and the classes
// counted; certified (`scan --certify`), each parameter point gets the certificate of one
// exact start at the exact double (a, eps) or (a, c), with double's class beside it.
//
//     ScanRequest r;  r.model = ...;  r.a_lo = ...;  r.y_lo = ...;
//     const ScanResult s = scan(r);
//     s.cells[i].count[OrbitClass::chaotic]: how many of the k x k starts at point i are chaotic
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bouncer/model/spec.hpp"
#include "bouncer/run/cells.hpp"
#include "bouncer/scalar/precision.hpp"

namespace bouncer {

struct ScanRequest {
  ModelSpec model;  // a and the scanned parameter are set to each grid point
  // The scanned axes: a, and eps (constant model) or c (velocity-dependent model).
  Decimal a_lo, a_hi, y_lo, y_hi;
  long p = 20, q = 20;  // parameter points, 1..4096 each
  long k = 10;          // k x k starts per point, 1..1000
  Decimal theta_lo = Decimal::from_int(0), theta_hi = Decimal::from_int(1);
  // The starting velocities; none: the trapping region of each point (model/trapping.hpp).
  std::optional<std::pair<Decimal, Decimal>> v_range;
  // Re-checks by recurrence by default (`scan --recheck`; analysis/classify.hpp RecheckRule).
  ClassifyOptions classify{.recheck = RecheckRule::recurrence};
  Precision precision;  // an analysis scalar; certified: double, the twin run
  // certified_scan only: the certified start (exact) and the certificate's schedule.
  InitialCondition start{Decimal::from_int(0), Decimal::from_int(0)};
  // certified_scan only: start at a smooth wall's release state instead of `start` (its theta_r
  // is irrational: verify/certified_point.hpp, certify_release_point).
  bool start_at_release = false;
  CertifyPointOptions cert;
  // scan only: the starts of a sample of parameter points classified again at higher
  // precision (run/cells.hpp; the lattice is over the p x q points, each with its k x k starts).
  GridConfirm confirm;
};

// The scanned parameter: eps (constant model) or c (velocity-dependent); InputError("model")
// for the elastic model.
Parameter scan_parameter(const ModelSpec& m);

// The classes a scan counts, in the order of its CSV columns (the classifier's, then outside).
const std::vector<OrbitClass>& scan_classes();

struct ScanCell {
  std::array<long, kOrbitClassCount> count{};  // starts of each class
  long operator[](OrbitClass c) const { return count[static_cast<size_t>(c)]; }
  long total() const;
  long in_phase_space() const { return total() - (*this)[OrbitClass::outside]; }
  // --confirm, at a parameter point of the sample: its starts inside the phase space counted by
  // verdict (PrecisionVerdict: agrees, artefact, precision_dependent), and the artefacts' start
  // indices j (theta index j mod k, v index j / k: ScanGrid::start).
  bool confirmed = false;
  std::array<long, 3> verdicts{};
  std::vector<long> artefacts;
  friend bool operator==(const ScanCell&, const ScanCell&) = default;
};
std::string encode(const ScanCell& c);
template <>
ScanCell decode_cell<ScanCell>(std::string_view text);

struct ScanResult {
  ScanRequest request;
  Parameter y = Parameter::eps;
  std::vector<Number> a, y_values;  // the p and q centres, in the run's scalar
  std::vector<ScanCell> cells;      // p * q: item i at a index i mod p, y index i / p
};
struct CertifiedScanResult {
  ScanRequest request;
  Parameter y = Parameter::eps;
  std::vector<Number> a, y_values;  // the exact double centres (digits: their exact decimals)
  std::vector<CertifiedCell> cells;
};

// One start of a scan point and its classification.
struct StartLabel {
  long j = 0;  // the start's index, 0 <= j < k * k (ScanGrid::start)
  Classification label;
};

// The grid of a scan request, cell by cell (any thread).
class ScanGrid {
 public:
  ScanGrid(const ScanRequest& r, bool certified);
  ~ScanGrid();
  ScanGrid(const ScanGrid&) = delete;
  ScanGrid& operator=(const ScanGrid&) = delete;
  const ScanRequest& request() const;
  Parameter y() const;
  GridPlan plan() const;
  std::string item(long i) const;
  ScanCell cell(long i) const;  // with --confirm, confirmed where point i is in the sample
  long confirm_stride() const;  // --confirm: the sample's lattice over the p x q points; else 1
  // Start j (0 <= j < k * k) of parameter point i, in the run's scalar: (theta, v).
  std::pair<Number, Number> start(long i, long j) const;
  // The classifications of point i's starts inside the phase space (what cell(i) counts), in
  // the order of j: for comparing runs start by start (bench_recheck compares the re-check rules).
  std::vector<StartLabel> labels(long i) const;
  CertifiedCell certified_cell(long i) const;
  ScanResult result(std::vector<ScanCell> cells) const;
  CertifiedScanResult certified_result(std::vector<CertifiedCell> cells) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

ScanResult scan(const ScanRequest& r, const GridOptions& run = {});
CertifiedScanResult certified_scan(const ScanRequest& r, const GridOptions& run = {});

}  // namespace bouncer
