// Bifurcation diagrams (`bouncer bifurcation`, paper sec. IV.B): sweep one parameter (a, eps
// or c) over `samples` values p_k = lo + (hi - lo) k/(K - 1); at each, follow the orbit of
// one start for `transient` steps and record the next `record` (paper: 5000 and 500). Each
// value is one column, computed on its own (or, with `carry`, from the last state of the
// previous value, in order). Certified (`bifurcation --certify`), each column also gets the
// certificate of the exact orbit at the exact double value of the parameter and double's
// class of the same orbit.
//
//     BifurcationRequest r;  r.model = ...;  r.vary = Parameter::a;  r.lo = ...;  r.hi = ...;
//     for (const BifurcationColumn& c : bifurcation(r).columns) ... c.points[j].theta.value
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bouncer/model/spec.hpp"
#include "bouncer/run/cells.hpp"
#include "bouncer/scalar/precision.hpp"

namespace bouncer {

struct BifurcationRequest {
  ModelSpec model;  // the varied parameter is set to each value
  Parameter vary = Parameter::a;
  Decimal lo, hi;  // both ends included; lo < hi
  long samples = 200;                 // 1..100000
  long transient = 5000, record = 500;  // record >= 1; samples x record <= 5e7
  InitialCondition start{Decimal::from_int(0), Decimal::from_int(0)};
  bool carry = false;  // start each value from the last state of the previous one
  Precision precision;  // an analysis scalar; certified: double
  bool certify = false;
  CertifyPointOptions cert;  // certify: the schedule (max_steps = transient + record)
};

struct BifurcationPoint {
  long n = 0;  // the step (1-based, counting the transient)
  Number theta, v;
  bool sticking = false;  // this step was a sticking (ends at the release)
};

struct BifurcationColumn {
  Number value;  // the parameter p_k in the run's scalar
  std::vector<BifurcationPoint> points;
  // A step the scalar could not decide stops the column there: its step and why.
  std::optional<long> undecided_step;
  std::string undecided_reason;
  // certify: the exact parameter (the double p_k as an exact decimal) and its certificate.
  std::optional<std::string> exact_value;
  std::optional<CertifiedCell> certified;
};
std::string encode(const BifurcationColumn& c);
template <>
BifurcationColumn decode_cell<BifurcationColumn>(std::string_view text);

struct BifurcationResult {
  BifurcationRequest request;
  std::vector<BifurcationColumn> columns;  // samples
};

// The sweep of a request, column by column: any thread, except with `carry` (one worker, in
// order: column(k) continues from column(k - 1)'s last state).
class BifurcationGrid {
 public:
  explicit BifurcationGrid(const BifurcationRequest& r);
  ~BifurcationGrid();
  BifurcationGrid(const BifurcationGrid&) = delete;
  BifurcationGrid& operator=(const BifurcationGrid&) = delete;
  const BifurcationRequest& request() const;
  GridPlan plan() const;  // carry: one tile
  std::string item(long k);
  BifurcationColumn column(long k);
  // About how many bytes one column's tile text takes (the grid's memory estimate).
  double item_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

BifurcationResult bifurcation(const BifurcationRequest& r, const GridOptions& run = {});

}  // namespace bouncer
