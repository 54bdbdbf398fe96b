// bouncer basin: basins of attraction (run/basin.hpp). Every point of an N x M grid of
// initial conditions is classified (fixed, periodic q, sticking k, quasiperiodic, chaotic,
// unbounded, effective sticking, transient chaos, undecided) and coloured by its class and
// period (io/grid_figures.hpp); points below the wall's velocity are "outside". --certify:
// every point certified, with double's answer beside it and the artefact map.
// This file reads the options, runs the library's BasinGrid through the tiles, and writes.
#include "bouncer/run/basin.hpp"
#include "bouncer/io/requests/grids.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

// --confirm: the JSON summary's "confirm" (the artefact map is io/grid_figures.hpp basin_confirm_figure).
nlohmann::ordered_json confirm_summary(const BasinResult& b, long stride) {
  const BasinRequest& r = b.request;
  long n[3] = {0, 0, 0};
  nlohmann::ordered_json artefacts = nlohmann::ordered_json::array();
  for (size_t i = 0; i < b.cells.size(); ++i) {
    const AttractorCell& c = b.cells[i];
    if (!c.confirm) continue;
    ++n[static_cast<int>(*c.confirm)];
    if (*c.confirm == PrecisionVerdict::artefact)
      artefacts.push_back({{"theta", b.theta[i % static_cast<size_t>(r.nx)].digits},
                           {"v", b.v[i / static_cast<size_t>(r.nx)].digits},
                           {"class", name(c.cls)},
                           {"period", c.period},
                           {"check_class", name(c.check_cls)},
                           {"check_period", c.check_period},
                           {"differs_in", c.differs_in}});
  }
  return confirm_json(r.precision, r.confirm, r.classify,
                      {{"stride", stride},
                       {"rule", "the start at offset (min(s, n) - 1) / 2 of every s x s block of the grid, s = stride"},
                       {"starts", confirm_sample_units(r.nx, r.ny, stride)}},
                      n, std::move(artefacts));
}

void write_basin(const BasinResult& b, long stride, const RunFlags& f, const Provenance& prov) {
  const BasinRequest& r = b.request;
  const bool confirm = r.confirm.on;
  std::string csv = confirm ? "theta,v,class,period,confirm,check_class,check_period,differs_in\n" : "theta,v,class,period\n";
  long outside = 0;
  for (size_t i = 0; i < b.cells.size(); ++i) {
    const AttractorCell& c = b.cells[i];
    csv += b.theta[i % static_cast<size_t>(r.nx)].digits + ',' + b.v[i / static_cast<size_t>(r.nx)].digits + ',' +
           name(c.cls) + ',' + std::to_string(c.period);
    if (confirm)
      csv += c.confirm ? std::string(",") + name(*c.confirm) + ',' + name(c.check_cls) + ',' + std::to_string(c.check_period) +
                             ',' + c.differs_in
                       : std::string(",,,,");
    csv += '\n';
    outside += c.cls == OrbitClass::outside;
  }
  ImageFigure fig = basin_figure(b, f.picture.palette);
  fig.metadata = png_metadata(prov, fig.title);
  const double total = static_cast<double>(b.cells.size()), inside = total - static_cast<double>(outside);
  nlohmann::ordered_json s;
  s["command"] = "basin";
  s["grid"] = {r.nx, r.ny};
  s["theta_range"] = {r.theta_lo.text(), r.theta_hi.text()};
  s["v_range"] = {r.v_range->first.text(), r.v_range->second.text()};  // the default is the trapping region
  s["points"] = b.cells.size();
  s["points_in_phase_space"] = b.cells.size() - static_cast<size_t>(outside);
  nlohmann::ordered_json types = nlohmann::ordered_json::array();
  for (const ClassCount& k : attractor_census(b.cells)) {
    const bool out = k.cls == OrbitClass::outside;
    nlohmann::ordered_json t{{"class", name(k.cls)}, {"period", k.period}, {"points", k.points}, {"fraction", k.points / total}};
    // The legend's share: of the points in the phase space (none for the points outside).
    t["share_of_phase_space"] = out || inside <= 0 ? nlohmann::ordered_json() : nlohmann::ordered_json(k.points / inside);
    types.push_back(t);
  }
  s["attractors"] = types;
  s["precision"] = r.precision.text();
  std::vector<ExtraFigure> extra;
  if (confirm) {
    s["confirm"] = confirm_summary(b, stride);
    extra.push_back(extra_figure("artefacts", basin_confirm_figure(b, f.picture.palette), prov, f));
  }
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s,
                extra);
}

void write_certified_basin(const CertifiedBasinResult& b, const RunFlags& f, const Provenance& prov) {
  const BasinRequest& r = b.request;
  nlohmann::ordered_json s;
  s["command"] = "basin";
  s["certified"] = true;
  s["grid"] = {r.nx, r.ny};
  s["theta_range"] = {r.theta_lo.text(), r.theta_hi.text()};
  s["v_range"] = {r.v_range->first.text(), r.v_range->second.text()};
  write_certified_map(certified_map(b), b.theta, b.v, b.cells, s, r.precision.text(), f, prov);
}

}  // namespace

const std::set<std::string>& basin_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"grid", "theta-range", "v-range", "transient", "steps", "max-period", "recheck-factor", "precision",
              "certify", "max-bits", "confirm", "confirm-sample"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_basin(const Options& o, const RunFlags& f) {
  const BasinOptions b = basin_options(o);
  BasinGrid grid(b.request, b.certify);  // validates the request, resolves the v range
  const Provenance prov = provenance_for("basin", job_options(o), b.request.precision, f.invocation);
  if (b.certify) {
    if (const auto cells = run_cells<CertifiedCell>("basin", o, f, grid)) write_certified_basin(grid.certified_result(*cells), f, prov);
  } else if (const auto cells = run_cells<AttractorCell>("basin", o, f, grid)) {
    write_basin(grid.result(*cells), grid.confirm_stride(), f, prov);
  }
  return 0;
}

CommandRunner setup_basin(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("grid", "NxM: N phases by M velocities (cell centres), 1..8192 each (default 100x100)");
  opts->add("theta-range", "T0:T1 within [0, 1] (default 0:1)");
  opts->add("v-range", "V0:V1, the initial velocities (default: the trapping region, as scan; needed for elastic; points below the wall velocity are 'outside')");
  add_classify_options(*opts);
  opts->add("precision", kPointPrecisionHelp);
  add_grid_confirm_options(*opts, "start");
  opts->add("max-bits", "With --certify: the last MPFI precision of the schedule interval:double, 64, 128, ..., 64..4096 (default 256)");
  opts->add_flag("certify",
                "Certify every point (constant, elastic, or veldep without collapse): sticking period, trapping set, 'not_trapped' (veldep, elastic: "
                "the orbit certified through every step) or 'undecided', with double's answer "
                "beside it; also writes PREFIX-artefacts.png, the map of where double is wrong");
  auto flags = add_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "basin", basin_keys()), opts->collected());
    // A bare --confirm is recorded as a flag ("true"), so that provenance and audit rerun it.
    if (o.has("confirm") && o.get("confirm").empty()) o.set("confirm", "true");
    return run_basin(o, run_flags_from(o, *flags, argv_text));
  };
  return run;
}

}  // namespace bouncer::cli
