// bouncer bifurcation: sweep one parameter (a, eps or c); at each value follow an orbit for
// N transient steps and record the next M (paper sec. IV.B: N = 5000, M = 500). Output: CSV
// rows (param, n, theta, v, sticking), a density image of theta (or v) against the
// parameter with the sticking releases marked in red at theta = 1/2 as in the paper, and a
// JSON summary. Each parameter value is one grid item (independent unless --carry).
// --certify (constant, elastic, or veldep without collapse; double): each column also gets a
// certified answer for the exact orbit at the exact double value of the parameter
// (verify/certified_point.hpp) and double's class of the same orbit; the picture shades the
// columns where double is refuted (vermillion), where only the orbit is certified (not_trapped:
// lavender; every certified elastic column) or where nothing is certified (grey).
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/verify/certified_point.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

struct BifurcationRequest {
  ModelSpec model;
  std::string vary;
  Decimal lo, hi;
  long samples = 200;
  long transient = 5000, record = 500;
  InitialCondition ic;
  bool carry = false;
  Precision precision;
  std::string show = "theta";
  long bins = 400;
  bool certify = false;
  CertifyPointOptions cert;
};

BifurcationRequest bifurcation_request(const Options& given) {
  BifurcationRequest r;
  r.vary = given.get_or("vary", "a");
  Options o = given;
  default_to_range_start(o, r.vary);
  r.model = model_from(o);
  if (r.vary != "a" && r.vary != "eps" && r.vary != "c") throw InputError("vary", "must be a, eps or c (got '" + r.vary + "')");
  if (r.vary == "eps" && r.model.law != Law::constant) throw InputError("vary", "eps can only vary with --model constant");
  if (r.vary == "c" && r.model.law != Law::veldep) throw InputError("vary", "c can only vary with --model veldep");
  std::tie(r.lo, r.hi) = parse_range("range", o.get("range"));
  validate_range_ends(r.model, parse_parameter("vary", r.vary), "range", r.lo, r.hi);
  r.samples = integer_from(o, "samples", 1, 100000, 200);
  r.transient = integer_from(o, "transient", 0, 100000000, 5000);
  r.record = integer_from(o, "record", 1, 1000000, 500);
  if (static_cast<double>(r.samples) * static_cast<double>(r.record) > 5e7)
    throw InputError("record", "samples x record must be at most 5e7 rows (got " + std::to_string(r.samples) + " x " +
                                   std::to_string(r.record) + ")");
  const auto ics = initial_conditions_from(o, r.model);
  if (ics.size() != 1) throw InputError("theta", "takes one initial condition here");
  r.ic = ics[0];
  const std::string carry = o.get_or("carry", "false");
  if (carry != "true" && carry != "false") throw InputError("carry", "must be true or false");
  r.carry = carry == "true";
  r.precision = point_precision(o);
  r.show = o.get_or("show", "theta");
  if (r.show != "theta" && r.show != "v") throw InputError("show", "must be theta or v (got '" + r.show + "')");
  r.bins = integer_from(o, "bins", 10, 4000, 400);
  const std::string certify = o.get_or("certify", "false");
  if (certify != "true" && certify != "false") throw InputError("certify", "must be true or false (got '" + certify + "')");
  r.certify = certify == "true";
  if (o.has("max-bits") && !r.certify) throw InputError("max-bits", "is only used with --certify");
  if (r.certify) {
    require_certified_model(r.model, "bifurcation");
    if (r.carry) throw InputError("carry", "cannot be used with --certify (each column is certified from its own start)");
    if (r.precision.kind != Precision::Kind::double_)
      throw InputError("precision", "with --certify the twin run is double; got '" + r.precision.text() + "'");
    r.cert.max_steps = r.transient + r.record;
    r.cert.max_bits = integer_from(o, "max-bits", 64, 4096, 256);
  }
  return r;
}

// One parameter value: the model at p_k = lo + (hi - lo) k/(K - 1), computed in T.
template <class T>
struct Sweep {
  const BifurcationRequest& r;
  Model<T> base;
  T lo, hi;
  std::optional<State<T>> carried;  // --carry: the last state of the previous value

