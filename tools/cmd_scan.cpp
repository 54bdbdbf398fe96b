// bouncer scan: parameter-space scans (paper figs. paramspace1 and paramspace2). Over a
// P x Q grid of (a, eps) (constant model) or (a, c) (velocity-dependent model), K x K
// initial conditions per parameter point (paper: 10 x 10, in the trapping region) are
// classified, and the solution types are counted. The picture shows the fraction of one
// type (--show; default "regular" = fixed + periodic, the paper's "periodic solutions").
#include <cmath>
#include <memory>
#include <sstream>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/trapping.hpp"
#include "bouncer/verify/certified_point.hpp"
#include "bouncer/verify/sticking.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

// Count columns, in CSV order.
// The count columns, in CSV order: the classifier's classes (their names from
// analysis/classify.hpp), then outside (a start below the wall).
const std::vector<std::string>& count_names() {
  static const std::vector<std::string> n = [] {
    std::vector<std::string> v;
    for (OrbitClass c : {OrbitClass::fixed, OrbitClass::periodic, OrbitClass::sticking, OrbitClass::quasiperiodic,
                         OrbitClass::chaotic, OrbitClass::unbounded, OrbitClass::effective_sticking,
                         OrbitClass::transient_chaos, OrbitClass::undecided})
      v.emplace_back(name(c));
    v.emplace_back("outside");
    return v;
  }();
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
  // --certify (constant, or veldep without collapse; double twin): per parameter point, the
  // certificate of the orbit of one exact start (--theta, --v; default the release state
  // (1/2, 4), which every sticking orbit of the triangle wall passes through) at the exact
  // double (a, eps) or (a, c).
  bool certify = false;
  InitialCondition start;
  CertifyPointOptions cert;
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
  } else if (law == Law::constant && r.y1 == Decimal::from_int(1) && o.get_or("certify", "false") != "true") {
    throw InputError("v-range", "is needed when eps reaches 1 (the trapping region 4(1+3eps)/(1-eps) is unbounded)");
  }
  r.classify = classify_options_from(o);
  r.precision = point_precision(o);
  r.show = o.get_or("show", "regular");
  bool known = r.show == "regular";
  for (const auto& n : count_names()) known = known || n == r.show;
  if (!known) {
    std::string allowed = "regular";
    for (const std::string& n : count_names()) allowed += ", " + n;
    throw InputError("show", "must be one of " + allowed);
  }
  // The analytic fixed-point curves (paper eq. 5) belong to the (a, eps) plane of the
  // constant model: drawn there by default, never elsewhere.
  const std::string curves = o.get_or("curves", r.y == "eps" ? "fixed-points" : "none");
  if (curves != "fixed-points" && curves != "none")
    throw InputError("curves", "must be fixed-points or none (got '" + curves + "')");
  if (curves == "fixed-points" && r.y != "eps")
    throw InputError("curves", "fixed-points needs --model constant (the curves are in the (a, eps) plane)");
  r.fixed_point_curves = curves == "fixed-points";
  const std::string certify = o.get_or("certify", "false");
  if (certify != "true" && certify != "false") throw InputError("certify", "must be true or false (got '" + certify + "')");
  r.certify = certify == "true";
  for (const char* k : {"max-bits", "theta", "v"})
    if (o.has(k) && !r.certify) throw InputError(k, "is only used with --certify (the certified start; the classified starts are --ics, --theta-range, --v-range)");
  if (r.certify) {
    require_certified_model(r.model, "scan");
    if (r.precision.kind != Precision::Kind::double_)
      throw InputError("precision", "with --certify the twin run is double (the artefact map compares double with the "
                                    "certified answer); got '" + r.precision.text() + "'");
    Options m = o;
    m.set("theta", o.get_or("theta", "0.5"));
    m.set("v", o.get_or("v", "4"));
    r.start = start_from(m, r.model);  // the wall does not depend on (a, eps): valid at every point
    r.cert.max_steps = r.classify.transient + r.classify.steps;
    r.cert.max_bits = integer_from(o, "max-bits", 64, 4096, 256);
    r.cert.max_attractor_period = r.classify.max_period;
  }
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

  // Item i: a index i mod P, y index i / P (cell centres).
  std::string item(long i) const {
    const T a = cell_centre(a0, a1, i % r.p, r.p), y = cell_centre(y0, y1, i / r.p, r.q);
    const Model<T> m = with_parameter(with_parameter(base, Parameter::a, a), parse_parameter("y", r.y), y);
    const ImpactMap<T> map(m);
    // Default: the trapping region of this point (model/trapping.hpp), from the wall's fastest
    // upward velocity; eps = 1 needs --v-range (refused when the request is read).
    const T vlo = r.v_given ? v0 : wall_up_speed(m.wall);
    const T vhi = r.v_given ? v1 : trapping_top(m).value();
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

// --certify: item i is "a,eps|c,class,period,certified_steps,scalar,double_class,double_period,
// agreement" with a and eps the exact decimals of the double cell centres.
template <class T>
struct CertifiedScanGrid {
  const ScanRequest& r;
  ScanGrid<T> twin;
  explicit CertifiedScanGrid(const ScanRequest& req) : r(req), twin(req) {}

  std::string item(long i) const {
    using Tr = ScalarTraits<T>;
    const T a = cell_centre(twin.a0, twin.a1, i % r.p, r.p), y = cell_centre(twin.y0, twin.y1, i / r.p, r.q);
    const std::string a_text = exact_decimal(mpq_class(Tr::to_double(a))), y_text = exact_decimal(mpq_class(Tr::to_double(y)));
    ModelSpec spec = r.model;
    spec.a = *Decimal::parse(a_text);
    (r.y == "eps" ? spec.eps : spec.c) = *Decimal::parse(y_text);
    ReleaseCache releases;  // parameters differ from point to point: nothing to share
    const CertifiedPoint c = certify_point(spec, r.start, r.cert, releases);
    const ImpactMap<T> map(with_parameter(with_parameter(twin.base, Parameter::a, a), parse_parameter("y", r.y), y));
    const Classification d = classify<T>(map, make_state<T>(r.start, r.precision.bits), r.classify);
    std::ostringstream out;
    out << a_text << ',' << y_text << ',' << c.cls << ',' << c.period << ',' << c.certified_steps << ',' << c.scalar << ','
        << name(d.cls) << ',' << d.period << ',' << compare_with_certified(c, name(d.cls), d.period);
    return out.str();
  }
};

void certified_scan_finish(const ScanRequest& r, const std::vector<std::string>& items, const RunFlags& f,
                           const Provenance& prov) {
  CertifiedMap m;
  m.x_name = "a";
  m.y_name = r.y;
  m.nx = r.p;
  m.ny = r.q;
  m.x0 = r.a0.value();
  m.x1 = r.a1.value();
  m.y0 = r.y0.value();
  m.y1 = r.y1.value();
  m.title = "Certified parameter scan, " + model_title(r.model.law) + " model: each coloured pixel is proved";
  m.subtitle = "the orbit of (θ₀, v₀) = (" + r.start.theta.text() + ", " + r.start.v.text() + "); " + std::to_string(r.p) +
               " x " + std::to_string(r.q) + " exact parameter points, " + std::to_string(r.cert.max_steps) +
               " steps, interval:double then MPFI up to " + std::to_string(r.cert.max_bits) + " bits";
  m.xlabel = "a";
  m.ylabel = r.y == "eps" ? "ε" : "c";
  m.max_steps = r.cert.max_steps;
  m.max_bits = r.cert.max_bits;
  m.collapses = r.model.law == Law::constant;
  m.summary["command"] = "scan";
  m.summary["certified"] = true;
  m.summary["grid"] = {r.p, r.q};
  m.summary["a_range"] = {r.a0.text(), r.a1.text()};
  m.summary[r.y + "_range"] = {r.y0.text(), r.y1.text()};
  m.summary["start"] = {r.start.theta.text(), r.start.v.text()};
  m.twin_precision = r.precision.text();
  certified_map_finish(m, items, f, prov);
}

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
        s.x.push_back(zx(bouncer::paper::fixed_point_a(e, pp)));
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
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

}  // namespace

