// bouncer lyapunov: leading Lyapunov exponent per collision through the AD tangent map,
// with a transient, renormalisation at every step and a block error estimate.
//
// With --vary a|eps|c --range LO:HI --samples K it draws exponent curves (the paper's fig.
// lyapunov_one): at each value p_k = LO + (HI - LO) k/(K - 1) the same measurement as the
// single-point command (the same function, so a value's exponent is bit for bit that of
// `bouncer lyapunov` at that value) for --ics N initial conditions, each classified by
// bouncer::classify where its measured window ended. A grid job like `bifurcation`: tiles,
// threads, shards, resume, `bouncer merge`.
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "analysis_common.hpp"
#include "bouncer/analysis/classify.hpp"
#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/model/trapping.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& lyapunov_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "transient", "steps", "blocks", "precision"});
    return k;
  }();
  return keys;
}

// ---- exponent curves (--vary) ----------------------------------------------------------

struct CurveRequest {
  ModelSpec model;
  std::string vary;
  Decimal lo, hi;
  long samples = 100;
  long ics = 1;
  std::vector<InitialCondition> starts;  // the --ics starts, the same at every value
  LyapunovOptions lyap;
  ClassifyOptions classify;
  Precision precision;
};

// Fraction of x in [0, 1).
double frac(double x) { return x - std::floor(x); }

std::string fixed_text(double x, int decimals) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(decimals) << x;
  return os.str();
}

