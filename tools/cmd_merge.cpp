// bouncer merge: finish a grid job from its saved tiles. Shards of one job (`--shard i/N`)
// write tiles into PREFIX.tiles/ (one shared prefix, or one prefix per shard); merge reads
// the job from PREFIX.tiles/job.toml, gathers the tiles of every prefix given, checks that
// none is missing, and writes PREFIX.csv, PREFIX.png and PREFIX.json as the unsharded run
// would have (byte for byte, apart from the invocation recorded in the provenance).
#include <memory>

#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

const std::map<std::string, PictureCommand>& picture_commands() {
  static const std::map<std::string, PictureCommand> m{
      {"bifurcation", {&bifurcation_keys, &run_bifurcation}},
      {"portrait", {&portrait_keys, &run_portrait}},
      {"basin", {&basin_keys, &run_basin}},
      {"scan", {&scan_keys, &run_scan}},
      {"lyapunov", {&lyapunov_curve_keys, &run_lyapunov_curve}},
  };
  return m;
}

namespace {

std::string first_line(const std::string& path) { return first_line_of("prefix", path); }

int run_merge(const std::vector<std::string>& prefixes, Options o, const FlagSet& flags, const std::string& argv_text) {
  if (prefixes.empty()) throw InputError("prefix", "give the output prefix(es) of the shard runs");
  const std::string dir0 = tiles_dir(prefixes[0]);
  const std::string command_line = first_line(dir0 + "/job.toml");
  const std::string tag = "command = \"";
  if (command_line.rfind(tag, 0) != 0 || command_line.size() < tag.size() + 1)
    throw InputError("prefix", "'" + dir0 + "/job.toml' not found or not a bouncer job (run the shards with --out " +
                                   prefixes[0] + " first)");
  const std::string command = command_line.substr(tag.size(), command_line.size() - tag.size() - 1);
  const auto it = picture_commands().find(command);
  if (it == picture_commands().end()) throw InputError("prefix", "'" + dir0 + "' holds a job of unknown command '" + command + "'");
  const std::string key = first_line(dir0 + "/job.key");
  for (const std::string& p : prefixes)
    if (first_line(tiles_dir(p) + "/job.key") != key)
      throw InputError("prefix", "'" + tiles_dir(p) + "' is missing or holds a different job than '" + dir0 + "'");
  Options job = load_scene(dir0 + "/job.toml", command, it->second.keys());
  // A job file holds what the job computes, never how or where it runs (job_options): a run
  // key in it was put there by hand, and must not choose merge's outputs or threads.
  for (const std::string& k : run_keys())
    if (job.has(k))
      throw InputError("prefix", "'" + dir0 + "/job.toml' names '" + k + "', which is not part of a job (was it edited?); "
                                 "give --" + k + " to merge instead");
  // Run options of the merge itself (threads, out) and its picture options (format, size,
  // dpi, palette: how the merged job is drawn) on top of the job's.
  for (const auto& [k, v] : o.values) job.values[k] = v;
  if (!job.has("out")) job.set("out", prefixes[0]);
  RunFlags f = run_flags_from(job, flags, argv_text);
  f.merge_only = true;
  for (const std::string& p : prefixes) f.merge_from.push_back(tiles_dir(p));
  return it->second.run(job, f);
}

}  // namespace

CommandRunner setup_merge(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto prefixes = std::make_shared<std::vector<std::string>>();
  sub->add_option("prefix", *prefixes, "Output prefix(es) of the shard runs; the first names the job")->required();
  opts->add("out", "Write the merged outputs to PREFIX (default: the first prefix)");
  opts->add("threads", "Ignored by merge (nothing is computed); accepted for symmetry");
  add_picture_options(*opts);  // render the merged job differently from its shards
  auto flags = std::make_shared<FlagSet>();
  sub->add_flag("--quiet", flags->quiet, "No progress output");
  sub->add_flag("--json", flags->json, "Print the JSON summary on stdout");
  sub->add_flag("--keep-tiles", flags->keep_tiles, "Keep the merged PREFIX.tiles/ after writing the outputs");
  auto run = [opts, prefixes, flags](const std::string& argv_text) {
    return run_merge(*prefixes, opts->collected(), *flags, argv_text);
  };
  return run;
}

}  // namespace bouncer::cli
