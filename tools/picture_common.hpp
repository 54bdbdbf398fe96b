// Shared plumbing of the grid and picture commands (bifurcation, portrait, basin, scan,
// merge): run flags, the tiled parallel run with resume and shards, and the outputs
// PREFIX.csv, PREFIX.json and the pictures PREFIX.png/.pdf/.svg (--format), written all or
// none, each atomically.
//
// A job is defined by its options minus the run flags (threads, shard, out, quiet, json):
// those decide how the job runs, never what it computes. The job's options are saved in
// PREFIX.tiles/job.toml, so `bouncer merge PREFIX` can finish it from the saved tiles.
#pragma once

// GCC 12 at -O3 reports false "maybe uninitialized" warnings inside nlohmann::json.
#pragma GCC diagnostic push
#if !defined(__clang__)  // clang has no such warning (the fuzzing build, tests/fuzz/)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nlohmann/json.hpp>
#include <unistd.h>
#pragma GCC diagnostic pop

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "bouncer/io/grid_figures.hpp"
#include "bouncer/run/grid.hpp"
#include "bouncer/base/input.hpp"
#include "bouncer/io/plot.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/io/scene.hpp"
#include "bouncer/verify/sticking.hpp"
#include "cli_common.hpp"

namespace bouncer::cli {

// How a job runs (not part of its identity).
struct RunFlags {
  unsigned threads = 0;
  Shard shard;
  bool quiet = false;
  bool json = false;
  bool keep_tiles = false;
  std::optional<std::string> out;
  std::vector<std::string> merge_from;  // bouncer merge: tile directories to import
  std::optional<std::string> tiles_from;  // --tiles-from: a tile directory of the same job to reuse
  bool merge_only = false;              // bouncer merge: compute nothing
  bool force = false;                   // --force: run a grid larger than the memory available
  std::string invocation;
  Presentation picture;  // --format, --size, --dpi, --palette (how the picture looks)
  // What the run holds until its command returns (RunFlags is copied by value; the copies
  // share it): the lock on PREFIX.tiles/ and the output files reserved before the work, so
  // that another run on the same prefix is refused at its start and a path that cannot be
  // written is found before the computation. Released when the command ends, also in a host
  // process that runs many commands (the Python module).
  struct Hold {
    std::unique_ptr<PrefixLock> lock;
    OutputSet outputs;
  };
  std::shared_ptr<Hold> hold = std::make_shared<Hold>();
};

inline const std::set<std::string>& run_keys() {
  static const std::set<std::string> k{"threads", "shard", "out", "tiles-from"};
  return k;
}

// The options that define the job: everything but the run flags.
inline Options job_options(const Options& o) {
  Options j;
  for (const auto& [k, v] : o.values)
    if (!run_keys().count(k)) j.values[k] = v;
  return j;
}

// Flags and run options every grid command registers. The returned function reads them
// (after parsing) into RunFlags, validating --threads, --shard and --out.
struct FlagSet {
  bool quiet = false, json = false, keep_tiles = false, force = false;
};
inline std::shared_ptr<FlagSet> add_run_options(CLI::App* sub, OptionSet& opts) {
  auto f = std::make_shared<FlagSet>();
  opts.add("threads", "Worker threads, integer >= 1 (default: all cores); results do not depend on it");
  opts.add("shard", "Run only shard I/N of the tiles (0 <= I < N); needs --out; join with bouncer merge");
  opts.add("out", "Write PREFIX.csv, PREFIX.json and the pictures PREFIX.png/.pdf/.svg of --format (tiles in PREFIX.tiles/ while running)");
  opts.add("tiles-from", "Reuse the finished tiles of the same job from PREFIX.tiles/ (kept by --keep-tiles), e.g. to draw it "
                         "again with another --show or --out; needs --out");
  add_picture_options(opts);
  sub->add_flag("--quiet", f->quiet, "No progress bar on stderr");
  sub->add_flag("--json", f->json, "Print a JSON summary on stdout");
  sub->add_flag("--keep-tiles", f->keep_tiles, "Keep PREFIX.tiles/ after the outputs are written");
  sub->add_flag("--force", f->force, "Run a grid whose estimated memory exceeds what the machine has available");
  return f;
}

// The run options of a picture command that runs once, without tiles (trajectory, tongues):
// --out, the picture options, --json, and --quiet (accepted like the grid commands'; such a
// command prints no progress). The scene keys of these options: single_run_keys().
inline std::shared_ptr<FlagSet> add_single_run_options(CLI::App* sub, OptionSet& opts) {
  opts.add("out", "Write PREFIX.csv, PREFIX.json and the pictures (PREFIX.png, or --format; all or none)");
  add_picture_options(opts);
  auto f = std::make_shared<FlagSet>();
  sub->add_flag("--json", f->json, "Print a JSON summary on stdout");
  sub->add_flag("--quiet", f->quiet, "Accepted like the other picture commands (this one prints no progress)");
  return f;
}
inline std::set<std::string> single_run_keys() {
  std::set<std::string> k = picture_keys();
  k.insert("out");
  return k;
}

inline std::string tiles_dir(const std::string& prefix) { return prefix + ".tiles"; }

// MPI ranks: tools/mpi_ranks.cpp when the command-line tool is built with MPI, otherwise
// tools/mpi_none.cpp (one process; also the Python module, which never starts MPI).
struct Ranks {
  int rank = 0, size = 1;
};
Ranks mpi_ranks();
void mpi_barrier();

inline RunFlags run_flags_from(const Options& o, const FlagSet& f, const std::string& invocation) {
  RunFlags r;
  r.threads = static_cast<unsigned>(integer_from(o, "threads", 1, 4096, 0));
  if (o.has("shard")) r.shard = parse_shard("shard", o.get("shard"));
  if (o.has("out")) {
    r.out = o.get("out");
    check_prefix("out", *r.out, "-artefacts.json");  // the longest name made from it
  }
  if (!r.shard.all() && !r.out) throw InputError("shard", "needs --out PREFIX (the shard's tiles go to PREFIX.tiles/)");
  if (o.has("tiles-from")) {
    // Whether the tiles belong to this job is known only once the job's key is: run_job.
    if (!r.out) throw InputError("tiles-from", "needs --out PREFIX (the reused tiles are copied to PREFIX.tiles/)");
    const std::string from = tiles_dir(o.get("tiles-from"));
    if (!read_input_file_if_present("tiles-from", from + "/job.key", kMaxSceneBytes))
      throw InputError("tiles-from", "'" + from + "/' holds no tiles (keep them with --keep-tiles when that job runs)");
    r.tiles_from = from;
  }
  r.picture = presentation_from(o);
  // The pictures need their font: a missing font is an output failure found before the work.
  if (r.out && r.shard.all()) check_figure_font();
  r.quiet = f.quiet;
  r.json = f.json;
  r.keep_tiles = f.keep_tiles;
  r.force = f.force;
  r.invocation = invocation;
  // The outputs are reserved now, before the work (a shard writes none: merge does; under
  // mpirun rank 0 does): each path checked, its staging file created and locked.
  if (r.out && r.shard.all() && mpi_ranks().rank == 0)
    for (const std::string& path : output_paths(*r.out, r.picture)) r.hold->outputs.reserve("out", path);
  return r;
}

// A grid job: what to compute for each item.
struct PictureJob {
  std::string command;
  Options job;     // job_options(...) of the merged scene + command line
  GridPlan plan;
  std::function<std::string(long)> item;
  // Optional: items computed in groups of at most `group` (run_grid's grouped form), the
  // same texts as item() one by one (BasinGrid: orbits side by side).
  long group = 1;
  std::function<void(long, long, std::string*)> items;
  // About how many bytes one item's text takes (a CSV row of a point grid, a column of a
  // bifurcation diagram, an orbit of a portrait): the memory estimate of run_job.
  double item_bytes = 32;
  std::string size_field = "grid";  // the option that sets the number of items, for messages
};

// --confirm in a grid's JSON summary (basin, scan): the settings (the two precisions of
// check_precisions, the classifier's windows, the sample as `sample` describes it), then the
// verdict counts n[] (agrees, artefact, precision_dependent) and the artefacts' starts.
inline nlohmann::ordered_json confirm_json(const Precision& run, const GridConfirm& c, const ClassifyOptions& w,
                                           nlohmann::ordered_json sample, const long (&n)[3],
                                           nlohmann::ordered_json artefacts) {
  const std::pair<Precision, Precision> p = check_precisions(run, c.bits);
  nlohmann::ordered_json j;
  j["bits"] = c.bits;
  j["precisions"] = {p.first.text(), p.second.text()};
  j["transient"] = w.transient;
  j["steps"] = w.steps;
  j["recheck_factor"] = w.recheck_factor;
  nlohmann::ordered_json described{{"requested", c.sample == 0 ? nlohmann::ordered_json("all") : nlohmann::ordered_json(c.sample)}};
  for (auto& item : sample.items()) described[item.key()] = item.value();
  j["sample"] = std::move(described);
  const long confirmed = n[0] + n[1] + n[2];
  j["confirmed"] = confirmed;  // the sample's starts inside the phase space
  j["agrees"] = n[0];
  j["artefact"] = n[1];
  j["precision_dependent"] = n[2];
  j["confirmed_fraction"] = confirmed > 0 ? nlohmann::ordered_json(static_cast<double>(n[0]) / confirmed) : nlohmann::ordered_json();
  j["artefacts"] = std::move(artefacts);
  return j;
}

// Refuses (InputError naming the option that sets the job's size) a grid whose items, held
// in memory while it runs and again as the CSV and picture made from them, would need more
// than the memory available to this process (available_memory_bytes: MemAvailable, ulimit
// -v, a container's limit), unless --force; says how much a large one needs before it
// starts. The estimate, 3 bytes per byte of item text and 112 per item (string and tile
// overheads, the CSV copy, the pixel), was measured on basins: 186 bytes per point.
// The test itself, for any computation that holds `need` bytes: `what` names its size ("this
// job of 40000 items"), `field` the option that sets it, `remedy` what to do instead.
inline void check_memory_need(const std::string& command, const std::string& field, const std::string& what, double need,
                              bool force, bool quiet, const std::string& remedy) {
  const double have = available_memory_bytes();
  auto gb = [](double b) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(1) << b / 1e9;
    return s.str();
  };
  if (force || have <= 0 || need <= 0.9 * have) {
    if (need > 2e9 && !quiet)
      std::cerr << "bouncer " << command << ": " << what << " needs about " << gb(need) << " GB of memory (" << gb(have)
                << " GB available)\n";
    return;
  }
  throw InputError(field, what + " needs about " + gb(need) + " GB of memory, more than the " + gb(have) +
                              " GB available to this process: " + remedy);
}