// The starts: the given (or default) one first, then ics - 1 points of the R2
// low-discrepancy sequence (Roberts 2018: x_j = frac(1/2 + j (1/g, 1/g^2)), g the plastic
// number) mapped to theta in (0, 1) and v in (v_wall, v_top]. v_wall is the wall's fastest
// upward velocity (4 on the triangle), so every start lies above the wall. v_top is the top
// of the trapping region at the range's end where it is smallest, so the starts lie in the
// trapping region of every value (model/trapping.hpp: 4(1 + 3 eps)/(1 - eps) for constant
// eps on the triangle; the paper's V_c for the velocity-dependent law where it is
// invariant, else 4 + c (5/3)^(5/3) e^(-5/3), README Claims row 5). The elastic map has no
// trapping region: v_top = v_wall + a/2 (a the smallest of the range; ap/2 is the speed of
// period-p motions). Decimals with 6 (theta) and 4 (v) places, so that each start is an exact
// decimal that `bouncer lyapunov --theta --v` reproduces.
std::vector<InitialCondition> curve_starts(const CurveRequest& r, const Options& o) {
  const Model<double> m = make_model<double>(r.model, 53);
  const double v_wall = wall_up_speed(m.wall);
  std::vector<InitialCondition> out;
  if (o.has("theta") || o.has("v")) {
    out.push_back(start_from(o, r.model));
  } else {
    // Default: theta = 0.1 and v two above the wall's fastest upward velocity (6 on the
    // triangle, inside the trapping region of constant eps >= 1/7 and of veldep c >= 1).
    InitialCondition ic{parse_decimal("theta", "0.1"), Decimal::from_int(static_cast<long>(std::ceil(v_wall)) + 2)};
    validate(r.model, ic, "theta", "v");
    out.push_back(ic);
  }
  // The model at the range's end where the trapping region is lowest (a: the top does not
  // depend on a; eps and c: the lower end), its top from model/trapping.hpp.
  const double lo = r.lo.approx();
  const double a = r.vary == "a" ? lo : r.model.a.approx();
  const Model<double> at_lo = r.vary == "a" ? m : with_parameter(m, parse_parameter("vary", r.vary), lo);
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

CurveRequest curve_request(const Options& given) {
  CurveRequest r;
  r.vary = given.get("vary");
  Options o = given;
  default_to_range_start(o, r.vary);
  r.model = model_from(o);
  if (r.vary != "a" && r.vary != "eps" && r.vary != "c") throw InputError("vary", "must be a, eps or c (got '" + r.vary + "')");
  if (r.vary == "eps" && r.model.law != Law::constant) throw InputError("vary", "eps can only vary with --model constant");
  if (r.vary == "c" && r.model.law != Law::veldep) throw InputError("vary", "c can only vary with --model veldep");
  if (!o.has("range")) throw InputError("range", "is needed with --vary: LO:HI (decimals, LO < HI)");
  std::tie(r.lo, r.hi) = parse_range("range", o.get("range"));
  validate_range_ends(r.model, parse_parameter("vary", r.vary), "range", r.lo, r.hi);
  r.samples = integer_from(o, "samples", 1, 100000, 100);
  r.ics = integer_from(o, "ics", 1, 1000, 1);
  r.lyap.transient = integer_from(o, "transient", 0, 1000000000LL, 1000);
  r.lyap.steps = integer_from(o, "steps", 1, 1000000000LL, 10000);
  r.lyap.blocks = integer_from(o, "blocks", 1, 10000, 20);
  // The class is decided where the measured window ended (the orbit has then run
  // transient + steps steps): no further transient, the classifier's default window.
  Options co = o;
  co.set("transient", "0");
  co.values.erase("steps");
  r.classify = classify_options_from(co);
  r.precision = analysis_precision(o, "lyapunov");
  r.starts = curve_starts(r, o);
  return r;
}

template <class T>
struct CurveGrid {
  using Tr = ScalarTraits<T>;
  const CurveRequest& r;
  Model<T> base;
  T lo, hi;
  explicit CurveGrid(const CurveRequest& req)
      : r(req), base(make_model<T>(req.model, req.precision.bits)),
        lo(Tr::from_decimal(req.lo.text(), req.precision.bits)), hi(Tr::from_decimal(req.hi.text(), req.precision.bits)) {}

  T param(long k) const { return r.samples == 1 ? lo : T(lo + (hi - lo) * k / (r.samples - 1)); }

  // The model at p, exactly as make_model builds it from the decimal that prints p.
  Model<T> model_at(const T& p) const {
    return with_parameter(base, parse_parameter("vary", r.vary), p);
  }

  // Value k: one row per start (value, ic, theta0, v0, lambda, stderr, class, period).
  std::string item(long k) const {
    const T p = param(k);
    const Model<T> m = model_at(p);
    const ImpactMap<T> map(m);
    const std::string ptext = Tr::to_string(p);
    std::ostringstream out;
    for (size_t j = 0; j < r.starts.size(); ++j) {
      const InitialCondition& ic = r.starts[j];
      State<T> end = make_state<T>(ic, r.precision.bits);
      const LyapunovResult lr = lyapunov(m, end, r.lyap, &end);
      out << ptext << ',' << j << ',' << ic.theta.text() << ',' << ic.v.text() << ',' << number_text(lr.lambda) << ','
          << number_text(lr.stderr_) << ',';
      if (lr.undecided) {
        out << "undecided,0\n";
      } else {
        // The same orbit, classified where its measured window ended (a contracted run
        // stopped at a sticking step: the classifier finds the sticking period from there).
        const Classification c = classify<T>(map, end, r.classify);
        out << name(c.cls) << ',' << c.period << '\n';
      }
    }
    return out.str();
  }

  static std::string number_text(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    return ScalarTraits<double>::to_string(x);
  }
};

struct CurveRow {
  double value = 0, lambda = 0, err = 0;
  std::string cls;
};

void curve_finish(const CurveRequest& r, const std::vector<std::string>& items, const RunFlags& f, const Provenance& prov) {
  std::string csv = "value,ic,theta0,v0,lambda,stderr,class,period\n";
  // The x window: the range and 2% beyond each end, exactly; relative to an offset when a
  // double cannot resolve it (a zoom), and then each value is placed from its exact text.
  const mpq_class lo = r.lo.value(), hi = r.hi.value();
  const mpq_class margin = r.samples == 1 ? mpq_class(1, 2) : mpq_class((hi - lo) / 50);
  const mpq_class x_lo = lo - margin, x_hi = (r.samples == 1 ? lo : hi) + margin;
  const AxisZoom zx(x_lo, x_hi);
  std::vector<CurveRow> rows;
  std::map<std::string, long> counts;
  nlohmann::ordered_json per_value = nlohmann::ordered_json::array();
  long not_drawn = 0;
  for (const std::string& item : items) {
    csv += item;
    std::istringstream in(item);
    std::string line, value_text;
    double mx = -std::numeric_limits<double>::infinity(), sum = 0;
    long n = 0;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      std::istringstream ls(line);
      std::string cell[8];
      for (auto& c : cell) std::getline(ls, c, ',');
      CurveRow row{zx.active() ? zx(exact_value(cell[0])) : std::strtod(cell[0].c_str(), nullptr),
                   std::strtod(cell[4].c_str(), nullptr), std::strtod(cell[5].c_str(), nullptr), cell[6]};
      value_text = cell[0];
      mx = std::max(mx, row.lambda);  // NaN (undecided) is skipped by max
      sum += row.lambda;
      ++n;
      ++counts[row.cls];
      if (!std::isfinite(row.lambda)) ++not_drawn;
      rows.push_back(row);
    }
    nlohmann::ordered_json v;
    v["value"] = value_text;
    v["max_lambda"] = json_number(mx);
    v["mean_lambda"] = json_number(n ? sum / n : std::numeric_limits<double>::quiet_NaN());
    per_value.push_back(v);
  }

  // One series per class (legend order: by count, then name), error bars +- stderr, and the
  // zero line that separates contraction from chaos.
  std::vector<std::pair<std::string, long>> order(counts.begin(), counts.end());
  std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) {
    return x.second != y.second ? x.second > y.second : x.first < y.first;
  });
  Figure fig;
  {
    Series zero;
    zero.x = {zx(lo), zx(hi)};
    zero.y = {0, 0};
    zero.lines = true;
    zero.markers = false;
    zero.color = Rgb{120, 120, 120};
    fig.series.push_back(zero);
  }
  const int marker = r.samples * r.ics > 2000 ? 1 : r.samples * r.ics > 300 ? 2 : 3;
  int sticking_rank = 0;
  for (const auto& [cls, n] : order) {
    Series s;
    const OrbitClass oc = orbit_class_named(cls).value_or(OrbitClass::undecided);
    s.color = attractor_color(oc, 0, sticking_rank, f.picture.palette);
    if (oc == OrbitClass::sticking) ++sticking_rank;
    std::string label = cls;
    std::replace(label.begin(), label.end(), '_', ' ');
    s.label = label + " (" + std::to_string(n) + ")";
    s.marker_size = marker;
    for (const CurveRow& row : rows)
      if (row.cls == cls) {
        s.x.push_back(row.value);
        s.y.push_back(row.lambda);
        s.yerr.push_back(row.err);
      }
    fig.series.push_back(std::move(s));
  }
  const std::string par = r.vary == "eps" ? "ε" : r.vary;
  fig.title = "Leading Lyapunov exponent, " + model_title(r.model.law) + " model";
  std::string fixed;
  if (r.vary != "a") fixed += "a = " + r.model.a.text() + ", ";
  if (r.model.law == Law::constant && r.vary != "eps") fixed += "ε = " + r.model.eps.text() + ", ";
  if (r.model.law == Law::veldep && r.vary != "c") fixed += "c = " + r.model.c.text() + ", ";
  fig.subtitle = fixed + std::to_string(r.samples) + " values x " + std::to_string(r.ics) + " start" +
                 (r.ics == 1 ? "" : "s") + ", " + std::to_string(r.lyap.transient) + " + " + std::to_string(r.lyap.steps) +
                 " steps, " + r.precision.text() + (not_drawn ? "; " + std::to_string(not_drawn) + " with λ = −∞ or NaN not drawn" : "");
  fig.xlabel = par;
  fig.ylabel = "λ per collision (± standard error)";
  fig.legend_below = true;
  fig.x_min = zx(x_lo);
  fig.x_max = zx(x_hi);
  fig.x_offset = zx.offset();
  fig.metadata = png_metadata(prov, fig.title);

  nlohmann::ordered_json s;
  s["command"] = "lyapunov";
  s["vary"] = r.vary;
  s["range"] = {r.lo.text(), r.hi.text()};
  s["samples"] = r.samples;
  s["ics"] = r.ics;
  nlohmann::ordered_json starts = nlohmann::ordered_json::array();
  for (const auto& ic : r.starts) starts.push_back({ic.theta.text(), ic.v.text()});
  s["starts"] = starts;
  s["transient"] = r.lyap.transient;
  s["steps"] = r.lyap.steps;
  s["blocks"] = r.lyap.blocks;
  nlohmann::ordered_json classes;
  for (const auto& [cls, n] : order) classes[cls] = n;
  s["classes"] = classes;
  s["values"] = per_value;
  s["precision"] = r.precision.text();
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

