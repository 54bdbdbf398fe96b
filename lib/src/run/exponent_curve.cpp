// Exponent curves (run/exponent_curve.hpp).
#include "bouncer/run/exponent_curve.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/trapping.hpp"

namespace bouncer {

namespace {

std::string integer_range(long long lo, long long hi) {
  return "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

void check_curve(const ExponentCurveRequest& r) {
  check_varied_range(r.model, r.vary, r.lo, r.hi);
  if (r.samples < 1 || r.samples > 100000) throw InputError("samples", integer_range(1, 100000));
  if (r.ics < 1 || r.ics > 1000) throw InputError("ics", integer_range(1, 1000));
  if (r.lyapunov.transient < 0 || r.lyapunov.transient > 1000000000L) throw InputError("transient", integer_range(0, 1000000000L));
  if (r.lyapunov.steps < 1 || r.lyapunov.steps > 1000000000L) throw InputError("steps", integer_range(1, 1000000000L));
  if (r.lyapunov.blocks < 1 || r.lyapunov.blocks > 10000) throw InputError("blocks", integer_range(1, 10000));
  if (r.classify.steps < 8) throw InputError("steps", "the classifier's window must be at least 8 steps");
  if (r.classify.max_period < 1 || r.classify.max_period * 2 > r.classify.steps)
    throw InputError("max-period", "must be in [1, steps/2] (" + std::to_string(r.classify.steps / 2) + ")");
  if (r.classify.recheck_factor < 0 || r.classify.recheck_factor > 1000) throw InputError("recheck-factor", integer_range(0, 1000));
  if (!r.precision.is_analysis())
    throw InputError("precision", "interval precision is not supported here (use " +
                                      precision_names<AnalysisScalars>(" or ") + ")");
  if (r.start) validate(r.model, *r.start, "theta", "v");
}

// Fraction of x in [0, 1).
double frac(double x) { return x - std::floor(x); }

std::string fixed_text(double x, int decimals) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(decimals) << x;
  return os.str();
}

struct CurveBase {
  virtual ~CurveBase() = default;
  virtual ExponentColumn column(long k) const = 0;
};

template <class T>
struct Curve final : CurveBase {
  using Tr = ScalarTraits<T>;
  const ExponentCurveRequest& r;
  const std::vector<InitialCondition>& starts;
  Model<T> base;
  T lo, hi;

  Curve(const ExponentCurveRequest& req, const std::vector<InitialCondition>& s)
      : r(req), starts(s), base(make_model<T>(req.model, req.precision.bits)),
        lo(Tr::from_decimal(req.lo.text(), req.precision.bits)), hi(Tr::from_decimal(req.hi.text(), req.precision.bits)) {}

  T param(long k) const { return r.samples == 1 ? lo : T(lo + (hi - lo) * k / (r.samples - 1)); }