inline void check_grid_memory(const PictureJob& j, const RunFlags& f) {
  if (!f.shard.all()) return;
  const double need = static_cast<double>(j.plan.items) * (3 * j.item_bytes + 112);
  check_memory_need(j.command, j.size_field, "this job of " + std::to_string(j.plan.items) + " items", need, f.force, f.quiet,
                    "make it smaller (or split it with --shard), or give --force");
}


// The key of the tiles: the job's options without the presentation (format, size, dpi,
// palette, curves), which change the picture, not a tile.
inline std::string job_key(const PictureJob& j) {
  Options computed;
  for (const auto& [k, v] : j.job.values)
    if (!presentation_keys().count(k)) computed.values[k] = v;
  return job_fingerprint("bouncer-grid-1\n" + computed.as_toml(j.command) + "items " + std::to_string(j.plan.items) +
                         " tile " + std::to_string(j.plan.tile_items) + "\n");
}

inline std::string missing_tiles_text(const std::vector<long>& miss, long tiles) {
  std::string list;
  for (size_t i = 0; i < miss.size() && i < 10; ++i) list += (i ? ", " : "") + std::to_string(miss[i]);
  if (miss.size() > 10) list += ", ...";
  return std::to_string(miss.size()) + " of " + std::to_string(tiles) + " tiles are missing (" + list +
         "): run the remaining shards first";
}

