// bouncer portrait: phase portraits (theta_n, v_n) of several orbits, one colour each;
// --polar draws (phi = 2 pi theta, radius v), where the elastic model's branched Fermi
// acceleration (paper sec. III, a = 19) shows as straight branches. --theta-range and
// --v-range choose the window shown (a zoom, at any precision: points are placed from their
// exact values when a double cannot resolve the window).
#include <cmath>
#include <memory>
#include <sstream>

#include "bouncer/model/impact_map.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

struct PortraitRequest {
  ModelSpec model;
  std::vector<InitialCondition> initial;
  long steps = 1000, transient = 0;
  bool polar = false;
  Precision precision;
  std::optional<std::pair<Decimal, Decimal>> theta_window, v_window;  // the picture's window
};

PortraitRequest portrait_request(const Options& o) {
  PortraitRequest r;
  r.model = model_from(o);
  r.initial = initial_conditions_from(o, r.model);
  if (r.initial.size() > 1000) throw InputError("theta", "at most 1000 initial conditions");
  r.steps = integer_from(o, "steps", 1, 10000000, 1000);
  r.transient = integer_from(o, "transient", 0, 100000000, 0);
  if (static_cast<double>(r.steps) * static_cast<double>(r.initial.size()) > 2e7)
    throw InputError("steps", "orbits x steps must be at most 2e7 points");
  const std::string polar = o.get_or("polar", "false");
  if (polar != "true" && polar != "false") throw InputError("polar", "must be true or false");
  r.polar = polar == "true";
  for (const char* k : {"theta-range", "v-range"})
    if (r.polar && o.has(k)) throw InputError(k, "chooses the window of the (theta, v) picture, not of --polar");
  if (o.has("theta-range")) {
    r.theta_window = parse_range("theta-range", o.get("theta-range"));
    if (r.theta_window->first < Decimal::from_int(0) || r.theta_window->second > Decimal::from_int(1))
      throw InputError("theta-range", "must lie in [0, 1] (got '" + o.get("theta-range") + "')");
  }
  if (o.has("v-range")) {
    r.v_window = parse_range("v-range", o.get("v-range"));
    if (r.v_window->second.approx() > 1e15 || r.v_window->first.approx() < -1e15) throw InputError("v-range", "must lie within +-1e15");
  }
  r.precision = point_precision(o);
  return r;
}

template <class T>
std::string orbit_rows(const PortraitRequest& r, const ImpactMap<T>& map, long k) {
  using Tr = ScalarTraits<T>;
  State<T> s = make_state<T>(r.initial[static_cast<size_t>(k)], r.precision.bits);
  std::ostringstream out;
  long n = 0;
  try {
    for (; n < r.transient; ++n) s = map.step(s).next;
    if (r.transient == 0) out << k << ",0," << Tr::to_string(s.theta) << ',' << Tr::to_string(s.v) << ",start\n";
    for (long m = 0; m < r.steps; ++m, ++n) {
      const StepResult<T> st = map.step(s);
      s = st.next;
      out << k << ',' << n + 1 << ',' << Tr::to_string(s.theta) << ',' << Tr::to_string(s.v) << ',' << name(st.kind) << '\n';
    }
  } catch (const Undecided& u) {
    out << "# undecided: orbit " << k << " step " << n + 1 << ": " << u.what() << "\n";
  }
  return out.str();
}

// One axis of the (theta, v) picture: its window when given, and how values are placed.
struct PortraitAxis {
  AxisZoom zoom;
  double lo = -INFINITY, hi = INFINITY;  // a little beyond the window, in double
  explicit PortraitAxis(const std::optional<std::pair<Decimal, Decimal>>& w) {
    if (!w) return;
    zoom = AxisZoom(w->first.value(), w->second.value());
    lo = std::nextafter(std::nextafter(w->first.approx(), -INFINITY), -INFINITY);
    hi = std::nextafter(std::nextafter(w->second.approx(), INFINITY), INFINITY);
  }
  // The coordinate of a printed value; NaN when it lies outside a zoomed window (a zoom
  // places each point from its exact value, so points far outside are not converted).
  double operator()(const std::string& text, double approx) const {
    if (!zoom.active()) return approx;
    if (!(approx >= lo && approx <= hi)) return NAN;
    return zoom(exact_value(text));
  }
};