  explicit Sweep(const BifurcationRequest& req)
      : r(req), base(make_model<T>(req.model, req.precision.bits)),
        lo(ScalarTraits<T>::from_decimal(req.lo.text(), req.precision.bits)),
        hi(ScalarTraits<T>::from_decimal(req.hi.text(), req.precision.bits)) {}

  T param(long k) const { return r.samples == 1 ? lo : T(lo + (hi - lo) * k / (r.samples - 1)); }

  Model<T> model_at(const T& p) const {
    return with_parameter(base, parse_parameter("vary", r.vary), p);
  }

  std::string item(long k) {
    using Tr = ScalarTraits<T>;
    const T p = param(k);
    const ImpactMap<T> map(model_at(p));
    State<T> s = r.carry && carried ? *carried : make_state<T>(r.ic, r.precision.bits);
    const std::string ptext = Tr::to_string(p);
    std::ostringstream out;
    long n = 0;
    try {
      for (; n < r.transient; ++n) s = map.step(s).next;
      for (long m = 0; m < r.record; ++m, ++n) {
        const StepResult<T> st = map.step(s);
        s = st.next;
        out << ptext << ',' << n + 1 << ',' << Tr::to_string(s.theta) << ',' << Tr::to_string(s.v) << ','
            << (st.kind == EventKind::sticking ? 1 : 0) << '\n';
      }
      carried = s;
    } catch (const Undecided& u) {
      out << "# undecided: " << r.vary << "=" << ptext << " step " << n + 1 << ": " << u.what() << "\n";
      carried.reset();
    }
    if (r.certify) out << certificate_line(p);
    return out.str();
  }

  // --certify: "# certified: a,class,period,certified_steps,scalar,double_class,double_period,
  // agreement" for the exact orbit at the exact value of p (a double, printed exactly).
  std::string certificate_line(const T& p) const {
    if constexpr (std::is_same_v<T, double>) {
      CertifyPointOptions opt = r.cert;
      const mpq_class exact(p);
      // The column's parameter is the double p exactly: a dyadic number, a finite decimal.
      ModelSpec spec = r.model;
      (r.vary == "a" ? spec.a : r.vary == "eps" ? spec.eps : spec.c) = *Decimal::parse(exact_decimal(exact));
      opt.max_attractor_period = std::min<long>(64, std::max<long>(1, r.record / 2));
      ReleaseCache releases;
      const CertifiedPoint c = certify_point(spec, r.ic, opt, releases);
      ClassifyOptions co;
      co.transient = r.transient;
      co.steps = std::max<long>(8, r.record);
      co.max_period = opt.max_attractor_period;
      co.recheck_factor = 0;
      const ImpactMap<T> map(model_at(p));
      const Classification d = classify<T>(map, make_state<T>(r.ic, 53), co);
      std::ostringstream out;
      out << "# certified: " << exact_decimal(exact) << ',' << c.cls << ',' << c.period << ',' << c.certified_steps << ','
          << c.scalar << ',' << name(d.cls) << ',' << d.period << ',' << compare_with_certified(c, name(d.cls), d.period)
          << '\n';
      return out.str();
    } else {
      return "";
    }
  }
};

struct Point {
  double p, theta, v;
  bool sticking;
};