// The first line of a small file bouncer keeps in PREFIX.tiles/ (job.key), or "" when absent.
inline std::string first_line_of(const std::string& field, const std::string& path) {
  const std::optional<std::string> text = read_input_file_if_present(field, path, kMaxSceneBytes);
  if (!text) return "";
  return text->substr(0, text->find('\n'));
}

// True when a tile directory holds no saved tile (only its lock and job files).
inline bool holds_no_tiles(const std::string& dir) {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().filename().string().rfind("tile-", 0) == 0) return false;
  return !ec;
}

// Runs the job's grid. Returns the item texts when every tile is available; nothing for a
// shard run that leaves tiles for other shards (a message says so on stderr).
inline std::optional<std::vector<std::string>> run_job(const PictureJob& j, const RunFlags& f) {
  // Under mpirun the ranks are the shards: each computes its share of the tiles into the
  // shared PREFIX.tiles/, then rank 0 joins them as `bouncer merge` would.
  const Ranks world = mpi_ranks();
  if (world.size > 1) {
    if (!f.out) throw InputError("out", "is needed under mpirun (the ranks share PREFIX.tiles/)");
    if (!f.shard.all()) throw InputError("shard", "cannot be combined with mpirun (the ranks are the shards)");
    if (f.merge_only) throw InputError("merge", "runs in one process, not under mpirun");
  }
  check_grid_memory(j, f);
  GridOptions g;
  g.threads = f.threads;
  g.shard = world.size > 1 ? Shard{world.rank, world.size} : f.shard;
  g.job_key = job_key(j);
  if (f.tiles_from && first_line_of("tiles-from", *f.tiles_from + "/job.key") != g.job_key)
    throw InputError("tiles-from", "'" + *f.tiles_from + "/' holds the tiles of a different job: every option but "
                                   "--out, --threads, --shard, --show, --bins, --curves, --format, --size, --dpi and "
                                   "--palette must be the same");
  g.compute = !f.merge_only;
  g.progress = !f.quiet && stderr_is_terminal() && world.rank == 0;
  g.label = "bouncer " + j.command;
  bool made_tile_dir = false;  // by this run: removed again if the run fails before saving a tile
  if (f.out) {
    namespace fs = std::filesystem;
    g.tile_dir = tiles_dir(*f.out);
    const std::string field = f.merge_only ? "prefix" : "out";
    if (f.merge_only) {
      // Nothing is created (no folder, no lock) unless every tile is there to merge.
      std::vector<long> miss;
      std::vector<std::string> buf;
      for (long t = 0; t < j.plan.tiles(); ++t) {
        bool found = false;
        for (const std::string& from : f.merge_from) found = found || read_tile(from, t, j.plan, g.job_key, buf);
        found = found || read_tile(g.tile_dir, t, j.plan, g.job_key, buf);
        if (!found) miss.push_back(t);
      }
      if (!miss.empty()) throw InputError("merge", missing_tiles_text(miss, j.plan.tiles()));
    }
    if (world.rank == 0) {
      std::error_code ec;
      made_tile_dir = !fs::exists(fs::symlink_status(g.tile_dir, ec));
      // Held until the command returns: the outputs are written after run_job returns.
      f.hold->lock = std::make_unique<PrefixLock>(field, g.tile_dir, world.size > 1 ? Shard{} : f.shard);
      // Tiles of another job under the same prefix are stale: start afresh (the lock stays).
      // The directory is a real one (PrefixLock refuses a link), and remove_all never
      // follows a link inside it.
      const std::string old_key = first_line_of(field, g.tile_dir + "/job.key");
      if (!old_key.empty() && old_key != g.job_key && !f.merge_only) {
        if (!f.hold->lock->make_whole())
          throw InputError(field, "'" + g.tile_dir + "' holds the tiles of another job whose shards are still running; choose another --out");
        for (const auto& e : fs::directory_iterator(g.tile_dir))
          if (e.path().filename() != "lock") fs::remove_all(e.path());
      }
      if (old_key != g.job_key) {
        // Shards of one job may start together: each writes its own copy and renames it
        // (the same bytes), so neither is refused by the other's staging file.
        const std::string own = "." + std::to_string(::getpid());
        auto put = [&](const std::string& path, const std::string& text) {
          write_output(field, path + own, [&](std::ostream& s) { s << text; });
          if (::rename((path + own).c_str(), path.c_str()) != 0)
            throw OutputError("cannot rename '" + path + own + "': " + std::strerror(errno));
        };
        put(g.tile_dir + "/job.toml", j.job.as_toml(j.command));
        put(g.tile_dir + "/job.key", g.job_key + "\n");
      }
    }
    mpi_barrier();
    for (const std::string& from : f.merge_from)
      if (from != g.tile_dir) import_tiles(from, g.tile_dir, j.plan, g.job_key);
    if (f.tiles_from && *f.tiles_from != g.tile_dir) import_tiles(*f.tiles_from, g.tile_dir, j.plan, g.job_key);
    set_interrupt_hint("finished tiles are kept in " + g.tile_dir + "/: run the same command again to resume" +
                       (f.shard.all() ? "" : " (shard " + f.shard.text() + ")"));
  }
  GridResult r;
  try {
    r = (j.items ? run_grid(j.plan, j.group, j.items, g) : run_grid(j.plan, j.item, g));
  } catch (...) {
    // A run that fails before it saved a tile (no thread could start, bad input found in
    // the first item) leaves no tile directory it made: nothing in it could be resumed.
    if (made_tile_dir && f.shard.all() && world.size == 1 && holds_no_tiles(g.tile_dir)) {
      std::error_code ec;
      std::filesystem::remove_all(g.tile_dir, ec);
    }
    throw;
  }
  if (r.tiles_other_build + r.tiles_bad_checksum > 0)
    std::cerr << "bouncer " << j.command << ": " << r.tiles_other_build + r.tiles_bad_checksum
              << " saved tile(s) in " << g.tile_dir << "/ recomputed: " << r.tiles_other_build << " from another build, "
              << r.tiles_bad_checksum << " with a bad checksum (damaged or edited)\n";
  if (world.size > 1) {
    mpi_barrier();  // every rank's tiles are saved
    if (world.rank != 0) return std::nullopt;
    g.compute = false;
    r = (j.items ? run_grid(j.plan, j.group, j.items, g) : run_grid(j.plan, j.item, g));
    if (!r.complete()) throw std::runtime_error("mpirun: tiles missing after every rank finished");
    return std::move(r.items);
  }
  // A shard only leaves tiles, even when it completes the set: `bouncer merge` writes the
  // outputs, so a job array needs no "who finishes" logic.
  if (r.complete() && f.shard.all()) return std::move(r.items);
  const std::vector<long> miss = r.missing();
  if (f.merge_only) throw InputError("merge", missing_tiles_text(miss, j.plan.tiles()));
  if (!f.quiet)
    std::cerr << "bouncer " << j.command << ": shard " << f.shard.text() << " done (" << r.tiles_computed
              << " tiles computed; " << miss.size() << " of " << j.plan.tiles() << " tiles still missing). Run `bouncer merge "
              << *f.out << "` when all shards are done.\n";
  if (f.json) {
    nlohmann::ordered_json s;
    s["status"] = "shard done";
    s["shard"] = f.shard.text();
    s["tiles"] = j.plan.tiles();
    s["tiles_computed"] = r.tiles_computed;
    s["tiles_missing"] = miss.size();
    s["merge"] = "bouncer merge " + *f.out;
    command_out() << s.dump(2) << "\n";
  }
  return std::nullopt;
}

