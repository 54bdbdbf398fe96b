// bouncer trajectory: the particle's height and the wall's height against time (the paper's
// fig. realtime), from a state (theta, v) of the impact map, over a few wall periods. The
// trajectory is the library's (analysis/trajectory.hpp: trace_trajectory); this file reads
// the options and writes the CSV, the picture and the summary. Every number is printed so
// that it reads back to the same value in its type; the picture is drawn from the same points.
#include <algorithm>
#include <memory>

#include "bouncer/analysis/trajectory.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

TrajectoryRequest trajectory_request(const Options& o) {
  TrajectoryRequest r;
  r.model = model_from(o);
  r.start.theta = parse_decimal("theta", o.get_or("theta", "0.3"));
  r.start.v = parse_decimal("v", o.get_or("v", "12"));
  validate(r.model, r.start, "theta", "v");
  r.periods = integer_from(o, "periods", 1, 100, 3);
  r.samples = integer_from(o, "samples", 8, 10000, 400);
  r.precision = point_precision(o);
  return r;
}

Series series(const char* label, Rgb color, bool lines, int marker_size = 2) {
  Series s;
  s.label = label;
  s.color = color;
  s.lines = lines;
  s.markers = !lines;
  s.marker_size = marker_size;
  return s;
}

template <class T>
void finish(const TrajectoryRequest& r, const Trajectory<T>& tr, const RunFlags& f, const Provenance& prov) {
  using Tr = ScalarTraits<T>;
  std::string csv = "t,particle,wall,event,step\n";
  Series wall = series("wall f(t)", Rgb{120, 120, 120}, true), particle = series("particle", Rgb{20, 20, 20}, true);
  Series hits = series("impacts (and the start)", Rgb{30, 70, 210}, false, 4);
  Series stuck = series("sticking: riding the wall", Rgb{215, 25, 28}, false, 2);
  Series chat = series("chatter (collapse)", Rgb{250, 110, 100}, false, 1);
  double ymax = 1, ymin = -1;  // the wall's range at least (any --wall profile)
  for (const TracePoint<T>& q : tr.points) {
    const double td = Tr::to_double(q.t), yd = Tr::to_double(q.particle), wd = Tr::to_double(q.wall);
    ymin = std::min({ymin, wd, yd});
    ymax = std::max({ymax, wd, yd});
    csv += Tr::to_string(q.t) + ',' + Tr::to_string(q.particle) + ',' + Tr::to_string(q.wall) + ',' + name(q.event) +
           ',' + std::to_string(q.step) + '\n';
    wall.x.push_back(td);
    wall.y.push_back(wd);
    particle.x.push_back(td);
    particle.y.push_back(yd);
    const TraceEvent e = q.event;  // impacts as the particle, the ride as the wall
    Series* mark = e == TraceEvent::impact || e == TraceEvent::start ? &hits
                   : e == TraceEvent::chatter                        ? &chat
                   : e == TraceEvent::flight                         ? nullptr
                                                                     : &stuck;
    if (mark) mark->x.push_back(td), mark->y.push_back(mark == &stuck ? wd : yd);
  }
  if (!tr.stopped.empty()) csv += "# stopped: " + tr.stopped + "\n";
  Figure fig;
  fig.series.push_back(std::move(wall));
  fig.series.push_back(std::move(particle));
  if (!stuck.x.empty()) fig.series.push_back(std::move(stuck));
  if (!chat.x.empty()) fig.series.push_back(std::move(chat));
  fig.series.push_back(std::move(hits));
  fig.title = "Particle and wall heights against time, " + model_name(r.model);
  std::string par = "a = " + r.model.a.text();
  if (r.model.law == Law::constant) par += ", ε = " + r.model.eps.text();
  if (r.model.law == Law::veldep) par += ", c = " + r.model.c.text();
  const long n = tr.impacts;
  fig.subtitle = par + "; from θ₀ = " + r.start.theta.text() + ", v₀ = " + r.start.v.text() + "; " + std::to_string(n) +
                 (n == 1 ? " impact" : " impacts") +
                 (tr.sticking_steps ? ", " + std::to_string(tr.sticking_steps) + " sticking" : "") + ", " +
                 r.precision.text();
  fig.xlabel = "t (wall periods; θ = t mod 1)";
  fig.ylabel = "height (units: A = 1)";
  fig.x_min = tr.points.empty() ? 0 : Tr::to_double(tr.points.front().t);
  fig.x_max = fig.x_min + static_cast<double>(r.periods);
  fig.y_min = ymin - 0.06 * (ymax - ymin);
  fig.y_max = ymax + 0.05 * (ymax - ymin);
  fig.width = 1000;
  fig.height = 640;
  fig.legend_below = true;
  fig.metadata = png_metadata(prov, fig.title);
  nlohmann::ordered_json s;
  s["command"] = "trajectory";
  s["periods"] = r.periods;
  s["samples_per_period"] = r.samples;
  s["rows"] = tr.points.size();
  s["steps"] = tr.steps;
  s["impacts"] = tr.impacts;
  s["sticking_steps"] = tr.sticking_steps;
  s["max_height"] = ymax;
  if (!tr.stopped.empty()) s["stopped"] = tr.stopped;
  s["precision"] = r.precision.text();
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

const std::set<std::string>& trajectory_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "periods", "samples", "precision"});
    const std::set<std::string> run = single_run_keys();
    k.insert(run.begin(), run.end());
    return k;
  }();
  return keys;
}

int run_trajectory(const Options& o, const RunFlags& f) {
  const TrajectoryRequest req = trajectory_request(o);
  const Provenance prov = provenance_for("trajectory", job_options(o), req.precision, f.invocation);
  return with_point_scalar(req.precision, [&](auto tag) -> int {
    using T = typename decltype(tag)::type;
    finish(req, trace_trajectory<T>(req), f, prov);
    return 0;
  });
}

}  // namespace

CommandRunner setup_trajectory(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("theta", "Phase of the start impact in [0, 1) (default 0.3; with --eps 0.5 --a 24 the eq. 5 fixed point)");
  opts->add("v", "Particle velocity after the start impact, >= the wall velocity at theta (default 12)");
  opts->add("periods", "Wall periods drawn, integer in [1, 100] (default 3)");
  opts->add("samples", "Samples per wall period, integer in [8, 10000] (default 400); impacts and corners are added exactly");
  opts->add("precision", kPointPrecisionHelp);
  auto flags = add_single_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "trajectory", trajectory_keys()), opts->collected());
    return run_trajectory(o, run_flags_from(o, *flags, argv_text));
  };
  return run;
}

}  // namespace bouncer::cli
