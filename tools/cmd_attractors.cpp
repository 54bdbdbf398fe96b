// bouncer attractors: every attractor at a parameter point (run/attractors.hpp), with its
// basin share, its certificate (periodic orbits, sticking cycles) or exponent (aperiodic
// sets). This file reads the options, calls find_attractors and writes the outputs of
// io/attractors.hpp: PREFIX.json, PREFIX.csv (one row per start), PREFIX.png (the basins);
// without --out a readable summary on stdout. With --vary: sweep_attractors
// (run/attractors_sweep.hpp), the chains' shares per value, each periodic chain's branch
// continued and tied to its appearances and disappearances, and the stacked figure.
#include "bouncer/io/attractors.hpp"
#include "bouncer/io/requests/attractors.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& attractors_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"starts", "sampling", "theta-range", "v-range", "cells", "recurrences", "attractor-steps", "hits", "lost-steps",
              "max-steps", "lyapunov-steps", "transient", "steps", "max-period", "recheck-factor", "no-certify", "max-bits",
              "precision", "threads", "vary", "range", "values", "no-branches"});
    const std::set<std::string> single = single_run_keys();
    k.insert(single.begin(), single.end());
    return k;
  }();
  return keys;
}

// Refuses (exit 2, naming --starts or --cells) a request whose starts and recurrence grid
// would not fit in the memory available (picture_common.hpp check_memory_need, as basin's
// grids): per start its label, its (theta, v) as numbers and its CSV row, about 400 bytes as
// a basin's point (check_grid_memory: 3 x 96 + 112); per cell of the recurrence grid its owner
// and its share of the attractors' cell lists, about 16 bytes.
void check_attractors_memory(const AttractorsRequest& r, bool quiet) {
  const double starts = static_cast<double>(r.nx) * static_cast<double>(r.ny);
  const double cells = static_cast<double>(r.cells_theta) * static_cast<double>(r.cells_v);
  const double need_starts = starts * (3 * 96 + 112), need_cells = cells * 16;
  const bool by_starts = need_starts >= need_cells;
  check_memory_need("attractors", by_starts ? "starts" : "cells",
                    "this request of " + std::to_string(static_cast<long long>(starts)) + " starts and " +
                        std::to_string(static_cast<long long>(cells)) + " cells",
                    need_starts + need_cells, false, quiet,
                    by_starts ? "give fewer --starts" : "give fewer --cells");
}

// --vary: the attractors at each value of the range, chained (run/attractors_sweep.hpp).
int run_sweep(const Options& o, const AttractorsSweepRequest& req, const FlagSet& flags, const std::string& invocation) {
  const RunFlags f = run_flags_from(o, flags, invocation);
  check_attractors_memory(req.point, f.quiet);
  const Provenance prov = provenance_for("attractors", job_options(o), req.point.precision, f.invocation);
  GridOptions run;
  run.threads = f.threads;
  run.progress = !f.quiet && stderr_is_terminal();
  const AttractorsSweepResult r = sweep_attractors(req, run);
  if (!f.out && !f.json) {
    command_out() << prov.as_comment_lines() << attractors_sweep_text(r);
    return 0;
  }
  ImageFigure fig = attractors_sweep_figure(r, f.picture.palette);
  fig.metadata = png_metadata(prov, fig.title);
  write_outputs(f, prov, attractors_sweep_csv(r),
                [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); },
                nlohmann::ordered_json::parse(attractors_sweep_json(r)));
  return 0;
}

int run_attractors(const Options& o, const FlagSet& flags, const std::string& invocation) {
  if (const auto sweep = attractors_sweep_request(o)) return run_sweep(o, *sweep, flags, invocation);
  const AttractorsRequest req = attractors_request(o);
  const RunFlags f = run_flags_from(o, flags, invocation);
  check_attractors_memory(req, f.quiet);
  const Provenance prov = provenance_for("attractors", job_options(o), req.precision, f.invocation);
  GridOptions run;
  run.threads = f.threads;
  run.progress = !f.quiet && stderr_is_terminal();
  const AttractorsResult r = find_attractors(req, run);
  if (!f.out && !f.json) {
    command_out() << prov.as_comment_lines() << attractors_text(r);
    return 0;
  }
  ImageFigure fig = attractors_figure(r, f.picture.palette);
  fig.metadata = png_metadata(prov, fig.title);
  write_outputs(f, prov, attractors_csv(r),
                [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); },
                nlohmann::ordered_json::parse(attractors_json(r)));
  return 0;
}

}  // namespace

CommandRunner setup_attractors(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("starts", "NxM starts: N phases by M velocities (cell centres, as basin), 1..8192 each, N*M <= 4e6 (default 100x100)");
  opts->add("sampling", "grid (default: the cell centres, as basin) | halton (N*M points of the Halton sequence, low discrepancy)");
  opts->add("theta-range", "T0:T1 within [0, 1] (default 0:1)");
  opts->add("v-range", "V0:V1, the starts' velocities (default: the trapping region; needed for elastic)");
  opts->add("cells", "NxM cells of the recurrence grid over theta in [0, 1) and v up to the trapping top, 16..4096 each (default 512x512)");
  opts->add("recurrences", "Own cells revisited this many steps in a row: a new attractor, integer in [1, 1e6] (default 100)");
  opts->add("attractor-steps", "A new attractor is followed this many steps, its cells recorded, integer in [10, 1e7] (default 1000)");
  opts->add("hits", "Steps in a row on an aperiodic attractor's cells that decide a start, integer in [1, 1e6] (default 8)");
  opts->add("lost-steps", "Steps in a row above the trapping top that make an escape, integer in [1, 1e6] (default 20)");
  opts->add("max-steps", "Steps per start before it is undecided, integer in [100, 1e9] (default 200000)");
  opts->add("lyapunov-steps", "Steps of an aperiodic attractor's exponent, integer in [100, 1e9] (default 100000)");
  add_classify_options(*opts);
  opts->add_flag("no-certify", "Do not prove the periodic attractors and sticking cycles (Krawczyk)");
  opts->add("max-bits", "The certificates' last MPFI precision, 64..4096 (default 1024)");
  opts->add("precision", kPointPrecisionHelp);
  opts->add("vary", "Follow the attractors across a parameter: a | eps (constant model) | c (veldep model); "
                    "writes the stacked basin shares against it");
  opts->add("range", "With --vary: LO:HI (decimals, LO < HI), both ends included");
  opts->add("values", "With --vary: values of the parameter, integer in [2, 1000] (default 11), equally spaced");
  opts->add_flag("no-branches", "With --vary: do not continue the periodic chains' branches (by default each is continued, "
                                 "its ends proved unless --no-certify, and tied to where the chain appears and disappears)");
  opts->add("threads", "Worker threads, integer >= 1 (default: all cores); results do not depend on it");
  auto flags = add_single_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "attractors", attractors_keys()), opts->collected());
    return run_attractors(o, *flags, argv_text);
  };
  return run;
}

}  // namespace bouncer::cli
