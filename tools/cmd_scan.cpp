// bouncer scan: parameter-space scans (paper figs. paramspace1 and paramspace2). Over a
// P x Q grid of (a, eps) (constant model) or (a, c) (velocity-dependent model), K x K
// initial conditions per parameter point (paper: 10 x 10, in the trapping region) are
// classified, and the solution types are counted. The picture shows the fraction of one
// type (--show; default "regular" = fixed + periodic, the paper's "periodic solutions").
#include <cmath>
#include <memory>
#include <sstream>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/model/impact_map.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

// Count columns, in CSV order.
const std::vector<std::string>& count_names() {
  static const std::vector<std::string> n{"fixed",     "periodic",           "sticking",        "quasiperiodic",
                                          "chaotic",   "unbounded",          "effective_sticking", "transient_chaos",
                                          "undecided", "outside"};
  return n;
}

struct ScanRequest {
  ModelSpec model;
  std::string y;  // eps or c
  Decimal a0, a1, y0, y1;
  long p = 20, q = 20, k = 10;
  Decimal t0, t1;
  bool v_given = false;
  Decimal v0, v1;
  ClassifyOptions classify;
  Precision precision;
  std::string show = "regular";
  bool fixed_point_curves = false;  // --curves fixed-points: the paper's eq. 5 over the picture
};

ScanRequest scan_request(const Options& given) {
  ScanRequest r;
  Options o = given;
  std::tie(r.a0, r.a1) = parse_range("a-range", o.get("a-range"));
  const Law law = parse_law("model", o.get("model"));
  if (law == Law::elastic) throw InputError("model", "scan needs an inelastic model (constant: a x eps; veldep: a x c)");
  r.y = law == Law::constant ? "eps" : "c";
  const std::string yr = r.y + "-range";
  std::tie(r.y0, r.y1) = parse_range(yr, o.get(yr));
  if (o.has("a")) throw InputError("a", "is scanned: give --a-range instead");
  if (o.has(r.y)) throw InputError(r.y, "is scanned: give --" + yr + " instead");
  // Validate both ends of both ranges through the model's own checks.
  for (const Decimal& a : {r.a0, r.a1})
    for (const Decimal& y : {r.y0, r.y1}) {
      Options m = o;
      m.set("a", a.text());
      m.set(r.y, y.text());
      try {
        r.model = model_from(m);
      } catch (const InputError& e) {
        throw InputError(e.field == "a" ? "a-range" : e.field == r.y ? yr : e.field, e.what());
      }
    }
  std::tie(r.p, r.q) = parse_grid("grid", o.get_or("grid", "20x20"), 4096);
  r.k = integer_from(o, "ics", 1, 1000, 10);
  std::tie(r.t0, r.t1) = parse_range("theta-range", o.get_or("theta-range", "0:1"));
  if (r.t0 < Decimal::from_int(0) || r.t1 > Decimal::from_int(1)) throw InputError("theta-range", "must lie in [0, 1]");
  if (o.has("v-range")) {
    r.v_given = true;
    std::tie(r.v0, r.v1) = parse_range("v-range", o.get("v-range"));
    if (r.v1.approx() > 1e15 || r.v0.approx() < -1e15) throw InputError("v-range", "must lie within +-1e15");
  } else if (law == Law::constant && r.y1 == Decimal::from_int(1)) {
    throw InputError("v-range", "is needed when eps reaches 1 (the trapping region 4(1+3eps)/(1-eps) is unbounded)");
  }
  r.classify = classify_options_from(o);
  r.precision = point_precision(o);
  r.show = o.get_or("show", "regular");
  bool known = r.show == "regular";
  for (const auto& n : count_names()) known = known || n == r.show;
  if (!known) throw InputError("show", "must be regular or one of fixed, periodic, sticking, quasiperiodic, chaotic, unbounded, effective_sticking, transient_chaos, undecided");
  // The analytic fixed-point curves (paper eq. 5) belong to the (a, eps) plane of the
  // constant model: drawn there by default, never elsewhere.
  const std::string curves = o.get_or("curves", r.y == "eps" ? "fixed-points" : "none");
  if (curves != "fixed-points" && curves != "none")
    throw InputError("curves", "must be fixed-points or none (got '" + curves + "')");
  if (curves == "fixed-points" && r.y != "eps")
    throw InputError("curves", "fixed-points needs --model constant (the curves are in the (a, eps) plane)");
  r.fixed_point_curves = curves == "fixed-points";
  return r;
}

template <class T>
struct ScanGrid {
  using Tr = ScalarTraits<T>;
  const ScanRequest& r;
  Model<T> base;
  T a0, a1, y0, y1, t0, t1, v0, v1;
  T num(const Decimal& d) const { return Tr::from_decimal(d.text(), r.precision.bits); }
  explicit ScanGrid(const ScanRequest& req)
      : r(req), base(make_model<T>(req.model, req.precision.bits)), a0(num(req.a0)), a1(num(req.a1)), y0(num(req.y0)),
        y1(num(req.y1)), t0(num(req.t0)), t1(num(req.t1)), v0(num(req.v_given ? req.v0 : req.a0)),
        v1(num(req.v_given ? req.v1 : req.a1)) {}

