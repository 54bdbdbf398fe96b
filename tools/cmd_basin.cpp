// bouncer basin: basins of attraction. Every point of an N x M grid of initial conditions
// (cell centres of the theta and v ranges) is classified by bouncer::classify (fixed,
// periodic q, sticking k, quasiperiodic, chaotic, unbounded, effective sticking, transient
// chaos, undecided) and coloured by its attractor type: class and period. Black = fixed points and
// red = sticking, as in the paper's figs. basin1 and basin2; blue = unbounded. Grid
// points below the wall's velocity are outside the phase space and are marked "outside".
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/trapping.hpp"
#include "bouncer/verify/certified_point.hpp"
#include "bouncer/verify/sticking.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

struct BasinRequest {
  ModelSpec model;
  long nx = 100, ny = 100;
  Decimal t0, t1, v0, v1;
  ClassifyOptions classify;
  Precision precision;
  // --certify: every point certified (verify/certified_point.hpp), double's answer beside it.
  bool certify = false;
  CertifyPointOptions cert;
};

BasinRequest basin_request(const Options& o) {
  BasinRequest r;
  r.model = model_from(o);
  std::tie(r.nx, r.ny) = parse_grid("grid", o.get_or("grid", "100x100"), 8192);
  std::tie(r.t0, r.t1) = parse_range("theta-range", o.get_or("theta-range", "0:1"));
  if (r.t0 < Decimal::from_int(0) || r.t1 > Decimal::from_int(1))
    throw InputError("theta-range", "must lie in [0, 1] (got '" + o.get_or("theta-range", "0:1") + "')");
  if (o.has("v-range")) {
    std::tie(r.v0, r.v1) = parse_range("v-range", o.get("v-range"));
    if (r.v1.approx() > 1e15 || r.v0.approx() < -1e15) throw InputError("v-range", "must lie within +-1e15");
  } else {
    const auto range = trapping_v_range(r.model);
    if (!range && r.model.law == Law::constant)
      throw InputError("v-range", "is needed when eps = 1 (the trapping region 4(1+3eps)/(1-eps) is unbounded)");
    if (!range) throw InputError("v-range", "is needed for --model elastic (no trapping region: velocities grow without bound)");
    std::tie(r.v0, r.v1) = *range;
  }
  r.classify = classify_options_from(o);
  r.precision = point_precision(o);
  const std::string certify = o.get_or("certify", "false");
  if (certify != "true" && certify != "false") throw InputError("certify", "must be true or false (got '" + certify + "')");
  r.certify = certify == "true";
  if (o.has("max-bits") && !r.certify) throw InputError("max-bits", "is only used with --certify");
  if (r.certify) {
    require_certified_model(r.model, "basin");
    if (r.precision.kind != Precision::Kind::double_)
      throw InputError("precision", "with --certify the twin run is double (the artefact map compares double with the "
                                    "certified answer); got '" + r.precision.text() + "'");
    r.cert.max_steps = r.classify.transient + r.classify.steps;
    r.cert.max_bits = integer_from(o, "max-bits", 64, 4096, 256);
    r.cert.max_attractor_period = r.classify.max_period;
  }
  return r;
}

template <class T>
struct BasinGrid {
  const BasinRequest& r;
  ImpactMap<T> map;
  T t0, t1, v0, v1;
  explicit BasinGrid(const BasinRequest& req)
      : r(req), map(make_model<T>(req.model, req.precision.bits)),
        t0(ScalarTraits<T>::from_decimal(req.t0.text(), req.precision.bits)),
        t1(ScalarTraits<T>::from_decimal(req.t1.text(), req.precision.bits)),
        v0(ScalarTraits<T>::from_decimal(req.v0.text(), req.precision.bits)),
        v1(ScalarTraits<T>::from_decimal(req.v1.text(), req.precision.bits)) {}

