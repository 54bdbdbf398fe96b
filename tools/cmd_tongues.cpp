// bouncer tongues: the paper's Arnold-tongue figure (fig. arnold). The period-p fixed
// points of eq. 5 (flight of exactly p wall periods, launched and landing on the rising
// wall at the same phase theta*) have v* = a p / 2 (back at the same height after time p)
// and v* = 4(1+eps)/(1-eps) (eq. 2 with v^- = -v*, fdot = 4), so they lie on the curves
//     a = 8 (1 + eps) / (p (1 - eps)),   p = 1, 2, ...
// in the (a, eps) plane. proofs/fixed_point_family.cpp proved (README Claims, row 1) that
// the family is theta* in (max(0, 1/2 - 2p eps/(1+eps)), 1/2): the whole (0, 1/2) iff
// eps >= 1/(4p-1), i.e. a <= 16/(2p-1) on the curve. Each curve is drawn solid where the
// whole interval exists and dashed where only part does, with the switch marked.
//
// Everything is exact: points are taken uniformly in a within the window (exact rationals),
// eps = (a p - 8)/(a p + 8) is the inverse of the formula, and the CSV gives a, eps and
// theta_min as exact fractions (plus doubles for plotting tools).
#include <gmpxx.h>
#include <mpfr.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <memory>

#include "bouncer/analysis/periodic.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

struct TonguesRequest {
  long p_max = 10, samples = 600;
  std::pair<Decimal, Decimal> a_range{Decimal::from_int(0), Decimal::from_int(30)};
  std::pair<Decimal, Decimal> eps_range{Decimal::from_int(0), Decimal::from_int(1)};
};

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