void finish(const BifurcationRequest& r, const std::vector<std::string>& items, const RunFlags& f, const Provenance& prov) {
  std::string csv = r.vary + ",n,theta,v,sticking\n";
  std::vector<std::vector<Point>> per(items.size());
  std::vector<std::string> certified(items.size());  // --certify: the column's certificate line
  long rows = 0, undecided = 0, sticking_samples = 0, sticking_events = 0;
  for (size_t k = 0; k < items.size(); ++k) {
    csv += items[k];
    std::istringstream in(items[k]);
    std::string line;
    bool stuck = false;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      if (line.rfind("# certified: ", 0) == 0) {
        certified[k] = line.substr(13);
        continue;
      }
      if (line[0] == '#') { ++undecided; continue; }
      Point pt{};
      int flag = 0;
      std::istringstream ls(line);
      std::string cell[5];
      for (auto& c : cell) std::getline(ls, c, ',');
      long n;
      pt.p = std::strtod(cell[0].c_str(), nullptr);
      n = std::strtol(cell[1].c_str(), nullptr, 10);
      (void)n;
      pt.theta = std::strtod(cell[2].c_str(), nullptr);
      pt.v = std::strtod(cell[3].c_str(), nullptr);
      flag = std::atoi(cell[4].c_str());
      pt.sticking = flag != 0;
      stuck = stuck || pt.sticking;
      sticking_events += pt.sticking;
      per[k].push_back(pt);
      ++rows;
    }
    sticking_samples += stuck;
  }

  // Density raster: one column per parameter value, `bins` rows over the shown variable.
  const bool show_theta = r.show == "theta";
  double y0 = 0, y1 = 1;
  if (!show_theta) {
    y0 = std::numeric_limits<double>::infinity();
    y1 = -y0;
    for (const auto& col : per)
      for (const Point& pt : col)
        if (std::isfinite(pt.v)) { y0 = std::min(y0, pt.v); y1 = std::max(y1, pt.v); }
    if (!std::isfinite(y0)) { y0 = 0; y1 = 1; }
    const double pad = std::max(1e-9, (y1 - y0) * 0.04);
    y0 -= pad;
    y1 += pad;
  }
  const int nx = static_cast<int>(std::min<long>(r.samples, 1600));
  const int ny = static_cast<int>(r.bins);
  std::vector<long> count(static_cast<size_t>(nx) * ny, 0);
  std::vector<char> stick(static_cast<size_t>(nx) * ny, 0);
  for (size_t k = 0; k < per.size(); ++k) {
    const int col = r.samples == 1 ? 0 : static_cast<int>(static_cast<double>(k) * nx / r.samples);
    for (const Point& pt : per[k]) {
      const double y = show_theta ? pt.theta : pt.v;
      if (!std::isfinite(y)) continue;
      const int row = std::clamp(static_cast<int>((y1 - y) / (y1 - y0) * ny), 0, ny - 1);
      const size_t at = static_cast<size_t>(row) * nx + col;
      if (pt.sticking) stick[at] = 1;
      else ++count[at];
    }
  }
  long max_count = 1;
  for (long c : count) max_count = std::max(max_count, c);
  ImageFigure fig;
  Raster& ras = fig.raster;
  ras.nx = nx;
  ras.ny = ny;
  // Each value's column is centred on it: the window reaches half a sample beyond the ends,
  // exactly, and is drawn relative to an offset when a double cannot resolve it (a zoom).
  const mpq_class half = r.samples == 1 ? mpq_class(1, 2) : mpq_class((r.hi.value() - r.lo.value()) / (2 * (r.samples - 1)));
  const mpq_class x_lo = r.lo.value() - half, x_hi = (r.samples == 1 ? r.lo.value() : r.hi.value()) + half;
  const AxisZoom zx(x_lo, x_hi);
  ras.x_min = zx(x_lo);
  ras.x_max = zx(x_hi);
  ras.x_offset = zx.offset();
  ras.y_min = y0;
  ras.y_max = y1;
  // Density of orbit points, log scale: grey to black (--palette paper, the paper's look) or
  // viridis from green (sparse) to dark purple (dense), both readable on the white background.
  const bool paper = f.picture.palette == Palette::paper;
  const Rgb red = paper ? Rgb{215, 25, 28} : Rgb{213, 94, 0};
  auto density = [&](double t) { return paper ? ramp_color(0.45 + 0.55 * t) : viridis_color(0.75 * (1 - t)); };
  // --certify: the background of each column says what the certificate says of double there.
  // not_trapped (veldep, elastic): the exact orbit is certified through every step but its
  // class is not decided; pale lavender as in the certified basins, not the grey of "nothing
  // certified".
  const Rgb refuted_bg{250, 205, 185}, undecided_bg{222, 222, 222}, orbit_only_bg{218, 210, 235};
  long orbit_only = 0;
  std::vector<Rgb> column_bg(static_cast<size_t>(nx), Rgb{255, 255, 255});
  std::map<std::string, long> agreement;
  nlohmann::ordered_json columns = nlohmann::ordered_json::array();
  if (r.certify) {
    for (size_t k = 0; k < certified.size(); ++k) {
      std::istringstream ls(certified[k]);
      std::string cell[8];
      for (auto& c : cell) std::getline(ls, c, ',');
      ++agreement[cell[7]];
      const int col = r.samples == 1 ? 0 : static_cast<int>(static_cast<double>(k) * nx / r.samples);
      if (cell[7] == "differs") column_bg[static_cast<size_t>(col)] = refuted_bg;
      else if (cell[7] == "undecided" && column_bg[static_cast<size_t>(col)].r == 255)
        column_bg[static_cast<size_t>(col)] = cell[1] == "not_trapped" ? orbit_only_bg : undecided_bg;
      orbit_only += cell[1] == "not_trapped";
      columns.push_back({{r.vary, cell[0]}, {"class", cell[1]}, {"period", std::atol(cell[2].c_str())},
                         {"certified_steps", std::atoll(cell[3].c_str())}, {"scalar", cell[4]}, {"double_class", cell[5]},
                         {"double_period", std::atol(cell[6].c_str())}, {"agreement", cell[7]}});
    }
  }
  for (size_t i = 0; i < count.size(); ++i) {
    if (stick[i]) ras.pixels.push_back(red);
    else if (count[i] == 0) ras.pixels.push_back(column_bg[i % static_cast<size_t>(nx)]);
    else ras.pixels.push_back(density(std::log1p(static_cast<double>(count[i])) / std::log1p(static_cast<double>(max_count))));
  }
  ras.legend = {{paper ? "orbit points (darker: denser)" : "orbit points (green: sparse, purple: dense)", density(1.0)},
                {show_theta ? "sticking release (θ = 1/2)" : "sticking release (v = 4)", red}};
  if (r.certify) {
    auto n_of = [&](const char* k) { return agreement.count(k) ? agreement[k] : 0L; };
    ras.legend.emplace_back("double refuted by the certificate (" + std::to_string(n_of("differs")) + " values)", refuted_bg);
    if (orbit_only > 0)
      ras.legend.emplace_back("orbit certified, class open (" + std::to_string(orbit_only) + " values)", orbit_only_bg);
    ras.legend.emplace_back("no certified answer (" + std::to_string(n_of("undecided") - orbit_only) + " values)", undecided_bg);
  }
  ras.colorbar.clear();  // grey level ~ log(points per cell); the legend names the marks
  ras.legend_below = true;
  const std::string par = r.vary == "eps" ? "ε" : r.vary;
  fig.title = "Bifurcation diagram, " + model_title(r.model.law) + " model";
  std::string fixed;
  if (r.vary != "a") fixed += "a = " + r.model.a.text() + ", ";
  if (r.model.law == Law::constant && r.vary != "eps") fixed += "ε = " + r.model.eps.text() + ", ";
  if (r.model.law == Law::veldep && r.vary != "c") fixed += "c = " + r.model.c.text() + ", ";
  fig.subtitle = fixed + "θ₀ = " + r.ic.theta.text() + ", v₀ = " + r.ic.v.text() + "; " + std::to_string(r.transient) +
                 " + " + std::to_string(r.record) + " steps x " + std::to_string(r.samples) + (r.carry ? " (carried)" : "") +
                 ", " + r.precision.text() +
                 (r.certify ? "; columns certified (interval:double, then MPFI up to " + std::to_string(r.cert.max_bits) + " bits)"
                            : "");
  fig.xlabel = par;
  fig.ylabel = show_theta ? "θ (phase of impact)" : "v (velocity after impact)";
  fig.metadata = png_metadata(prov, fig.title);

  nlohmann::ordered_json s;
  s["command"] = "bifurcation";
  s["vary"] = r.vary;
  s["range"] = {r.lo.text(), r.hi.text()};
  s["samples"] = r.samples;
  s["transient"] = r.transient;
  s["record"] = r.record;
  s["rows"] = rows;
  s["samples_with_sticking"] = sticking_samples;
  s["sticking_events"] = sticking_events;
  s["undecided_samples"] = undecided;
  s["precision"] = r.precision.text();
  if (r.certify) {
    auto n_of = [&](const char* k) { return agreement.count(k) ? agreement[k] : 0L; };
    s["certified"] = true;
    s["max_steps"] = r.cert.max_steps;
    s["schedule"] = "interval:double, then MPFI at 64, 128, ... up to " + std::to_string(r.cert.max_bits) + " bits";
    s["double_vs_certified"] = {{"agrees", n_of("agrees")}, {"differs", n_of("differs")}, {"undecided", n_of("undecided")}};
    s["columns"] = columns;
  }
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

}  // namespace

