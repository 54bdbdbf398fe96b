#include "bouncer/workflow/reproduce.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>
#include <thread>

#include "bouncer/base/build_info.hpp"
#include "bouncer/base/cancel.hpp"
#include "bouncer/base/error.hpp"
#include "bouncer/base/input.hpp"
#include "bouncer/base/output.hpp"
#include "bouncer/base/text.hpp"
#include "bouncer/workflow/paper.hpp"
#include "bouncer/workflow/report.hpp"

namespace bouncer {

namespace {

namespace fs = std::filesystem;

// The bouncer binary: `executable`, or this process's.
fs::path executable_path(const std::string& executable) {
  if (!executable.empty()) return executable;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw OutputError("cannot locate this binary (/proc/self/exe): " + ec.message());
  return exe;
}

// The proof directories a binary in EXE_DIR may use, in order: the build tree's
// (build/tools/../proofs) and the install's (bin/BOUNCER_PROOFS_FROM_BIN, lib/CMakeLists.txt).
std::vector<fs::path> proof_directories(const fs::path& exe_dir) {
  return {exe_dir / ".." / "proofs", exe_dir / BOUNCER_PROOFS_FROM_BIN};
}

std::optional<fs::path> find_proof(const fs::path& exe_dir, const std::string& name) {
  for (const fs::path& d : proof_directories(exe_dir)) {
    const fs::path p = d / name;
    std::error_code ec;
    if (fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0) return fs::weakly_canonical(p, ec);
  }
  return std::nullopt;
}

// A `--scene data/scenes/NAME.toml` of a manifest command names a scene compiled into the
// library (workflow/paper.hpp), so reproduce runs from any directory: the scene is written
// to SCENE_DIR/NAME.toml and the command reads it there. Returns a problem, or "".
std::string resolve_scenes(std::vector<std::string>& exec, const fs::path& scene_dir) {
  for (size_t i = 1; i < exec.size(); ++i) {
    if (exec[i - 1] != "--scene") continue;
    const auto it = built_in_scenes().find(exec[i]);
    if (it == built_in_scenes().end()) return "scene '" + exec[i] + "' is not one of data/scenes/ (built in)";
    const fs::path file = scene_dir / fs::path(exec[i]).filename();
    make_own_directory("out", scene_dir.string());
    write_output("out", file.string(), [&](std::ostream& s) { s << it->second; });
    exec[i] = file.string();
  }
  return "";
}

// The ids the request's `only` names (each also accepted without "fig:" or "picture:"),
// checked against `ids`, the mode's items.
std::set<std::string> selection(const ReproduceRequest& r, const std::vector<std::string>& ids) {
  std::set<std::string> only;
  if (!r.only) return only;
  const bool pictures = r.mode == ReproduceMode::pictures;
  for (const std::string& w : *r.only) {
    if (w.empty()) continue;
    std::string id = w;
    for (const char* tag : {"fig:", "picture:"})
      if (std::find(ids.begin(), ids.end(), id) == ids.end() && std::find(ids.begin(), ids.end(), tag + id) != ids.end())
        id = tag + id;
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) {
      std::vector<std::pair<size_t, std::string>> near;
      for (const std::string& c : ids) {
        const size_t d = edit_distance(w, c);
        if (d <= 4 || c.find(w) != std::string::npos) near.emplace_back(d, c);
      }
      std::sort(near.begin(), near.end());
      std::string list;
      for (size_t i = 0; i < near.size() && i < 4; ++i) list += (i ? ", " : "") + near[i].second;
      throw InputError("only", "unknown item '" + w + "'" + (list.empty() ? "" : " (close: " + list + ")") +
                                   (pictures ? "; with --pictures, items are the documentation pictures (picture:NAME) of data/paper/manifest.toml"
                                             : "; items are the panel labels (fig:...) and claim ids of data/paper/manifest.toml"));
    }
    only.insert(id);
  }
  if (only.empty()) throw InputError("only", "give a comma list of panel labels and claim ids");
  return only;
}

// DIR and bouncer's own subdirectories of it.
void make_directory(const std::string& out, bool pictures) {
  const fs::path dir = out;
  if (out.empty()) throw InputError("out", "must name a directory");
  // DIR is the user's (it may be a link to a directory they chose); its subdirectories are
  // bouncer's own, and a link planted there is refused, never followed.
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw InputError("out", "'" + out + "' exists and is not a directory");
  check_path_name("out", out);
  fs::create_directories(dir, ec);
  if (ec) throw OutputError("cannot create '" + dir.string() + "': " + ec.message());
  // (scenes/ is made when a command's scene is written there)
  const std::vector<std::string> subs =
      pictures ? std::vector<std::string>{"pictures", "logs", "keys"} : std::vector<std::string>{"panels", "claims", "logs", "keys"};
  for (const std::string& sub : subs) make_own_directory("out", (dir / sub).string());
}

// Each selected item of the manifest, as a result to fill and a job to run (or settled
// already: a pending panel, a deferred claim, a scene that is not built in).
void plan_items(const ReproduceRequest& r, const Manifest& m, const fs::path& dir,
                const std::function<bool(const std::string&)>& selected, std::vector<ItemResult>& items,
                std::vector<Job>& jobs) {
  const bool full = r.mode == ReproduceMode::full;
  auto make = [](const std::string& id, ItemKind kind, size_t index) {
    ItemResult item;
    item.id = id;
    item.kind = kind;
    item.index = index;
    return item;
  };
  auto add = [&](ItemResult item, Job job) {
    job.id = item.id;
    items.push_back(std::move(item));
    jobs.push_back(std::move(job));
  };
  // The command, resolved: its scenes written into DIR/scenes/. False: the item failed.
  auto resolve = [&](ItemResult& item, Job& job) {
    job.exec = item.argv;
    if (const std::string problem = resolve_scenes(job.exec, dir / "scenes"); !problem.empty()) {
      job.state = ItemState::failed;
      job.problem = problem;
      return false;
    }
    return true;
  };
  for (size_t i = 0; i < m.panels.size(); ++i) {
    const Panel& p = m.panels[i];
    if (!selected(p.label)) continue;
    ItemResult item = make(p.label, ItemKind::panel, i);
    Job job;
    if (p.status == "pending") {
      job.state = ItemState::skipped;
      job.problem = "pending: " + p.reason;
      add(std::move(item), std::move(job));
      continue;
    }
    item.argv = full ? p.full : p.quick;
    // Every panel in the three formats a journal takes: PNG for the report, PDF and SVG
    // (vector) for print. All picture commands take --format.
    item.outputs = {"panels/" + p.name() + ".png", "panels/" + p.name() + ".pdf", "panels/" + p.name() + ".svg",
                    "panels/" + p.name() + ".json", "panels/" + p.name() + ".csv"};
    if (!p.twin_of.empty())  // a certified twin also draws where double is wrong
      for (const char* ext : {".png", ".pdf", ".svg"}) item.outputs.push_back("panels/" + p.name() + "-artefacts" + ext);
    job.outputs = item.outputs;
    if (!resolve(item, job)) {
      add(std::move(item), std::move(job));
      continue;
    }
    job.exec.insert(job.exec.end(), {"--out", (dir / "panels" / p.name()).string(), "--quiet", "--format", "png,pdf,svg"});
    job.stdout_path = (dir / "logs" / (p.name() + ".stdout")).string();
    job.stderr_path = (dir / "logs" / (p.name() + ".stderr")).string();
    job.key_path = (dir / "keys" / (p.name() + ".key")).string();
    if (!p.tiles_from.empty())
      for (size_t k = 0; k < jobs.size(); ++k)
        if (jobs[k].id == p.tiles_from && jobs[k].state == ItemState::pending) {
          job.after = k;
          jobs[k].tiles_prefix = (dir / "panels" / m.panels[items[k].index].name()).string();
        }
    add(std::move(item), std::move(job));
  }
  for (size_t i = 0; i < m.claims.size(); ++i) {
    const Claim& c = m.claims[i];
    if (!selected(c.id)) continue;
    ItemResult item = make(c.id, ItemKind::claim, i);
    Job job;
    if (!full && !c.quick) {
      job.state = ItemState::deferred;
      job.problem = "not settled in --quick: run `" + command_text(c.full_run, proof_prefix(r.executable)) + "` (or bouncer reproduce --full --only " + c.id + ")";
      item.argv = c.full_run;
      add(std::move(item), std::move(job));
      continue;
    }
    item.argv = full ? c.full_run : c.run;
    if (!resolve(item, job)) {
      add(std::move(item), std::move(job));
      continue;
    }
    item.outputs = {"claims/" + c.id + ".json"};
    job.outputs = item.outputs;
    job.stdout_path = (dir / "claims" / (c.id + ".json")).string();
    job.stderr_path = (dir / "logs" / (c.id + ".stderr")).string();
    job.key_path = (dir / "keys" / (c.id + ".key")).string();
    add(std::move(item), std::move(job));
  }
  for (size_t i = 0; i < m.pictures.size(); ++i) {
    const Picture& p = m.pictures[i];
    if (!selected(p.id())) continue;
    ItemResult item = make(p.id(), ItemKind::picture, i);
    Job job;
    item.argv = p.command;  // the README's pictures are the same in --quick and --full
    if (!resolve(item, job)) {
      add(std::move(item), std::move(job));
      continue;
    }
    job.exec.insert(job.exec.end(), {"--out", (dir / "pictures" / p.name).string(), "--quiet"});
    for (const std::string& f : p.files) item.outputs.push_back("pictures/" + f);
    item.outputs.push_back("pictures/" + p.name + ".json");
    item.outputs.push_back("pictures/" + p.name + ".csv");
    job.outputs = item.outputs;
    job.stdout_path = (dir / "logs" / (p.name + ".picture.stdout")).string();
    job.stderr_path = (dir / "logs" / (p.name + ".picture.stderr")).string();
    job.key_path = (dir / "keys" / (p.name + ".picture.key")).string();
    add(std::move(item), std::move(job));
  }
}

// A settled claim: its verdict from its checks on the JSON it printed.
void judge_claim(const Claim& c, const fs::path& dir, ItemResult& it, ReproduceResult& r) {
  if (it.state == ItemState::deferred) {
    it.status = ClaimStatus::deferred;
    it.verdict = "not checked in --quick";
    ++r.deferred;
  } else if (it.state == ItemState::failed) {
    it.status = ClaimStatus::failed;
    it.verdict = it.problem.rfind("not reproduced", 0) == 0 ? it.problem : "not reproduced: the command failed (" + it.problem + ")";
    ++r.not_reproduced;
  } else {
    const std::string text = read_input_file_if_present("out", (dir / it.outputs[0]).string(), kMaxResultBytes).value_or("");
    auto checks = evaluate_checks(c.checks, text);
    if (!checks) {
      it.status = ClaimStatus::failed;
      it.verdict = "not reproduced: the output is not JSON";
      ++r.not_reproduced;
      ++r.failed_items;
      return;
    }
    it.checks = std::move(*checks);
    for (const CheckResult& k : it.checks)
      if (!k.held) it.failed_checks.push_back(k.check + " (got " + k.got + ")");
    if (it.failed_checks.empty()) {
      it.status = ClaimStatus::reproduced;
      it.verdict = c.expected;
      ++r.reproduced;
    } else {
      it.status = ClaimStatus::not_reproduced;
      it.verdict = "not reproduced: check " + it.failed_checks[0] + " failed";
      ++r.not_reproduced;
    }
  }
}

}  // namespace