  // Item i: column i mod N (theta), row i / N (v, from the bottom).
  std::string item(long i) const {
    using Tr = ScalarTraits<T>;
    const T theta = cell_centre(t0, t1, i % r.nx, r.nx);
    const T v = cell_centre(v0, v1, i / r.nx, r.ny);
    std::ostringstream out;
    out << Tr::to_string(theta) << ',' << Tr::to_string(v) << ',';
    const auto& wall = map.model().wall;
    const int seg = wall.segment_of(theta);
    if (v < wall.velocity[seg]) {
      out << "outside,0";
    } else {
      const Classification c = classify<T>(map, State<T>{theta, v}, r.classify);
      out << name(c.cls) << ',' << c.period;
    }
    return out.str();
  }
};

// --certify: item i is "theta,v,class,period,certified_steps,scalar,double_class,double_period,
// agreement" (certified class and period, verify/certified_point.hpp; the double class of the
// same start, as plain basin; compare_with_certified). T is double (basin_request).
template <class T>
struct CertifiedBasinGrid {
  const BasinRequest& r;
  BasinGrid<T> twin;
  std::shared_ptr<ReleaseCache> releases = std::make_shared<ReleaseCache>();
  explicit CertifiedBasinGrid(const BasinRequest& req) : r(req), twin(req) {}

  std::string item(long i) const {
    using Tr = ScalarTraits<T>;
    const T theta = cell_centre(twin.t0, twin.t1, i % r.nx, r.nx);
    const T v = cell_centre(twin.v0, twin.v1, i / r.nx, r.ny);
    std::ostringstream out;
    out << Tr::to_string(theta) << ',' << Tr::to_string(v) << ',';
    const auto& wall = twin.map.model().wall;
    if (v < wall.velocity[wall.segment_of(theta)]) {
      out << "outside,0,0,,outside,0,outside";
      return out.str();
    }
    // The exact start: the double grid point itself (a dyadic number, printed exactly).
    const InitialCondition start{*Decimal::parse(exact_decimal(mpq_class(Tr::to_double(theta)))),
                                 *Decimal::parse(exact_decimal(mpq_class(Tr::to_double(v))))};
    const CertifiedPoint c = certify_point(r.model, start, r.cert, *releases);
    const Classification d = classify<T>(twin.map, State<T>{theta, v}, r.classify);
    out << c.cls << ',' << c.period << ',' << c.certified_steps << ',' << c.scalar << ',' << name(d.cls) << ','
        << d.period << ',' << compare_with_certified(c, name(d.cls), d.period);
    return out.str();
  }
};

void certified_basin_finish(const BasinRequest& r, const std::vector<std::string>& items, const RunFlags& f,
                            const Provenance& prov) {
  CertifiedMap m;
  m.x_name = "theta";
  m.y_name = "v";
  m.nx = r.nx;
  m.ny = r.ny;
  m.x0 = r.t0.value();
  m.x1 = r.t1.value();
  m.y0 = r.v0.value();
  m.y1 = r.v1.value();
  m.title = "Certified basins, " + model_title(r.model.law) + " model: each coloured pixel is proved";
  m.subtitle = "a = " + r.model.a.text() +
               (r.model.law == Law::veldep ? ", c = " + r.model.c.text()
                : r.model.law == Law::constant ? ", ε = " + r.model.eps.text()
                                               : "") +
               "; " + std::to_string(r.nx) + " x " +
               std::to_string(r.ny) + " exact starts, " + std::to_string(r.cert.max_steps) +
               " steps, interval:double then MPFI up to " + std::to_string(r.cert.max_bits) + " bits";
  m.xlabel = "θ₀ (initial phase)";
  m.ylabel = "v₀ (initial velocity)";
  m.max_steps = r.cert.max_steps;
  m.max_bits = r.cert.max_bits;
  m.collapses = r.model.law == Law::constant;
  m.area_preserving = r.model.law == Law::elastic;
  m.summary["command"] = "basin";
  m.summary["certified"] = true;
  m.summary["grid"] = {r.nx, r.ny};
  m.summary["theta_range"] = {r.t0.text(), r.t1.text()};
  m.summary["v_range"] = {r.v0.text(), r.v1.text()};
  m.twin_precision = r.precision.text();
  certified_map_finish(m, items, f, prov);
}

