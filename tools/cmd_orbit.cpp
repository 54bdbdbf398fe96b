// bouncer orbit: iterate the impact map from one or more initial conditions.
#include <filesystem>
#include <iostream>
#include <memory>

#include "bouncer/io/orbit.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

CommandRunner setup_orbit(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add_list("theta", "Initial phase(s) in [0, 1); a comma list runs several orbits");
  opts->add_list("v", "Initial velocity(ies) after impact, >= the wall velocity at theta (<= 1e15)");
  opts->add("steps", "Number of impact-map steps, integer >= 0 (default 10)");
  opts->add("precision", "double | long | dd | quad | mpfr:BITS | interval:BITS | interval:double (16 <= BITS <= 1048576)");
  opts->add("format", "csv (default) | json | table | npy (double only, with --out PATH: a NumPy float64 array in "
                      "PATH, its provenance, columns and codes in PATH.json)");
  opts->add("method", "Interval runs: lohner (default, as the certified commands: Lohner's QR method, "
                      "tight enclosures, about 5x the cost per step) | naive (iterate the box)");
  opts->add("every", "Print every K-th step (and the last), integer >= 1 (default 1)");
  opts->add("out", "Write to FILE (atomically) instead of stdout");
  auto force = std::make_shared<bool>(false);
  sub->add_flag("--force", *force, "Write more than 1e8 rows (about 10 GB of CSV) all the same");

  auto run = [opts, scene, force](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "orbit", orbit_keys()), opts->collected());
    const OrbitRequest req = orbit_request(o);
    // A guard against unbounded output (--steps 1e10 without --every wrote 32 GB before it
    // was stopped): the rows are counted before anything is written.
    const double rows = static_cast<double>(req.initial.size()) * (static_cast<double>(req.steps / req.every) + 1);
    if (rows > 1e8 && !*force)
      throw InputError("steps", "would print " + std::to_string(static_cast<long long>(rows)) +
                                    " rows (more than 1e8, about 10 GB of CSV): raise --every, or give --force");
    Provenance p = provenance_for("orbit", o, req.precision, argv_text);
    std::optional<std::string> out;
    if (o.has("out")) out = o.get("out");
    std::vector<OrbitOutcome> outcomes;
    if (req.format == Format::npy) {
      // PATH and PATH.json, all or none. The header names the rows of a run whose orbits all
      // complete; an orbit that stops early leaves fewer, and the header is rewritten in the
      // staging file (a pipe or device cannot be rewritten: that run fails, exit status 1).
      // PATH.json is written beside PATH: a device or pipe (/dev/null, /dev/stdout) would put
      // it among the devices.
      std::error_code ec;
      const auto st = std::filesystem::status(*out, ec);
      if (!ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
        throw InputError("out", "with --format npy must name a regular file (PATH and PATH.json are written), not a "
                                "device, pipe or directory: '" + *out + "'");
      const std::string json_path = *out + ".json";
      OutputSet set;
      set.reserve("out", *out);
      set.reserve("out", json_path);
      const long long planned = planned_orbit_rows(req);
      NpyOrbits npy;
      set.write(*out, [&](std::ostream& s) { npy = write_orbits_npy(req, planned, s); });
      if (npy.total_rows != planned) {
        const int fd = set.descriptor(*out);
        if (fd < 0)
          throw OutputError("an orbit stopped early, so '" + *out + "' holds " + std::to_string(npy.total_rows) +
                            " rows, not the " + std::to_string(planned) +
                            " its header names, and a pipe or device cannot be rewritten: write to a file");
        rewrite_npy_header(fd, *out, npy.total_rows, npy_orbit_columns().size());
      }
      const std::string sidecar = orbit_npy_sidecar(req, p, npy, std::filesystem::path(*out).filename().string());
      set.write(json_path, [&](std::ostream& s) { s << sidecar; });
      set.commit();
      outcomes = npy.outcomes;
    } else {
      write_atomically(out, [&](std::ostream& s) { outcomes = write_orbits(req, p, s); });
    }
    for (size_t i = 0; i < outcomes.size(); ++i) {
      const OrbitOutcome& oc = outcomes[i];
      if (oc.undecided)
        std::cerr << "bouncer orbit: orbit " << i << " stopped at step " << oc.steps_done + 1 << ": " << oc.reason
                  << " (not certified at " << req.precision.bits << " bits beyond step " << oc.steps_done << ")\n";
      if (oc.phase_lost_at >= 0)
        std::cerr << "bouncer orbit: orbit " << i << ": theta has no correct bit from step " << oc.phase_lost_at << "\n";
    }
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