std::optional<std::string> proof_directory(const std::string& executable) {
  const fs::path exe_dir = executable_path(executable).parent_path();
  for (const fs::path& d : proof_directories(exe_dir)) {
    std::error_code ec;
    if (fs::is_directory(d, ec)) return fs::weakly_canonical(d, ec).string();
  }
  return std::nullopt;
}

std::string proof_prefix(const std::string& executable) {
  const fs::path exe_dir = executable_path(executable).parent_path();
  std::error_code ec;
  if (fs::is_directory(exe_dir / ".." / "proofs", ec)) return kBuildProofPrefix;
  const auto dir = proof_directory(executable);
  return dir ? *dir + "/" : kBuildProofPrefix;
}

const char* mode_name(ReproduceMode m) {
  switch (m) {
    case ReproduceMode::quick: return "quick";
    case ReproduceMode::full: return "full";
    case ReproduceMode::pictures: return "pictures";
  }
  return "?";
}

const char* status_name(ClaimStatus s) {
  switch (s) {
    case ClaimStatus::reproduced: return "reproduced";
    case ClaimStatus::not_reproduced: return "not reproduced";
    case ClaimStatus::failed: return "failed";
    case ClaimStatus::deferred: return "deferred";
  }
  return "?";
}

std::string manifest_source(const std::string& path) { return path.empty() ? kPaperManifestSource : path; }

