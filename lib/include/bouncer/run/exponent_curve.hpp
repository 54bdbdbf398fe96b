// Exponent curves (`bouncer lyapunov --vary`, the paper's fig. lyapunov_one): the leading
// Lyapunov exponent against one parameter (a, eps or c) at `samples` values
// p_k = lo + (hi - lo) k/(K - 1), in the request's scalar type. At each value, for each of the
// same `ics` starts, the measurement of the single-point `lyapunov()` (analysis/lyapunov.hpp:
// the same function on the model at p_k, so a value's exponent is bit for bit the
// single-point one at that value and start), and the class of that orbit by `classify()`
// where the exponent's window ended. Each value is one grid item, computed on its own.
//
//     ExponentCurveRequest r;  r.model = ...;  r.vary = Parameter::a;  r.lo = ...;  r.hi = ...;
//     for (const ExponentColumn& c : exponent_curve(r).columns) ... c.rows[j].lambda
//
// The command line runs the same ExponentCurveGrid through its tile files; its picture is
// io/curve_figures.hpp.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/run/cells.hpp"
#include "bouncer/run/grid.hpp"
#include "bouncer/scalar/number.hpp"
#include "bouncer/scalar/precision.hpp"

namespace bouncer {

struct ExponentCurveRequest {
  ModelSpec model;  // the varied parameter is set to each value
  Parameter vary = Parameter::a;  // eps only with the constant law, c only with veldep
  Decimal lo, hi;                 // both ends included and in the model's range; lo < hi
  long samples = 100;             // 1..100000
  long ics = 1;                   // starts per value, 1..1000 (exponent_curve_starts)
  // The first start; none: theta = 0.1, v = the wall's fastest upward velocity + 2 (rounded up).
  std::optional<InitialCondition> start;
  LyapunovOptions lyapunov;  // transient 0..1e9, steps 1..1e9, blocks 1..10000
  // The class where the exponent's window ended: no further transient, the classifier's
  // window (steps 500, max_period, recheck_factor).
  ClassifyOptions classify{.transient = 0};
  Precision precision;  // an analysis scalar
};

// The starts of a request, the same at every value: its start (or the default) first, then
// ics - 1 points of the R2 low-discrepancy sequence (Roberts 2018: x_j = frac(1/2 + j (1/g,
// 1/g^2)), g the plastic number) mapped to theta in (0, 1) and v in (v_wall, v_top], rounded
// to 6 and 4 decimals so that each is an exact decimal. v_wall is the wall's fastest upward
// velocity; v_top the top of the trapping region (model/trapping.hpp) at the range's end
// where it is lowest, so the starts lie in the trapping region of every value; the elastic
// map has none: v_top = v_wall + a/2 (a the least of the range). Each start is validated
// (InputError "theta"/"v").
std::vector<InitialCondition> exponent_curve_starts(const ExponentCurveRequest& r);

// One start at one value: the exponent per collision and its standard error (lambda -inf:
// a sticking step contracted the window; NaN: a step was undecided), and the orbit's class
// and period where the window ended (undecided, 0 when the exponent's run was undecided).
struct ExponentRow {
  double lambda = 0, stderr_ = 0;
  OrbitClass cls = OrbitClass::undecided;
  long period = 0;
};

struct ExponentColumn {
  Number value;                   // the parameter p_k in the run's scalar
  std::vector<ExponentRow> rows;  // one per start, in the order of the starts
  // Over the starts: the largest exponent (NaN rows skipped; -inf if none), and the mean
  // (NaN when any row is NaN).
  double max_lambda() const;
  double mean_lambda() const;
};
// The tile text of a column ("P digits", then "R lambda,stderr,class,period" per start) and
// back; decode throws std::runtime_error on a text no encode made.
std::string encode(const ExponentColumn& c);
template <>
ExponentColumn decode_cell<ExponentColumn>(std::string_view text);

// An exponent as the outputs print it: round-trip digits of the double, or nan, inf, -inf.
std::string exponent_text(double x);

struct ExponentCurveResult {
  ExponentCurveRequest request;
  std::vector<InitialCondition> starts;  // exponent_curve_starts(request)
  std::vector<ExponentColumn> columns;   // samples
};

// The curve of a request, value by value (any thread).
class ExponentCurveGrid {
 public:
  explicit ExponentCurveGrid(const ExponentCurveRequest& r);  // validates r, computes the starts
  ~ExponentCurveGrid();
  ExponentCurveGrid(const ExponentCurveGrid&) = delete;
  ExponentCurveGrid& operator=(const ExponentCurveGrid&) = delete;
  const ExponentCurveRequest& request() const;
  const std::vector<InitialCondition>& starts() const;
  GridPlan plan() const;
  std::string item(long k) const;  // encode(column(k))
  ExponentColumn column(long k) const;
  // About how many bytes one column's tile text takes (the grid's memory estimate).
  double item_bytes() const;
  ExponentCurveResult result(std::vector<ExponentColumn> columns) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The library call: every value computed in this process (GridOptions: threads, progress).
// Throws InputError for a bad request, Cancelled when the caller's flag is set (base/cancel.hpp).
ExponentCurveResult exponent_curve(const ExponentCurveRequest& r, const GridOptions& run = {});

}  // namespace bouncer