  // Upper end of the trapping region (paper sec. II.C), the default top of the v range.
  T v_upper(const Model<T>& m) const {
    using std::exp;
    using std::log;
    const T one = Tr::from_int(1, r.precision.bits);
    if (m.law == Law::constant) return (m.eps * 3 + 1) * 4 / (1 - m.eps);
    // veldep: 4 [2 coth(2^(4/5) / c^(3/5)) - 1], coth x = (e^(2x) + 1)/(e^(2x) - 1).
    const T x = exp(log(one * 2) * 4 / 5) / Tr::pow_3_5(m.c);
    const T e = exp(2 * x);
    return 4 * (2 * (e + 1) / (e - 1) - 1);
  }

  // Item i: a index i mod P, y index i / P (cell centres).
  std::string item(long i) const {
    const T a = cell_centre(a0, a1, i % r.p, r.p), y = cell_centre(y0, y1, i / r.p, r.q);
    const Model<T> m = with_parameter(with_parameter(base, Parameter::a, a), parse_parameter("y", r.y), y);
    const ImpactMap<T> map(m);
    const T vlo = r.v_given ? v0 : Tr::from_int(4, r.precision.bits);
    const T vhi = r.v_given ? v1 : v_upper(m);
    std::vector<long> count(count_names().size(), 0);
    for (long j = 0; j < r.k * r.k; ++j) {
      const T theta = cell_centre(t0, t1, j % r.k, r.k), v = cell_centre(vlo, vhi, j / r.k, r.k);
      const int seg = m.wall.segment_of(theta);
      size_t slot;
      if (v < m.wall.velocity[seg]) {
        slot = count_names().size() - 1;
      } else {
        const Classification c = classify<T>(map, State<T>{theta, v}, r.classify);
        slot = static_cast<size_t>(std::find(count_names().begin(), count_names().end(), name(c.cls)) - count_names().begin());
        if (slot >= count.size() - 1) slot = count.size() - 2;  // unknown name: undecided
      }
      ++count[slot];
    }
    std::ostringstream out;
    out << Tr::to_string(a) << ',' << Tr::to_string(y);
    for (long n : count) out << ',' << n;
    return out.str();
  }
};