Manifest load_manifest(const std::string& path) {
  const std::string text = path.empty() ? std::string(paper_manifest_text()) : read_input_file("manifest", path, kMaxManifestBytes);
  return parse_manifest(text, manifest_source(path));
}

void refuse_nested_reproduce() {
  if (const char* inside = std::getenv(kInReproduceVariable); inside && *inside)
    throw InputError("reproduce", "runs no reproduce inside another (a manifest runs bouncer's computing commands only)");
}

ReproduceResult reproduce(const ReproduceRequest& request) {
  refuse_nested_reproduce();
  ReproduceResult r;
  r.mode = request.mode;
  r.manifest_source = manifest_source(request.manifest_path);
  r.manifest = request.manifest ? *request.manifest : load_manifest(request.manifest_path);
  const Manifest& m = r.manifest;
  const bool pictures = request.mode == ReproduceMode::pictures;
  r.jobs = request.jobs ? request.jobs : std::max(1u, std::thread::hardware_concurrency());
  // Every item's id: claims by id, panels by label; with pictures, the README pictures.
  std::vector<std::string> ids;
  if (pictures) {
    for (const Picture& p : m.pictures) ids.push_back(p.id());
  } else {
    for (const Panel& p : m.panels) ids.push_back(p.label);
    for (const Claim& c : m.claims) ids.push_back(c.id);
  }
  const std::set<std::string> only = selection(request, ids);
  r.only.assign(only.begin(), only.end());
  r.dir = request.out;
  make_directory(request.out, pictures);
  const fs::path dir = request.out;
  const fs::path exe = executable_path(request.executable);
  const fs::path exe_dir = exe.parent_path();
  r.proof_prefix = proof_prefix(request.executable);
  r.build = build_info().version + " (commit " + build_info().commit + ")";

  std::vector<Job> jobs;
  plan_items(request, m, dir,
             [&](const std::string& id) {
               return std::find(ids.begin(), ids.end(), id) != ids.end() && (only.empty() || only.count(id));
             },
             r.items, jobs);
  // Resolve the binaries and the resume keys.
  for (size_t i = 0; i < jobs.size(); ++i) {
    Job& job = jobs[i];
    if (job.state != ItemState::pending) continue;
    if (job.exec[0] == "bouncer") {
      job.exec[0] = exe.string();
    } else if (job.exec[0].rfind("proof_", 0) == 0) {
      if (auto p = find_proof(exe_dir, job.exec[0])) {
        job.exec[0] = p->string();
      } else {
        job.state = ItemState::failed;
        job.problem = "not reproduced: proof binary not found (" + job.exec[0] + " in " + (exe_dir / ".." / "proofs").string() +
                      " or " + (exe_dir / BOUNCER_PROOFS_FROM_BIN).string() + "; build it: cmake --build build --target " +
                      job.exec[0] + ", or cmake --install it)";
        continue;
      }
    } else {
      job.state = ItemState::failed;
      job.problem = "manifest command must start with bouncer or proof_NAME, not '" + job.exec[0] + "'";
      continue;
    }
    job.key = std::string("mode ") + mode_name(request.mode) + "\nbuild " + r.build + "\ncommand " + command_text(r.items[i].argv) + "\n";
    if (resumable(job, dir.string())) job.state = ItemState::cached;
  }

  const auto t0 = std::chrono::steady_clock::now();
  r.stopped_by = run_jobs(jobs, dir.string(), r.jobs, request.progress);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (size_t i = 0; i < jobs.size(); ++i) {
    ItemResult& it = r.items[i];
    it.state = jobs[i].state;
    it.problem = jobs[i].problem;
    it.exit_status = jobs[i].exit_status;
    it.seconds = jobs[i].seconds;
  }
  // No report for a stopped run: it would call the stopped items failed.
  if (r.stopped_by) return r;
  remove_kept_tiles(jobs);

  // The claims' verdicts.
  size_t picture_items = 0;
  std::set<std::string> claim_ids;
  for (ItemResult& it : r.items) {
    if (it.state == ItemState::failed) ++r.failed_items;
    if (it.kind == ItemKind::picture) ++picture_items;
    if (it.kind != ItemKind::claim) continue;
    claim_ids.insert(it.id);
    judge_claim(m.claims[it.index], dir, it, r);
  }
  r.claims = claim_ids.size();
  r.ok = r.failed_items == 0 && r.not_reproduced == 0;
  r.summary = pictures ? std::to_string(picture_items - r.failed_items) + " of " + std::to_string(picture_items) +
                             " documentation pictures drawn; " + std::to_string(r.failed_items) + " items failed"
                       : std::to_string(r.reproduced) + " of " + std::to_string(r.claims) +
                             " claims reproduced their expected verdict" +
                             (r.deferred ? " (" + std::to_string(r.deferred) + " deferred to --full)" : "") + "; " +
                             std::to_string(r.failed_items) + " items failed";
  write_reports(r);
  return r;
}