const std::set<std::string>& bifurcation_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"vary", "range", "samples", "transient", "record", "theta", "v", "carry", "precision", "show", "bins",
              "certify", "max-bits"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_bifurcation(const Options& o, const RunFlags& f) {
  const BifurcationRequest req = bifurcation_request(o);
  PictureJob job;
  job.command = "bifurcation";
  job.job = job_options(o);
  job.plan.items = req.samples;
  // --carry chains the values: one tile, computed in order by one worker.
  job.plan.tile_items = req.carry ? req.samples : std::max<long>(1, std::min<long>(16, req.samples / 64 + 1));
  job.item_bytes = 40.0 * static_cast<double>(req.record) + 64;  // a column: `record` values
  job.size_field = "samples";
  const Provenance prov = provenance_for("bifurcation", job.job, req.precision, f.invocation);
  return with_scalar(req.precision, [&](auto tag) -> int {
    using T = typename decltype(tag)::type;
    if constexpr (ScalarTraits<T>::is_interval) {
      throw InputError("precision", "interval precision is not supported here");
    } else {
      auto sweep = std::make_shared<Sweep<T>>(req);
      job.item = [sweep](long k) { return sweep->item(k); };
      const auto items = run_job(job, f);
      if (items) finish(req, *items, f, prov);
      return 0;
    }
  });
}