void finish(const PortraitRequest& r, const std::vector<std::string>& items, const RunFlags& f, const Provenance& prov) {
  std::string csv = "orbit,n,theta,v,event\n";
  Figure fig;
  long points = 0, undecided = 0;
  double vmax = 0;
  const double two_pi = 2 * std::acos(-1.0);
  const PortraitAxis ax(r.theta_window), ay(r.v_window);
  for (size_t k = 0; k < items.size(); ++k) {
    csv += items[k];
    Series s;
    s.color = items.size() == 1 ? Rgb{20, 20, 20} : category_color(static_cast<int>(k));
    s.marker_size = r.steps * items.size() > 20000 ? 0 : 1;
    if (k < 12) s.label = "θ₀ = " + r.initial[k].theta.text() + ", v₀ = " + r.initial[k].v.text();
    std::istringstream in(items[k]);
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      if (line[0] == '#') { ++undecided; continue; }
      std::istringstream ls(line);
      std::string cell[5];
      for (auto& c : cell) std::getline(ls, c, ',');
      const double th = std::strtod(cell[2].c_str(), nullptr), v = std::strtod(cell[3].c_str(), nullptr);
      vmax = std::max(vmax, v);
      if (r.polar) {
        s.x.push_back(v * std::cos(two_pi * th));
        s.y.push_back(v * std::sin(two_pi * th));
      } else {
        const double x = ax(cell[2], th), y = ay(cell[3], v);
        if (!std::isnan(x) && !std::isnan(y)) {
          s.x.push_back(x);
          s.y.push_back(y);
        }
      }
      ++points;
    }
    fig.series.push_back(std::move(s));
  }
  // Labels of starts with many digits (a zoom) need the width of the picture: legend below.
  for (const Series& s : fig.series) fig.legend_below = fig.legend_below || s.label.size() > 40;
  if (items.size() > 12) {
    Series more;
    more.label = "... " + std::to_string(items.size() - 12) + " more orbits";
    more.color = Rgb{160, 160, 160};
    fig.series.push_back(more);
  }
  fig.title = std::string(r.polar ? "Polar phase portrait, " : "Phase portrait, ") + model_title(r.model.law) + " model";
  std::string par = "a = " + r.model.a.text();
  if (r.model.law == Law::constant) par += ", ε = " + r.model.eps.text();
  if (r.model.law == Law::veldep) par += ", c = " + r.model.c.text();
  fig.subtitle = par + "; " + std::to_string(items.size()) + (items.size() == 1 ? " orbit, " : " orbits, ") +
                 std::to_string(r.steps) + " steps" + (r.transient ? " after " + std::to_string(r.transient) : "") + ", " +
                 r.precision.text();
  if (r.polar) {
    fig.xlabel = "v cos(2πθ)";
    fig.ylabel = "v sin(2πθ)";
    fig.equal_aspect = true;
    fig.height = 800;
    fig.width = 1000;
  } else {
    fig.xlabel = "θ (phase of impact)";
    fig.ylabel = "v (velocity after impact)";
    fig.x_min = 0;
    fig.x_max = 1;
    if (r.theta_window) {
      fig.x_min = ax.zoom(r.theta_window->first.value());
      fig.x_max = ax.zoom(r.theta_window->second.value());
      fig.x_offset = ax.zoom.offset();
    }
    if (r.v_window) {
      fig.y_min = ay.zoom(r.v_window->first.value());
      fig.y_max = ay.zoom(r.v_window->second.value());
      fig.y_offset = ay.zoom.offset();
    }
  }
  fig.metadata = png_metadata(prov, fig.title);
  nlohmann::ordered_json s;
  s["command"] = "portrait";
  s["orbits"] = items.size();
  s["points"] = points;
  s["undecided_orbits"] = undecided;
  s["max_v"] = vmax;
  s["polar"] = r.polar;
  if (r.theta_window) s["theta_range"] = {r.theta_window->first.text(), r.theta_window->second.text()};
  if (r.v_window) s["v_range"] = {r.v_window->first.text(), r.v_window->second.text()};
  s["precision"] = r.precision.text();
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

}  // namespace

const std::set<std::string>& portrait_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "steps", "transient", "polar", "precision", "theta-range", "v-range"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_portrait(const Options& o, const RunFlags& f) {
  const PortraitRequest req = portrait_request(o);
  PictureJob job;
  job.command = "portrait";
  job.job = job_options(o);
  job.plan.items = static_cast<long>(req.initial.size());
  job.plan.tile_items = 1;
  job.item_bytes = 60.0 * static_cast<double>(req.steps) + 64;  // an orbit: `steps` rows
  job.size_field = "steps";
  const Provenance prov = provenance_for("portrait", job.job, req.precision, f.invocation);
  return with_scalar(req.precision, [&](auto tag) -> int {
    using T = typename decltype(tag)::type;
    if constexpr (ScalarTraits<T>::is_interval) {
      throw InputError("precision", "interval precision is not supported here");
    } else {
      auto map = std::make_shared<ImpactMap<T>>(make_model<T>(req.model, req.precision.bits));
      job.item = [map, &req](long k) { return orbit_rows<T>(req, *map, k); };
      const auto items = run_job(job, f);
      if (items) finish(req, *items, f, prov);
      return 0;
    }
  });
}

Command add_portrait(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("portrait", "Phase portrait (theta, v) of several orbits; --polar for Fermi acceleration");
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add_list("theta", "Initial phases in [0, 1), a comma list (one orbit each)");
  opts->add_list("v", "Initial velocities, as many as theta, each >= the wall velocity at its theta");
  opts->add("steps", "Steps drawn per orbit (default 1000)");
  opts->add("transient", "Steps discarded first (default 0)");
  opts->add("precision", kPointPrecisionHelp);
  opts->add("theta-range", "Window T0:T1 within [0, 1] of the picture (default 0:1); any width, e.g. 1e-20 at mpfr:256");
  opts->add("v-range", "Window V0:V1 of the picture (default: the data)");
  opts->add_flag("polar", "Polar picture: angle 2 pi theta, radius v");
  auto flags = add_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "portrait", portrait_keys()), opts->collected());
    return run_portrait(o, run_flags_from(o, *flags, argv_text));
  };
  return {sub, run};
}

}  // namespace bouncer::cli