  ExponentColumn column(long k) const override {
    const T p = param(k);
    // The model at p, exactly as make_model builds it from the decimal that prints p.
    const Model<T> m = with_parameter(base, r.vary, p);
    const ImpactMap<T> map(m);
    ExponentColumn col;
    col.value = number_of(p);
    col.rows.reserve(starts.size());
    for (const InitialCondition& ic : starts) {
      State<T> end = make_state<T>(ic, r.precision.bits);
      const LyapunovResult lr = lyapunov(m, end, r.lyapunov, &end);
      ExponentRow row{lr.lambda, lr.stderr_, OrbitClass::undecided, 0};
      if (!lr.undecided) {
        // The same orbit, classified where its measured window ended (a contracted run
        // stopped at a sticking step: the classifier finds the sticking period from there).
        const Classification c = classify<T>(map, end, r.classify);
        row.cls = c.cls;
        row.period = c.period;
      }
      col.rows.push_back(row);
    }
    return col;
  }
};

[[noreturn]] void bad_column(std::string_view text) {
  throw std::runtime_error("a grid tile holds an exponent column no bouncer wrote: '" + std::string(text.substr(0, 80)) + "'");
}

}  // namespace

std::vector<InitialCondition> exponent_curve_starts(const ExponentCurveRequest& r) {
  const Model<double> m = make_model<double>(r.model, 53);
  const double v_wall = wall_up_speed(m.wall);
  std::vector<InitialCondition> out;
  if (r.start) {
    out.push_back(*r.start);
  } else {
    // theta = 0.1 and v two above the wall's fastest upward velocity (6 on the triangle,
    // inside the trapping region of constant eps >= 1/7 and of veldep c >= 1).
    InitialCondition ic{parse_decimal("theta", "0.1"), Decimal::from_int(static_cast<long>(std::ceil(v_wall)) + 2)};
    validate(r.model, ic, "theta", "v");
    out.push_back(ic);
  }
  // The model at the range's end where the trapping region is lowest (a: the top does not
  // depend on a; eps and c: the lower end).
  const double lo = r.lo.approx();
  const double a = r.vary == Parameter::a ? lo : r.model.a.approx();
  const Model<double> at_lo = r.vary == Parameter::a ? m : with_parameter(m, r.vary, lo);
  double v_top = trapping_top(at_lo).value_or(v_wall + a / 2);
  v_top = std::max(v_top, v_wall + 1);
  const double g = 1.32471795724474602596;  // plastic number: x^3 = x + 1
  for (long j = 1; j < r.ics; ++j) {
    const double th = std::clamp(frac(0.5 + static_cast<double>(j) / g), 1e-6, 1 - 1e-6);
    const double u = frac(0.5 + static_cast<double>(j) / (g * g));
    const double v = v_wall + std::max(1e-4, u * (v_top - v_wall));
    InitialCondition ic{parse_decimal("theta", fixed_text(th, 6)), parse_decimal("v", fixed_text(v, 4))};
    validate(r.model, ic, "theta", "v");
    out.push_back(ic);
  }
  return out;
}

double ExponentColumn::max_lambda() const {
  double mx = -std::numeric_limits<double>::infinity();
  for (const ExponentRow& row : rows) mx = std::max(mx, row.lambda);  // NaN (undecided) is skipped by max
  return mx;
}

double ExponentColumn::mean_lambda() const {
  double sum = 0;
  for (const ExponentRow& row : rows) sum += row.lambda;
  return rows.empty() ? std::numeric_limits<double>::quiet_NaN() : sum / static_cast<double>(rows.size());
}

std::string exponent_text(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return ScalarTraits<double>::to_string(x);
}

std::string encode(const ExponentColumn& c) {
  std::string s = "P " + c.value.digits + "\n";
  for (const ExponentRow& row : c.rows)
    s += "R " + exponent_text(row.lambda) + ',' + exponent_text(row.stderr_) + ',' + name(row.cls) + ',' +
         std::to_string(row.period) + "\n";
  return s;
}

template <>
ExponentColumn decode_cell<ExponentColumn>(std::string_view text) {
  ExponentColumn c;
  const std::string_view whole = text;
  bool have_value = false;
  while (!text.empty()) {
    const size_t nl = text.find('\n');
    if (nl == std::string_view::npos || nl < 2 || text[1] != ' ') bad_column(whole);
    const std::string line(text.substr(2, nl - 2));
    if (text[0] == 'P' && !have_value) {
      c.value = {std::strtod(line.c_str(), nullptr), line};
      have_value = true;
    } else if (text[0] == 'R' && have_value) {
      const size_t c1 = line.find(','), c2 = line.find(',', c1 + 1), c3 = line.find(',', c2 + 1);
      if (c1 == std::string::npos || c2 == std::string::npos || c3 == std::string::npos) bad_column(whole);
      ExponentRow row;
      row.lambda = std::strtod(line.substr(0, c1).c_str(), nullptr);
      row.stderr_ = std::strtod(line.substr(c1 + 1, c2 - c1 - 1).c_str(), nullptr);
      const std::optional<OrbitClass> cls = orbit_class_named(std::string_view(line).substr(c2 + 1, c3 - c2 - 1));
      if (!cls) bad_column(whole);
      row.cls = *cls;
      const auto p = std::from_chars(line.data() + c3 + 1, line.data() + line.size(), row.period);
      if (p.ec != std::errc() || p.ptr != line.data() + line.size()) bad_column(whole);
      c.rows.push_back(row);
    } else {
      bad_column(whole);
    }
    text.remove_prefix(nl + 1);
  }
  if (!have_value) bad_column(whole);
  return c;
}

struct ExponentCurveGrid::Impl {
  ExponentCurveRequest request;
  std::vector<InitialCondition> starts;
  std::unique_ptr<CurveBase> curve;
};

ExponentCurveGrid::ExponentCurveGrid(const ExponentCurveRequest& r) : impl_(new Impl{r, {}, nullptr}) {
  check_curve(r);
  impl_->starts = exponent_curve_starts(r);
  with_point_scalar(r.precision, [&](auto tag) {
    impl_->curve = std::make_unique<Curve<typename decltype(tag)::type>>(impl_->request, impl_->starts);
  });
}
ExponentCurveGrid::~ExponentCurveGrid() = default;
const ExponentCurveRequest& ExponentCurveGrid::request() const { return impl_->request; }
const std::vector<InitialCondition>& ExponentCurveGrid::starts() const { return impl_->starts; }

GridPlan ExponentCurveGrid::plan() const { return point_grid_plan(impl_->request.samples, 16); }

// A row of the tile: two exponents of up to 24 characters, a class and a period.
double ExponentCurveGrid::item_bytes() const { return 64.0 * static_cast<double>(impl_->starts.size()) + 64; }

ExponentColumn ExponentCurveGrid::column(long k) const { return impl_->curve->column(k); }
std::string ExponentCurveGrid::item(long k) const { return encode(column(k)); }
ExponentCurveResult ExponentCurveGrid::result(std::vector<ExponentColumn> columns) const {
  return {impl_->request, impl_->starts, std::move(columns)};
}

ExponentCurveResult exponent_curve(const ExponentCurveRequest& r, const GridOptions& run) {
  const ExponentCurveGrid grid(r);
  return grid.result(
      decode_cells<ExponentColumn>(run_in_memory(grid.plan(), [&](long k) { return grid.item(k); }, run)));
}

}  // namespace bouncer