Command add_bifurcation(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("bifurcation", "Bifurcation diagram: sweep a, eps or c; CSV, density PNG, JSON");
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("vary", "Parameter to sweep: a (default) | eps (constant model) | c (veldep model)");
  opts->add("range", "Sweep range LO:HI (decimals, LO < HI), LO and HI included");
  opts->add("samples", "Number of parameter values K, 1..100000 (default 200)");
  opts->add("transient", "Steps discarded at each value, N (default 5000, as in the paper)");
  opts->add("record", "Steps recorded at each value, M >= 1 (default 500, as in the paper)");
  opts->add_list("theta", "Initial phase in [0, 1)");
  opts->add_list("v", "Initial velocity after impact, >= the wall velocity at theta");
  opts->add("precision", kPointPrecisionHelp);
  opts->add("show", "Picture: theta (default) or v against the parameter");
  opts->add("bins", "Rows of the density image, 10..4000 (default 400)");
  opts->add("max-bits", "With --certify: the last MPFI precision of the schedule interval:double, 64, 128, ..., 64..4096 (default 256)");
  opts->add_flag("carry", "Start each value from the last state of the previous one (one worker)");
  opts->add_flag("certify",
                "Certify each column (constant, elastic, or veldep without collapse): the exact orbit at the exact double value of the parameter; shade the "
                "columns where double's class is refuted or nothing is certified");
  auto flags = add_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "bifurcation", bifurcation_keys()), opts->collected());
    return run_bifurcation(o, run_flags_from(o, *flags, argv_text));
  };
  return {sub, run};
}

}  // namespace bouncer::cli
