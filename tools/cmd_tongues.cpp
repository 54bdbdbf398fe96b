// bouncer tongues: the paper's Arnold-tongue figure (fig. arnold). The curves are the
// library's (analysis/tongues.hpp: arnold_tongues, exact rationals); this file reads the
// options and writes the CSV (a, eps and theta_min as exact fractions, plus the nearest
// doubles for plotting tools), the picture (solid where the proved family fills (0, 1/2),
// dashed where it does not, the switch marked) and the summary; with --wall sine the sine
// wall's tongues (sine_tongues, closed forms in MPFR).
#include <cstdio>
#include <memory>

#include "bouncer/analysis/tongues.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

TonguesRequest tongues_request(const Options& o) {
  TonguesRequest r;
  r.p_max = integer_from(o, "p-max", 1, 50, 10);
  r.samples = integer_from(o, "samples", 16, 100000, 600);
  if (o.has("a-range")) {
    r.a_range = parse_range("a-range", o.get("a-range"));
    if (r.a_range.first < Decimal::from_int(0) || r.a_range.second > Decimal::from_int(1000000))
      throw InputError("a-range", "must lie in [0, 1e6] (got '" + o.get("a-range") + "')");
  }
  if (o.has("eps-range")) {
    r.eps_range = parse_range("eps-range", o.get("eps-range"));
    if (r.eps_range.first < Decimal::from_int(0) || r.eps_range.second > Decimal::from_int(1))
      throw InputError("eps-range", "must lie in [0, 1] (got '" + o.get("eps-range") + "')");
  }
  return r;
}

std::string dbl(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

Series line(std::string label, Rgb color, bool dashed) {
  Series s;
  s.label = std::move(label);
  s.color = color;
  s.lines = true;
  s.dashed = dashed;
  s.markers = false;
  return s;
}

// Either wall's figure frame (the window in (a, eps)), summary and files.
void write_tongues(const TonguesRequest& r, const char* wall, long points, nlohmann::ordered_json curves, const std::string& csv,
                   Figure& fig, const RunFlags& f, const Provenance& prov) {
  fig.xlabel = parameter_label(Parameter::a);
  fig.ylabel = parameter_label(Parameter::eps);
  fig.x_min = r.a_range.first.approx();
  fig.x_max = r.a_range.second.approx();
  fig.y_min = r.eps_range.first.approx();
  fig.y_max = r.eps_range.second.approx();
  fig.width = 1000;
  fig.height = 760;
  fig.legend_below = true;  // the keys of the marks and line styles: the plot keeps the figure's width
  fig.metadata = png_metadata(prov, fig.title);
  nlohmann::ordered_json s;
  s["command"] = "tongues";
  s["wall"] = wall;
  s["p_max"] = r.p_max;
  s["a_range"] = {r.a_range.first.text(), r.a_range.second.text()};
  s["eps_range"] = {r.eps_range.first.text(), r.eps_range.second.text()};
  s["points"] = points;
  s["curves"] = std::move(curves);
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

void finish(const TonguesRequest& r, const Tongues& tongues, const RunFlags& f, const Provenance& prov) {
  std::string csv = "p,a,eps,theta_min,full,a_double,eps_double\n";
  Figure fig;
  Series switches;
  switches.label = "switch: ε = 1/(4p−1), a = 16/(2p−1)";
  switches.marker_size = 4;
  nlohmann::ordered_json curves = nlohmann::ordered_json::array();
  for (const TongueCurve& c : tongues.curves) {
    const long p = c.p;
    // The solid and dashed parts; the switch point belongs to both, so they join.
    Series solid = line("p = " + std::to_string(p), series_color(static_cast<int>(p - 1)), false), dashed = solid;
    solid.end_label = true;  // named at its end: ten curves need more than colours
    dashed.dashed = true;
    for (const TonguePoint& q : c.points) {
      const double a = nearest_double(q.a), e = nearest_double(q.eps);
      csv += std::to_string(p) + ',' + q.a.get_str() + ',' + q.eps.get_str() + ',' + q.theta_min.get_str() + ',' +
             (q.full ? "yes" : "no") + ',' + dbl(a) + ',' + dbl(e) + '\n';
      for (Series* s : {q.full ? &solid : nullptr, !q.full || q.at_switch ? &dashed : nullptr, q.at_switch ? &switches : nullptr})
        if (s) s->x.push_back(a), s->y.push_back(e);
    }
    // The curve is named once, at its end (on the solid part if any), and only for p <= 20.
    if (solid.x.size() >= 2 || p > 20) dashed.label.clear();
    dashed.end_label = true;
    if (p > 20) solid.label.clear();
    for (Series* s : {&solid, &dashed})
      if (s->x.size() >= 2) fig.series.push_back(std::move(*s));
    nlohmann::ordered_json j;
    j["p"] = p;
    j["points"] = c.points.size();
    j["switch_eps"] = c.switch_eps.get_str();
    j["switch_a"] = c.switch_a.get_str();
    curves.push_back(j);
  }
  if (!switches.x.empty()) fig.series.push_back(std::move(switches));
  fig.series.push_back(line("solid: θ* fills (0, 1/2)", Rgb{110, 110, 110}, false));
  fig.series.push_back(line("dashed: θ* > 1/2 − 2pε/(1+ε) > 0", Rgb{110, 110, 110}, true));
  fig.title = "Period-p fixed points (eq. 5): a = 8(1+ε)/(p(1−ε))";
  fig.subtitle = "p = 1.." + std::to_string(r.p_max) + "; family θ* in (max(0, 1/2 − 2pε/(1+ε)), 1/2), proved";
  write_tongues(r, "triangle", tongues.points, std::move(curves), csv, fig, f, prov);
}

// The sine wall's tongues (analysis/tongues.hpp: sine_tongues): for each p the period
// doubling a_pd (solid) and the saddle-node a_sn (dashed) in one colour; the stable period-p
// orbit lives between them.
void finish_sine(const TonguesRequest& r, const SineTongues& tongues, const RunFlags& f, const Provenance& prov) {
  using Tr = ScalarTraits<Mpfr>;
  std::string csv = "p,eps,a_pd,a_sn,eps_double,a_pd_double,a_sn_double\n";
  Figure fig;
  nlohmann::ordered_json curves = nlohmann::ordered_json::array();
  for (const SineTongueCurve& c : tongues.curves) {
    const long p = c.p;
    Series pd = line("p = " + std::to_string(p), series_color(static_cast<int>(p - 1)), false), sn = pd;
    pd.end_label = true;
    sn.label.clear();
    sn.dashed = true;
    for (const SineTonguePoint& q : c.points) {
      const double e = nearest_double(q.eps), apd = Tr::to_double(q.a_pd), asn = Tr::to_double(q.a_sn);
      csv += std::to_string(p) + ',' + q.eps.get_str() + ',' + Tr::to_string(q.a_pd) + ',' + Tr::to_string(q.a_sn) + ',' +
             dbl(e) + ',' + dbl(apd) + ',' + dbl(asn) + '\n';
      pd.x.push_back(apd), pd.y.push_back(e);
      sn.x.push_back(asn), sn.y.push_back(e);
    }
    if (p > 20) pd.label.clear();
    for (Series* s : {&pd, &sn})
      if (s->x.size() >= 2) fig.series.push_back(std::move(*s));
    nlohmann::ordered_json j;
    j["p"] = p;
    j["points"] = c.points.size();
    curves.push_back(j);
  }
  fig.series.push_back(line("solid: period doubling a_PD", Rgb{110, 110, 110}, false));
  fig.series.push_back(line("dashed: saddle-node a_SN (stable between the two)", Rgb{110, 110, 110}, true));
  fig.title = "Sine wall: stable period-p orbits for a_PD < a < a_SN";
  fig.subtitle = "p = 1.." + std::to_string(r.p_max) + "; flights of p periods, closed forms (tongues of positive width)";
  write_tongues(r, "sine", tongues.points, std::move(curves), csv, fig, f, prov);
}

const std::set<std::string>& tongues_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = single_run_keys();
    k.insert({"p-max", "a-range", "eps-range", "samples", "wall"});
    return k;
  }();
  return keys;
}

}  // namespace

