// bouncer portrait: phase portraits (theta_n, v_n) of several orbits, one colour each
// (run/portrait.hpp); --polar draws (phi = 2 pi theta, radius v), where the elastic model's
// branched Fermi acceleration (paper sec. III, a = 19) shows as straight branches.
// --theta-range and --v-range choose the window shown (a zoom, at any precision: points are
// placed from their exact values when a double cannot resolve the window; io/curve_figures.hpp).
// This file reads the options, runs the library's PortraitGrid through the tiles, and writes.
#include "bouncer/io/requests/portrait.hpp"
#include "bouncer/run/portrait.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

void write_portrait(const PortraitResult& p, const PortraitView& view, const RunFlags& f, const Provenance& prov) {
  std::string csv = "orbit,n,theta,v,event\n";
  for (size_t k = 0; k < p.orbits.size(); ++k) {
    const PortraitOrbit& o = p.orbits[k];
    const std::string orbit = std::to_string(k) + ',';
    for (const PortraitPoint& q : o.points)
      csv += orbit + std::to_string(q.n) + ',' + q.theta.digits + ',' + q.v.digits + ',' + (q.event ? name(*q.event) : "start") + '\n';
    if (o.undecided_step)
      csv += "# undecided: orbit " + std::to_string(k) + " step " + std::to_string(*o.undecided_step) + ": " + o.undecided_reason + "\n";
  }
  Figure fig = portrait_figure(p, view);
  fig.metadata = png_metadata(prov, fig.title);
  const PortraitCounts counts = portrait_counts(p);
  nlohmann::ordered_json s;
  s["command"] = "portrait";
  s["orbits"] = p.orbits.size();
  s["points"] = counts.points;
  s["undecided_orbits"] = counts.undecided_orbits;
  s["max_v"] = counts.max_v;
  s["polar"] = view.polar;
  if (view.theta_window) s["theta_range"] = {view.theta_window->first.text(), view.theta_window->second.text()};
  if (view.v_window) s["v_range"] = {view.v_window->first.text(), view.v_window->second.text()};
  s["precision"] = p.request.precision.text();
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
  const PortraitOptions p = portrait_options(o);
  const PortraitGrid grid(p.request);  // validates the request
  const Provenance prov = provenance_for("portrait", job_options(o), p.request.precision, f.invocation);
  if (const auto orbits = run_cells<PortraitOrbit>("portrait", o, f, grid, grid.item_bytes(), "steps"))
    write_portrait(grid.result(*orbits), p.view, f, prov);
  return 0;
}

CommandRunner setup_portrait(CLI::App* sub) {
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
  return run;
}

}  // namespace bouncer::cli