template <class T>
nlohmann::ordered_json measure(const ModelSpec& spec, const Precision& prec, const InitialCondition& ic,
                               const LyapunovOptions& lo) {
  const Model<T> m = make_model<T>(spec, prec.bits);
  const LyapunovResult r = lyapunov(m, make_state<T>(ic, prec.bits), lo);
  nlohmann::ordered_json j;
  j["lambda"] = json_number(r.lambda);
  j["stderr"] = json_number(r.stderr_);
  j["steps"] = r.steps;
  j["transient"] = lo.transient;
  j["blocks"] = r.blocks;
  j["contracted"] = r.contracted;
  j["unbounded"] = r.unbounded;
  j["growth_alpha"] = json_number(r.alpha);
  j["v_max"] = json_number(r.v_max);
  j["undecided"] = r.undecided;
  j["note"] = r.note;
  return j;
}

}  // namespace

const std::set<std::string>& lyapunov_curve_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = lyapunov_keys();
    k.insert({"vary", "range", "samples", "ics", "max-period", "recheck-factor"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_lyapunov_curve(const Options& o, const RunFlags& f) {
  const CurveRequest req = curve_request(o);
  return run_point_grid<CurveGrid>("lyapunov", o, f, req, req.samples, 16, curve_finish);
}

Command add_lyapunov(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("lyapunov", "Leading Lyapunov exponent per collision (AD tangent map)");
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  add_start_options(*opts);
  opts->add("transient", "Steps discarded first, integer in [0, 1e12] (default 1000; at most 1e9 with --vary)");
  opts->add("steps", "Steps measured, integer in [1, 1e12] (default 10000)");
  opts->add("blocks", "Blocks for the error estimate, integer in [1, 10000] (default 20)");
  opts->add("precision", kPointPrecisionHelp);
  opts->add("vary", "Exponent curve: the parameter to sweep, a | eps (constant model) | c (veldep model)");
  opts->add("range", "With --vary: LO:HI (decimals, LO < HI, both inside the model's range), both included");
  opts->add("samples", "With --vary: number of values K, 1..100000 (default 100)");
  opts->add("ics", "With --vary: starts per value N, 1..1000 (default 1): --theta/--v (default 0.1, wall speed + 2), "
                   "then an R2 low-discrepancy spread in the trapping region");
  add_classify_period_options(*opts);  // with --vary: the classifier of each row (steps = 500 there)
  auto flags = add_run_options(sub, *opts);
  auto json = std::shared_ptr<bool>(flags, &flags->json);

  auto run = [opts, scene, json, flags](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "lyapunov", lyapunov_curve_keys()), opts->collected());
    if (o.has("vary")) return run_lyapunov_curve(o, run_flags_from(o, *flags, argv_text));
    for (const char* k : {"range", "samples", "ics", "max-period", "recheck-factor", "shard", "out", "threads"})
      if (o.has(k)) throw InputError(k, "belongs to an exponent curve: give --vary a|eps|c with --range LO:HI");
    if (flags->quiet || flags->keep_tiles || flags->force)
      throw InputError("vary", "--quiet/--keep-tiles/--force belong to an exponent curve (--vary)");
    const ModelSpec spec = model_from(o);
    const InitialCondition ic = start_from(o, spec);
    const LyapunovOptions lo = lyapunov_options_from(o);
    const Precision prec = analysis_precision(o, "lyapunov");
    const Provenance p = provenance_for("lyapunov", o, prec, argv_text);
    const nlohmann::ordered_json body = with_point_scalar(
        prec, [&](auto tag) { return measure<typename decltype(tag)::type>(spec, prec, ic, lo); });
    print_summary(p, body, *json);
    if (!body["note"].get<std::string>().empty()) std::cerr << "bouncer lyapunov: " << body["note"].get<std::string>() << "\n";
    return 0;
  };
  return {sub, run};
}

}  // namespace bouncer::cli