std::string attractor_label(const std::string& cls, long period) {
  if (cls == "fixed") return "fixed point";
  if (cls == "periodic") return "period " + std::to_string(period);
  if (cls == "sticking") return "sticking, k = " + std::to_string(period);
  if (cls == "effective_sticking") return "effective sticking";
  if (cls == "transient_chaos")
    return period ? "transient chaos, settles with period " + std::to_string(period) : std::string("transient chaos, settles (no period)");
  if (cls == "outside") return "outside the phase space (v < wall velocity)";
  return cls;
}

void basin_finish(const BasinRequest& r, const std::vector<std::string>& items, const RunFlags& f, const Provenance& prov) {
  std::string csv = "theta,v,class,period\n";
  std::vector<std::pair<std::string, long>> kinds(items.size());
  std::map<std::pair<std::string, long>, long> count;
  for (size_t i = 0; i < items.size(); ++i) {
    csv += items[i];
    csv += '\n';
    std::istringstream ls(items[i]);
    std::string cell[4];
    for (auto& c : cell) std::getline(ls, c, ',');
    kinds[i] = {cell[2], std::atol(cell[3].c_str())};
    ++count[kinds[i]];
  }
  // Order: by share, then by name and period (deterministic).
  std::vector<std::pair<std::pair<std::string, long>, long>> order(count.begin(), count.end());
  std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) {
    return x.second != y.second ? x.second > y.second : x.first < y.first;
  });
  std::map<std::pair<std::string, long>, Rgb> color;
  const Palette palette = f.picture.palette;
  int periodic_rank = 0, sticking_rank = 0, transient_rank = 0;
  for (const auto& [k, n] : order) {
    color[k] = attractor_color(k.first, periodic_rank, k.first == "transient_chaos" ? transient_rank : sticking_rank, palette);
    if (k.first == "periodic") ++periodic_rank;
    if (k.first == "sticking") ++sticking_rank;
    if (k.first == "transient_chaos") ++transient_rank;
  }
  ImageFigure fig;
  Raster& ras = fig.raster;
  ras.nx = static_cast<int>(r.nx);
  ras.ny = static_cast<int>(r.ny);
  // The window in the coordinates of its axes: relative to an offset when a double cannot
  // resolve it (a zoom at mpfr:256), the values themselves otherwise.
  set_exact_window(ras, r.t0.value(), r.t1.value(), r.v0.value(), r.v1.value());
  ras.pixels.resize(items.size());
  for (size_t i = 0; i < items.size(); ++i) {
    const long col = static_cast<long>(i) % r.nx, row = r.ny - 1 - static_cast<long>(i) / r.nx;
    ras.pixels[static_cast<size_t>(row * r.nx + col)] = color[kinds[i]];
  }
  // Shares in the legend are of the points in the phase space: the starts below the wall
  // velocity ("outside") are no orbits and do not count in the denominator.
  const double total = static_cast<double>(items.size());
  long outside = 0;
  for (const auto& [k, n] : order)
    if (k.first == "outside") outside += n;
  const double inside = total - static_cast<double>(outside);
  auto share = [&](long n) {
    char pct[32];
    std::snprintf(pct, sizeof pct, " (%.1f%%)", inside > 0 ? 100.0 * n / inside : 0.0);
    return std::string(pct);
  };
  // Legend entries: one per colour. The paper palette gives every periodic type one black and
  // every sticking period one red, so those are summed into one entry each.
  std::vector<std::pair<std::string, std::pair<Rgb, long>>> entries;  // label -> colour, points
  for (const auto& [k, n] : order) {
    std::string label = attractor_label(k.first, k.second);
    if (palette == Palette::paper && (k.first == "fixed" || k.first == "periodic")) label = "fixed point or periodic";
    if (palette == Palette::paper && k.first == "sticking") label = "sticking";
    auto it = std::find_if(entries.begin(), entries.end(), [&](const auto& e) { return e.first == label; });
    if (it == entries.end()) entries.push_back({label, {color[k], n}});
    else it->second.second += n;
  }
  std::stable_sort(entries.begin(), entries.end(), [](const auto& x, const auto& y) { return x.second.second > y.second.second; });
  const size_t shown = entries.size() > 14 ? 13 : entries.size();
  for (size_t k = 0; k < shown; ++k)
    ras.legend.emplace_back(entries[k].first + (entries[k].first.rfind("outside", 0) == 0 ? "" : share(entries[k].second.second)),
                            entries[k].second.first);
  if (shown < entries.size()) ras.legend.emplace_back("+" + std::to_string(entries.size() - shown) + " more types", Rgb{255, 255, 255});

  fig.title = "Basins of attraction, " + model_title(r.model.law) + " model";
  std::string par = "a = " + r.model.a.text();
  if (r.model.law == Law::constant) par += ", ε = " + r.model.eps.text();
  if (r.model.law == Law::veldep) par += ", c = " + r.model.c.text();
  fig.subtitle = par + "; " + std::to_string(r.nx) + " x " + std::to_string(r.ny) + " points, " +
                 std::to_string(r.classify.transient) + " + " + std::to_string(r.classify.steps) + " steps, " +
                 r.precision.text();
  fig.xlabel = "θ₀ (initial phase)";
  fig.ylabel = "v₀ (initial velocity)";
  fig.width = 1000;
  fig.height = 700;
  fig.metadata = png_metadata(prov, fig.title);

  nlohmann::ordered_json s;
  s["command"] = "basin";
  s["grid"] = {r.nx, r.ny};
  s["theta_range"] = {r.t0.text(), r.t1.text()};
  s["v_range"] = {r.v0.text(), r.v1.text()};  // the default is the trapping region
  s["points"] = items.size();
  s["points_in_phase_space"] = items.size() - static_cast<size_t>(outside);
  nlohmann::ordered_json types = nlohmann::ordered_json::array();
  for (const auto& [k, n] : order) {
    nlohmann::ordered_json t{{"class", k.first}, {"period", k.second}, {"points", n}, {"fraction", n / total}};
    // The legend's share: of the points in the phase space (none for the points outside).
    t["share_of_phase_space"] = k.first == "outside" || inside <= 0 ? nlohmann::ordered_json() : nlohmann::ordered_json(n / inside);
    types.push_back(t);
  }
  s["attractors"] = types;
  s["precision"] = r.precision.text();
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

}  // namespace