void finish(const ScanRequest& r, const std::vector<std::string>& items, const RunFlags& f, const Provenance& prov) {
  std::string csv = "a," + r.y;
  for (const auto& n : count_names()) csv += "," + n;
  csv += ",total\n";
  const size_t nc = count_names().size();
  std::vector<long> totals(nc, 0);
  std::vector<double> frac(items.size(), 0), regular(items.size(), 0), chaotic(items.size(), 0);
  for (size_t i = 0; i < items.size(); ++i) {
    std::istringstream ls(items[i]);
    std::string cell;
    std::getline(ls, cell, ',');
    std::getline(ls, cell, ',');
    std::vector<long> c(nc, 0);
    long total = 0;
    for (size_t k = 0; k < nc; ++k) {
      std::getline(ls, cell, ',');
      c[k] = std::atol(cell.c_str());
      totals[k] += c[k];
      total += c[k];
    }
    csv += items[i] + "," + std::to_string(total) + "\n";
    long hit = 0;
    for (size_t k = 0; k < nc; ++k)
      if (r.show == count_names()[k] || (r.show == "regular" && (k == 0 || k == 1))) hit += c[k];
    const long inside = total - c[nc - 1];
    frac[i] = inside > 0 ? static_cast<double>(hit) / inside : 0;
    regular[i] = inside > 0 ? static_cast<double>(c[0] + c[1]) / inside : 0;
    chaotic[i] = inside > 0 ? static_cast<double>(c[4]) / inside : 0;
  }
  ImageFigure fig;
  Raster& ras = fig.raster;
  ras.nx = static_cast<int>(r.p);
  ras.ny = static_cast<int>(r.q);
  // The window in the coordinates of its axes (relative to an offset for a zoom).
  const auto [zx, zy] = set_exact_window(ras, r.a0.value(), r.a1.value(), r.y0.value(), r.y1.value());
  ras.pixels.resize(items.size());
  const bool paper = f.picture.palette == Palette::paper;
  const Rgb paper_green{0, 150, 40};
  for (size_t i = 0; i < items.size(); ++i) {
    const long col = static_cast<long>(i) % r.p, row = r.q - 1 - static_cast<long>(i) / r.p;
    Rgb c = viridis_color(frac[i]);
    if (paper) {  // the paper's look: black where the starts are regular, green where chaotic
      auto ch = [&](double green) {
        return static_cast<std::uint8_t>(std::lround(255 * (1 - regular[i] - chaotic[i]) + green * chaotic[i]));
      };
      c = Rgb{ch(paper_green.r), ch(paper_green.g), ch(paper_green.b)};
    }
    ras.pixels[static_cast<size_t>(row * r.p + col)] = c;
  }
  const std::string shown = r.show == "regular" ? "fixed + periodic" : r.show;
  if (paper) {
    ras.legend = {{"fixed + periodic (black: all starts)", Rgb{0, 0, 0}},
                  {"chaotic (green: all starts)", paper_green},
                  {"neither (sticking, ...)", Rgb{255, 255, 255}}};
  } else {
    for (int i = 0; i < 64; ++i) ras.colorbar.push_back(viridis_color(i / 63.0));
    ras.colorbar_lo = 0;
    ras.colorbar_hi = 1;
    ras.colorbar_label = "share of starts " + (r.show == "regular" ? std::string("fixed + periodic") : r.show);
  }
  if (r.fixed_point_curves) {
    // Paper eq. 5: the fixed points of the constant model exist at a = 8(1+eps)/(p(1-eps)),
    // p = 1..10 (fig. paramspace1's curves), drawn over the window in its axis coordinates.
    const double e0 = r.y0.value().get_d(), e1 = std::min(r.y1.value().get_d(), 1 - 1e-9);
    const Rgb blue = paper ? Rgb{30, 70, 210} : Rgb{86, 180, 233};
    for (int pp = 1; pp <= 10; ++pp) {
      Series s;
      if (pp == 1) s.label = "eq. 5, p = 1…10: a = 8(1+ε)/(p(1−ε))";
      s.color = blue;
      s.lines = true;
      s.markers = false;
      for (int k = 0; k <= 400; ++k) {
        const double e = e0 + (e1 - e0) * k / 400.0;
        s.x.push_back(zx(8 * (1 + e) / (pp * (1 - e))));
        s.y.push_back(zy(e));
      }
      fig.overlay.push_back(s);
    }
  }
  fig.title = "Parameter scan: " + shown + " solutions";
  fig.subtitle = model_title(r.model.law) + " model; " + std::to_string(r.p) + " x " + std::to_string(r.q) +
                 " parameters, " + std::to_string(r.k) + " x " + std::to_string(r.k) + " initial conditions, " +
                 std::to_string(r.classify.transient) + " + " + std::to_string(r.classify.steps) + " steps, " +
                 r.precision.text();
  fig.xlabel = "a";
  fig.ylabel = r.y == "eps" ? "ε" : "c";
  fig.metadata = png_metadata(prov, fig.title);

  nlohmann::ordered_json s;
  s["command"] = "scan";
  s["grid"] = {r.p, r.q};
  s["initial_conditions"] = r.k * r.k;
  s["show"] = r.show;
  nlohmann::ordered_json t;
  for (size_t k = 0; k < nc; ++k) t[count_names()[k]] = totals[k];
  s["totals"] = t;
  s["precision"] = r.precision.text();
  write_outputs(f, prov, csv, [&](const std::string& path, ImageFormat fmt) { write_figure(path, fig, fmt, f.picture.render); }, s);
}

}  // namespace

const std::set<std::string>& scan_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"a-range", "eps-range", "c-range", "grid", "ics", "theta-range", "v-range", "transient", "steps",
              "max-period", "recheck-factor", "precision", "show", "curves"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_scan(const Options& o, const RunFlags& f) {
  const ScanRequest req = scan_request(o);
  return run_point_grid<ScanGrid>("scan", o, f, req, req.p * req.q, 16, finish);
}

Command add_scan(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("scan", "Parameter scan over (a, eps) or (a, c): solution types per point; CSV, PNG, JSON");
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("a-range", "A0:A1, the range of a (cell centres of --grid)");
  opts->add("eps-range", "E0:E1 within [0, 1], for --model constant");
  opts->add("c-range", "C0:C1, c > 0, for --model veldep");
  opts->add("grid", "PxQ parameter points (a by eps or c), 1..4096 each (default 20x20)");
  opts->add("ics", "K: K x K initial conditions per parameter point (default 10, as in the paper)");
  opts->add("theta-range", "Initial phases T0:T1 within [0, 1] (default 0:1)");
  opts->add("v-range", "Initial velocities V0:V1 (default: the trapping region [4, v_upper] of each point)");
  add_classify_options(*opts);
  opts->add("precision", kPointPrecisionHelp);
  opts->add("show", "Picture: fraction of regular (default: fixed + periodic) | fixed | periodic | sticking | chaotic | ...");
  opts->add("curves", "Over the picture: fixed-points (default for --model constant: the paper's eq. 5, "
                      "a = 8(1+eps)/(p(1-eps)), p = 1..10) | none");
  auto flags = add_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "scan", scan_keys()), opts->collected());
    return run_scan(o, run_flags_from(o, *flags, argv_text));
  };
  return {sub, run};
}

}  // namespace bouncer::cli