const std::set<std::string>& scan_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"a-range", "eps-range", "c-range", "grid", "ics", "theta-range", "v-range", "transient", "steps",
              "max-period", "recheck-factor", "precision", "show", "curves", "certify", "max-bits", "theta", "v"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_scan(const Options& o, const RunFlags& f) {
  const ScanRequest req = scan_request(o);
  if (req.certify) return run_point_grid<CertifiedScanGrid>("scan", o, f, req, req.p * req.q, 4, certified_scan_finish);
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
  opts->add("v-range", "Initial velocities V0:V1 (default: the trapping region of each point, from the wall velocity 4 to its top; README, Claims row 5)");
  add_classify_options(*opts);
  opts->add("precision", kPointPrecisionHelp);
  opts->add("show", "Picture: fraction of regular (default: fixed + periodic) | fixed | periodic | sticking | chaotic | ...");
  opts->add("curves", "Over the picture: fixed-points (default for --model constant: the paper's eq. 5, "
                      "a = 8(1+eps)/(p(1-eps)), p = 1..10) | none");
  opts->add("theta", "With --certify: the start's phase, an exact decimal (default 0.5, the release state)");
  opts->add("v", "With --certify: the start's velocity (default 4, the release state)");
  opts->add("max-bits", "With --certify: the last MPFI precision of the schedule interval:double, 64, 128, ..., 64..4096 (default 256)");
  opts->add_flag("certify",
                "Certify each parameter point (constant, or veldep without collapse): the exact orbit of --theta, --v at the exact double (a, eps) or (a, c), "
                "with double's answer beside it; also writes PREFIX-artefacts.png, the map of where double is wrong");
  auto flags = add_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "scan", scan_keys()), opts->collected());
    return run_scan(o, run_flags_from(o, *flags, argv_text));
  };
  return {sub, run};
}

}  // namespace bouncer::cli