CommandRunner setup_tongues(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  opts->add("p-max", "Curves p = 1..P, integer in [1, 50] (default 10)");
  opts->add("a-range", "Window of a, LO:HI within [0, 1e6] (default 0:30)");
  opts->add("eps-range", "Window of eps, LO:HI within [0, 1] (default 0:1)");
  opts->add("samples", "Points per curve, integer in [16, 100000] (default 600), uniform in a (sine: in eps)");
  opts->add("wall", "triangle (default: the eq. 5 curves) | sine (the sine wall's tongues between a_PD and a_SN)");
  auto flags = add_single_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "tongues", tongues_keys()), opts->collected());
    const TonguesRequest req = tongues_request(o);
    const std::string wall = o.get_or("wall", "triangle");
    if (wall != "triangle" && wall != "sine")
      throw InputError("wall", "tongues draws the triangle's eq. 5 curves or the sine wall's tongues (allowed: triangle, sine; got '" +
                                   wall + "')");
    const RunFlags f = run_flags_from(o, *flags, argv_text);
    Provenance prov;
    prov.command = "tongues";
    prov.inputs = job_options(o).inputs();
    prov.precision = "exact rationals";  // GMP throughout; no scalar type is involved (bits 0)
    prov.bits = 0;
    prov.decimal_note = "exact rational arithmetic: a, eps and theta_min are exact fractions; "
                        "the *_double columns are the nearest doubles";
    prov.invocation = argv_text;
    if (wall == "sine") {
      prov.precision = "mpfr:" + std::to_string(kSineTongueBits);
      prov.bits = kSineTongueBits;
      prov.decimal_note = "eps exact fractions; a_pd and a_sn computed in MPFR at " + std::to_string(kSineTongueBits) +
                          " bits and printed to round-trip; the *_double columns are the nearest doubles";
      finish_sine(req, sine_tongues(req), f, prov);
      return 0;
    }
    finish(req, arnold_tongues(req), f, prov);
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