// Writes the outputs of a finished job: PREFIX.csv (provenance comments + rows), the
// pictures of --format (PREFIX.png/.pdf/.svg through `draw`), PREFIX.json (provenance +
// summary), all or none; without --out the CSV goes to stdout unless --json. With --json the
// summary is printed on stdout.
// A second picture of the same run, written as PREFIX-SUFFIX.png/.pdf/.svg (e.g. the
// artefact map of a certified basin, "artefacts").
struct ExtraFigure {
  std::string suffix;
  std::function<void(std::ostream&, ImageFormat)> draw;
};
// The ExtraFigure that writes `fig` (with the run's provenance as PNG metadata) in f's
// formats; it keeps the figure alive. (basin's and scan's --confirm artefact maps.)
inline ExtraFigure extra_figure(const std::string& suffix, ImageFigure fig, const Provenance& prov, const RunFlags& f) {
  fig.metadata = png_metadata(prov, fig.title);
  auto kept = std::make_shared<const ImageFigure>(std::move(fig));
  return {suffix, [kept, &f](std::ostream& out, ImageFormat fmt) { write_figure(out, *kept, fmt, f.picture.render); }};
}

inline void write_outputs(const RunFlags& f, const Provenance& p, const std::string& csv_body,
                          const std::function<void(std::ostream&, ImageFormat)>& draw,
                          const nlohmann::ordered_json& summary, const std::vector<ExtraFigure>& extra = {}) {
  nlohmann::ordered_json doc;
  doc["provenance"] = nlohmann::ordered_json::parse(p.as_json());
  doc["summary"] = summary;
  if (f.out) {
    doc["files"] = {{"csv", *f.out + ".csv"}};
    for (ImageFormat fmt : f.picture.formats) doc["files"][format_name(fmt)] = *f.out + "." + format_name(fmt);
    doc["files"]["json"] = *f.out + ".json";
    std::vector<OutputFile> files{{*f.out + ".csv", [&](std::ostream& s) { s << p.as_comment_lines() << csv_body; }}};
    for (OutputFile& pic : picture_files(*f.out, f.picture, draw)) files.push_back(std::move(pic));
    for (const ExtraFigure& e : extra) {
      for (ImageFormat fmt : f.picture.formats)
        doc["files"][e.suffix + "_" + format_name(fmt)] = *f.out + "-" + e.suffix + "." + format_name(fmt);
      for (OutputFile& pic : picture_files(*f.out + "-" + e.suffix, f.picture, e.draw)) files.push_back(std::move(pic));
    }
    files.push_back({*f.out + ".json", [&](std::ostream& s) { s << doc.dump(2) << "\n"; }});
    write_output_set(files, &f.hold->outputs);
    if (!f.keep_tiles) {
      std::error_code ec;
      std::filesystem::remove_all(tiles_dir(*f.out), ec);
    }
  } else if (!f.json) {
    command_out() << p.as_comment_lines() << csv_body;
  }
  if (CommandCapture* c = command_capture()) c->csv = p.as_comment_lines() + csv_body;
  if (f.json) command_out() << doc.dump(2) << "\n";
}