// Eq. 5 and its proved family (analysis/periodic.hpp), exactly.
mpq_class a_of(const mpq_class& eps, long p) { return paper::fixed_point_a(eps, p); }
mpq_class eps_of(const mpq_class& a, long p) { return paper::fixed_point_eps(a, p); }
mpq_class theta_min_of(const mpq_class& eps, long p) { return fixed_point_theta_min(eps, p); }
std::string text(const mpq_class& q) { return q.get_str(); }
// The nearest double (mpq_class::get_d truncates).
double nearest(const mpq_class& q) {
  mpfr_t x;
  mpfr_init2(x, 53);
  mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDN);
  const double d = mpfr_get_d(x, MPFR_RNDN);
  mpfr_clear(x);
  return d;
}
std::string dbl(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

struct Point {
  mpq_class a, eps;
  bool full = false;
};

// The curve of period p inside the window, or nothing: points uniform in a, plus the
// switch point eps = 1/(4p-1) when it is inside.
std::vector<Point> curve(const TonguesRequest& r, long p) {
  const mpq_class alo = r.a_range.first.value(), ahi = r.a_range.second.value();
  const mpq_class elo = r.eps_range.first.value(), ehi = r.eps_range.second.value();
  // eps(a) increases with a; eps < 1 for every finite a, and eps >= 0 iff a >= 8/p.
  mpq_class lo = alo, hi = ahi;
  const mpq_class a_at_elo = a_of(elo, p);
  if (lo < a_at_elo) lo = a_at_elo;
  if (ehi < 1) {
    const mpq_class a_at_ehi = a_of(ehi, p);
    if (a_at_ehi < hi) hi = a_at_ehi;
  }
  std::vector<Point> out;
  if (!(lo < hi)) return out;
  const mpq_class eps_switch(1, 4 * p - 1);
  const mpq_class a_switch(16, 2 * p - 1);
  bool switch_done = !(lo < a_switch && a_switch < hi);
  const long n = r.samples;
  for (long i = 0; i < n; ++i) {
    const mpq_class a = lo + (hi - lo) * i / (n - 1);
    if (!switch_done && a_switch < a) {
      out.push_back({a_switch, eps_switch, true});
      switch_done = true;
    }
    const mpq_class e = eps_of(a, p);
    out.push_back({a, e, e >= eps_switch});
  }
  return out;
}

void finish(const TonguesRequest& r, const RunFlags& f, const Provenance& prov) {
  std::string csv = "p,a,eps,theta_min,full,a_double,eps_double\n";
  Figure fig;
  const double ax0 = r.a_range.first.approx(), ax1 = r.a_range.second.approx();
  const double ey0 = r.eps_range.first.approx(), ey1 = r.eps_range.second.approx();
  Series switches;
  switches.label = "switch: ε = 1/(4p-1), a = 16/(2p-1)";
  switches.color = Rgb{0, 0, 0};
  switches.marker_size = 4;
  nlohmann::ordered_json curves = nlohmann::ordered_json::array();
  long points = 0;
  for (long p = 1; p <= r.p_max; ++p) {
    const std::vector<Point> pts = curve(r, p);
    const Rgb color = category_color(static_cast<int>(p - 1));
    std::vector<double> sx_full, sy_full, sx_part, sy_part;
    for (const Point& q : pts) {
      const double a = nearest(q.a), e = nearest(q.eps);
      csv += std::to_string(p) + ',' + text(q.a) + ',' + text(q.eps) + ',' + text(theta_min_of(q.eps, p)) + ',' +
             (q.full ? "yes" : "no") + ',' + dbl(a) + ',' + dbl(e) + '\n';
      // The switch point belongs to both pieces, so they join.
      if (q.full) {
        sx_full.push_back(a);
        sy_full.push_back(e);
      }
      if (!q.full || q.eps == mpq_class(1, 4 * p - 1)) {
        sx_part.push_back(a);
        sy_part.push_back(e);
      }
      if (q.eps == mpq_class(1, 4 * p - 1)) {
        switches.x.push_back(a);
        switches.y.push_back(e);
      }
    }
    points += static_cast<long>(pts.size());
    const std::string label = "p = " + std::to_string(p);
    // The curve's solid and dashed parts; the legend names p once (on the solid part if any).
    auto add_part = [&](std::vector<double> x, std::vector<double> y, bool dashed, bool labelled) {
      if (x.size() < 2) return;
      Series s;
      s.label = labelled && p <= 12 ? label : "";
      s.color = color;
      s.lines = true;
      s.dashed = dashed;
      s.markers = false;
      s.x = std::move(x);
      s.y = std::move(y);
      fig.series.push_back(std::move(s));
    };
    const bool solid_part = sx_full.size() >= 2;
    add_part(std::move(sx_full), std::move(sy_full), false, true);
    add_part(std::move(sx_part), std::move(sy_part), true, !solid_part);
    nlohmann::ordered_json c;
    c["p"] = p;
    c["points"] = pts.size();
    c["switch_eps"] = "1/" + std::to_string(4 * p - 1);
    c["switch_a"] = text(mpq_class(16, 2 * p - 1));
    curves.push_back(c);
  }
  if (!switches.x.empty()) fig.series.push_back(std::move(switches));
  Series solid, dash;
  solid.label = "solid: θ* fills (0, 1/2)";
  dash.label = "dashed: θ* > 1/2 - 2pε/(1+ε) > 0";
  for (Series* s : {&solid, &dash}) {
    s->color = Rgb{110, 110, 110};
    s->lines = true;
    s->markers = false;
  }
  dash.dashed = true;
  fig.series.push_back(std::move(solid));
  fig.series.push_back(std::move(dash));
  fig.title = "Period-p fixed points (eq. 5): a = 8(1+ε)/(p(1-ε))";
  fig.subtitle = "p = 1.." + std::to_string(r.p_max) + "; family θ* in (max(0, 1/2 - 2pε/(1+ε)), 1/2), proved";
  fig.xlabel = "a (dimensionless gravity)";
  fig.ylabel = "ε (restitution)";
  fig.x_min = ax0;
  fig.x_max = ax1;
  fig.y_min = ey0;
  fig.y_max = ey1;
  fig.width = 1000;
  fig.height = 760;
  fig.legend_below = true;  // twelve entries: the plot keeps the figure's width
  fig.metadata = png_metadata(prov, fig.title);
  nlohmann::ordered_json s;
  s["command"] = "tongues";
  s["p_max"] = r.p_max;
  s["a_range"] = {r.a_range.first.text(), r.a_range.second.text()};
  s["eps_range"] = {r.eps_range.first.text(), r.eps_range.second.text()};
  s["points"] = points;
  s["curves"] = curves;
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

const std::set<std::string>& tongues_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = single_run_keys();
    k.insert({"p-max", "a-range", "eps-range", "samples"});
    return k;
  }();
  return keys;
}

}  // namespace

Command add_tongues(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "tongues", "Arnold tongues (fig. arnold): eq. 5 fixed-point curves in (a, eps), solid where the proved family fills (0, 1/2)");
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  opts->add("p-max", "Curves p = 1..P, integer in [1, 50] (default 10)");
  opts->add("a-range", "Window of a, LO:HI within [0, 1e6] (default 0:30)");
  opts->add("eps-range", "Window of eps, LO:HI within [0, 1] (default 0:1)");
  opts->add("samples", "Points per curve, integer in [16, 100000] (default 600), uniform in a");
  auto flags = add_single_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "tongues", tongues_keys()), opts->collected());
    const TonguesRequest req = tongues_request(o);
    const RunFlags f = run_flags_from(o, *flags, argv_text);
    Provenance prov;
    prov.command = "tongues";
    prov.inputs = job_options(o).inputs();
    prov.precision = "exact rationals";  // GMP throughout; no scalar type is involved (bits 0)
    prov.bits = 0;
    prov.decimal_note = "exact rational arithmetic: a, eps and theta_min are exact fractions; "
                        "the *_double columns are the nearest doubles";
    prov.invocation = argv_text;
    finish(req, f, prov);
    return 0;
  };
  return {sub, run};
}

}  // namespace bouncer::cli