const std::set<std::string>& basin_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"grid", "theta-range", "v-range", "transient", "steps", "max-period", "recheck-factor", "precision",
              "certify", "max-bits"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_basin(const Options& o, const RunFlags& f) {
  const BasinRequest req = basin_request(o);
  if (req.certify) return run_point_grid<CertifiedBasinGrid>("basin", o, f, req, req.nx * req.ny, 16, certified_basin_finish);
  return run_point_grid<BasinGrid>("basin", o, f, req, req.nx * req.ny, 256, basin_finish);
}

Command add_basin(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("basin", "Basins of attraction: classify a grid of initial conditions; CSV, PNG, JSON");
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("grid", "NxM: N phases by M velocities (cell centres), 1..8192 each (default 100x100)");
  opts->add("theta-range", "T0:T1 within [0, 1] (default 0:1)");
  opts->add("v-range", "V0:V1, the initial velocities (default: the trapping region, as scan; needed for elastic; points below the wall velocity are 'outside')");
  add_classify_options(*opts);
  opts->add("precision", kPointPrecisionHelp);
  opts->add("max-bits", "With --certify: the last MPFI precision of the schedule interval:double, 64, 128, ..., 64..4096 (default 256)");
  opts->add_flag("certify",
                "Certify every point (constant, elastic, or veldep without collapse): sticking period, trapping set, 'not_trapped' (veldep, elastic: "
                "the orbit certified through every step) or 'undecided', with double's answer "
                "beside it; also writes PREFIX-artefacts.png, the map of where double is wrong");
  auto flags = add_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "basin", basin_keys()), opts->collected());
    return run_basin(o, run_flags_from(o, *flags, argv_text));
  };
  return {sub, run};
}

}  // namespace bouncer::cli