// The registry used by `bouncer merge`: the command name -> its keys and its runner.
struct PictureCommand {
  const std::set<std::string>& (*keys)();
  int (*run)(const Options& job_and_run, const RunFlags& flags);
};
const std::map<std::string, PictureCommand>& picture_commands();

// Runners (tools/cmd_*.cpp), shared with merge.
const std::set<std::string>& bifurcation_keys();
int run_bifurcation(const Options& o, const RunFlags& f);
const std::set<std::string>& portrait_keys();
int run_portrait(const Options& o, const RunFlags& f);
const std::set<std::string>& basin_keys();
int run_basin(const Options& o, const RunFlags& f);
const std::set<std::string>& scan_keys();
int run_scan(const Options& o, const RunFlags& f);
const std::set<std::string>& lyapunov_curve_keys();
int run_lyapunov_curve(const Options& o, const RunFlags& f);

// A certified map (basin --certify, scan --certify; io/grid_figures.hpp): the CSV rows
// "X,Y,class,period,certified_steps,scalar,double_class,double_period,agreement", the two
// pictures PREFIX.png (the certified classes) and PREFIX-artefacts.png (where double's class
// is refuted), and the JSON summary (`summary` first, then the counts).
inline void write_certified_map(const CertifiedMap& m, const std::vector<Number>& xs, const std::vector<Number>& ys,
                                const std::vector<CertifiedCell>& cells, nlohmann::ordered_json s,
                                const std::string& twin_precision, const RunFlags& f, const Provenance& prov) {
  const std::string csv = certified_map_csv(m, xs, ys, cells);
  std::map<std::string, long> scalars;
  long outside = 0, agrees = 0, differs = 0, undecided = 0;
  for (const CertifiedCell& c : cells) {
    if (!c.scalar.empty()) ++scalars[c.scalar];
    outside += c.agreement == Agreement::outside;
    agrees += c.agreement == Agreement::agrees;
    differs += c.agreement == Agreement::differs;
    undecided += c.agreement == Agreement::undecided;
  }
  const double inside = static_cast<double>(cells.size()) - static_cast<double>(outside);
  // (Named references, not a structured binding: clang 14 cannot capture one in the lambdas below.)
  std::pair<ImageFigure, ImageFigure> figures = certified_figures(m, cells, f.picture.palette);
  ImageFigure& cert = figures.first;
  ImageFigure& art = figures.second;
  cert.metadata = png_metadata(prov, cert.title);
  art.metadata = png_metadata(prov, art.title);
  s["points"] = cells.size();
  s["points_in_phase_space"] = cells.size() - static_cast<size_t>(outside);
  s["max_steps"] = m.max_steps;
  s["schedule"] = "interval:double, then MPFI at 64, 128, ... up to " + std::to_string(m.max_bits) + " bits";
  nlohmann::ordered_json types = nlohmann::ordered_json::array();
  for (const CertifiedCount& k : certified_census(cells))
    types.push_back({{"class", name(k.cls)}, {"period", k.period}, {"points", k.points},
                     {"share_of_phase_space", k.cls == CertifiedClass::outside || inside <= 0
                                                  ? nlohmann::ordered_json()
                                                  : nlohmann::ordered_json(k.points / inside)}});
  s["classes"] = types;
  s["double_vs_certified"] = {{"agrees", agrees}, {"differs", differs}, {"undecided", undecided}};
  s["decided_by"] = scalars;
  s["twin_precision"] = twin_precision;
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, cert, fmt, f.picture.render); }, s,
                {{"artefacts", [&](std::ostream& out, ImageFormat fmt) { write_figure(out, art, fmt, f.picture.render); }}});
}

// Runs a grid of typed cells (run/: BasinGrid, ScanGrid, BifurcationGrid) through the job's
// tiles; returns the cells once every tile is done (nothing after a shard run, which leaves
// its tiles for `bouncer merge`).
template <class Cell, class Grid>
std::optional<std::vector<Cell>> run_cells(const std::string& command, const Options& o, const RunFlags& f, Grid& grid,
                                           double item_bytes = 32, const std::string& size_field = "grid") {
  PictureJob job;
  job.command = command;
  job.job = job_options(o);
  job.plan = grid.plan();
  job.item = [&grid](long i) { return grid.item(i); };
  if constexpr (requires(std::string* out) { grid.items(0L, 0L, out); }) {
    job.group = grid.group();
    job.items = [&grid](long b, long e, std::string* out) { grid.items(b, e, out); };
  }
  job.item_bytes = item_bytes;
  job.size_field = size_field;
  const auto items = run_job(job, f);
  if (!items) return std::nullopt;
  return decode_cells<Cell>(*items);
}

}  // namespace bouncer::cli