ManifestCheck check_manifest(const Manifest& m, const CommandValidator& validate, const std::string& executable) {
  const fs::path exe_dir = executable_path(executable).parent_path();
  std::string tmpl = (fs::temp_directory_path() / "bouncer-check-XXXXXX").string();
  if (!::mkdtemp(tmpl.data())) throw OutputError("cannot create a temporary directory: " + std::string(std::strerror(errno)));
  const fs::path tmp = tmpl;
  struct Remove {
    fs::path p;
    ~Remove() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } remove{tmp};
  ManifestCheck out;
  // kind: what reproduce appends when it runs the item: a panel --out, --quiet and --format; a
  // documentation picture --out and --quiet (as run_items does); a claim nothing.
  enum class Kind { panel, picture, claim };
  auto check = [&](const std::string& id, const std::string& which, std::vector<std::string> argv, Kind kind) {
    if (argv.empty()) return;
    const size_t checked = out.commands.size() + 1;
    std::string verdict;
    if (argv[0].rfind("proof_", 0) == 0) {
      verdict = find_proof(exe_dir, argv[0]) ? "ok (proof binary found)" : "refused: proof binary " + argv[0] + " not found";
    } else if (argv[0] != "bouncer") {
      verdict = "refused: must start with bouncer or proof_NAME";
    } else if (const std::string problem = resolve_scenes(argv, tmp / "scenes"); !problem.empty()) {
      verdict = "refused: " + problem;
    } else {
      if (kind != Kind::claim)
        argv.insert(argv.end(), {"--out", (tmp / (std::to_string(checked) + "-x")).string(), "--quiet"});
      if (kind == Kind::panel) argv.insert(argv.end(), {"--format", "png,pdf,svg"});
      const std::atomic<bool> stop{true};
      const CancelScope cancel(&stop);
      const CommandValidation v = validate(argv);
      using K = CommandValidation::Kind;
      verdict = v.kind == K::stopped ? "ok (validated; stopped at its first step)"
                : v.kind == K::ran   ? "ok (ran: nothing long to stop)"
                                     : "refused (exit " + std::to_string(v.status) + "): " + v.message;
    }
    const bool ok = verdict.rfind("ok", 0) == 0;
    if (!ok) ++out.refused;
    out.commands.push_back({id, which, verdict, ok});
  };
  for (const Panel& p : m.panels) {
    check(p.label, "quick", p.quick, Kind::panel);
    check(p.label, "full", p.full, Kind::panel);
  }
  for (const Claim& c : m.claims) {
    check(c.id, "run", c.run, Kind::claim);
    if (c.full_run != c.run) check(c.id, "full_run", c.full_run, Kind::claim);
  }
  for (const Picture& p : m.pictures) check(p.id(), "command", p.command, Kind::picture);
  return out;
}

}  // namespace bouncer
