// bouncer audit of one result (workflow/audit.hpp): its provenance read, the rerun planned
// within the trust boundary, run in a private directory, and compared.
#include "bouncer/workflow/audit.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>

#include "audit_internal.hpp"
#include "bouncer/base/error.hpp"
#include "bouncer/base/input.hpp"
#include "bouncer/io/orbit.hpp"
#include "bouncer/workflow/child_process.hpp"
#include "bouncer/workflow/commands.hpp"
#include "bouncer/workflow/reproduce.hpp"

namespace bouncer {

namespace audit_detail {

std::optional<std::string> read_result(const std::string& path) {
  try {
    return read_input_file("file", path, kMaxResultBytes);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

int run_to_file(const std::vector<std::string>& argv, const std::string& out_path, const std::string& cwd) {
  const int fd = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) return -1;
  const pid_t pid = start_child(argv, fd, -1, cwd);
  ::close(fd);
  if (pid < 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

PrivateDir::PrivateDir() {
  std::string tmpl = (std::filesystem::temp_directory_path() / "bouncer-audit-XXXXXX").string();
  if (!::mkdtemp(tmpl.data())) throw OutputError("cannot create a temporary directory: " + std::string(std::strerror(errno)));
  path = tmpl;
}

PrivateDir::~PrivateDir() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
}

}  // namespace audit_detail

using audit_detail::json;

namespace {

std::optional<RecordedRun> recorded_json(const std::string& text) {
  json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("provenance")) return std::nullopt;
  const json& p = j["provenance"];
  if (!p.is_object() || !p.contains("command") || !p["command"].is_string() || !p.contains("inputs") ||
      !p["inputs"].is_object())
    return std::nullopt;
  RecordedRun r;
  r.is_json = true;
  r.command = p["command"].get<std::string>();
  for (const auto& [k, v] : p["inputs"].items()) {
    if (!v.is_string()) return std::nullopt;
    r.inputs.emplace_back(k, v.get<std::string>());
  }
  return r;
}

std::optional<RecordedRun> recorded_text(const std::string& text) {
  std::istringstream in(text);
  std::string first;
  if (!std::getline(in, first) || first.rfind("# bouncer ", 0) != 0) return std::nullopt;
  // "# bouncer VERSION (commit C) COMMAND"
  const auto close = first.find(") ");
  if (close == std::string::npos) return std::nullopt;
  RecordedRun r;
  r.command = first.substr(close + 2);
  if (r.command.empty() || r.command.find(' ') != std::string::npos) return std::nullopt;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# inputs:", 0) != 0) continue;
    const auto tokens = audit_detail::input_tokens(line.substr(9));
    if (!tokens) return std::nullopt;
    r.inputs = *tokens;
    return r;
  }
  return std::nullopt;
}

// The first difference of two npy orbit files (io/orbit.hpp: format 1.0, '<f8', rows of
// npy_orbit_columns()), byte for byte; where it is in the data, by row and column.
Comparison compare_npy(const std::string& name, const std::string& file, const std::string& rerun) {
  Comparison c;
  if (file == rerun) return c;
  c.identical = false;
  c.path = name + " (npy data)";
  if (file.size() != rerun.size()) {
    c.detail = std::to_string(file.size()) + " vs " + std::to_string(rerun.size()) + " bytes";
    return c;
  }
  size_t at = 0;
  while (file[at] == rerun[at]) ++at;
  c.detail = "byte " + std::to_string(at) + " differs";
  // The data start after the 10-byte preamble and the header whose length bytes 8-9 give.
  const size_t data = file.size() >= 10 ? 10 + (static_cast<unsigned char>(file[8]) | static_cast<unsigned char>(file[9]) << 8) : file.size();
  if (at >= data) {
    const std::vector<std::string>& cols = npy_orbit_columns();
    const size_t value = (at - data) / 8;
    c.detail += " (row " + std::to_string(value / cols.size()) + ", column " + cols[value % cols.size()] + ")";
  } else {
    c.detail += " (in the header)";
  }
  return c;
}

// The rerun of one result file, planned, checked, run and compared.
AuditResult audit_result(const AuditRequest& request, const std::string& text) {
  const std::string& path = request.file;
  const audit_detail::PrivateDir private_dir;
  const std::string dir = private_dir.path;
  const AuditPlan plan = plan_rerun(path, text, dir, request.executable);
  const std::vector<std::string>& argv = plan.argv;
  // The rebuilt command is validated as the command line validates it, in this process and
  // before anything is started.
  if (request.check_command) {
    std::vector<std::string> words{"bouncer"};
    words.insert(words.end(), argv.begin() + 1, argv.end());
    if (const auto refused = request.check_command(words))
      throw InputError("file", "'" + path + "' records inputs that bouncer refuses: " + *refused);
  }
  // An npy orbit's data, read before anything runs: a provenance without its data proves nothing.
  std::optional<std::string> data;
  if (!plan.data_path.empty()) {
    data = audit_detail::read_result(plan.data_path);
    if (!data)
      throw InputError("file", "'" + path + "' is the provenance of an npy orbit, but its data '" + plan.data_path +
                                   "' cannot be read (missing, not a regular file, or above 1 GiB)");
  }
  AuditResult result;
  result.is_json = plan.is_json;
  result.data_file = plan.data_path;
  result.rerun = "bouncer " + plan.command;
  for (size_t i = 2; i < argv.size(); ++i) result.rerun += " " + (argv[i].rfind(dir, 0) == 0 ? "<tmp>" + argv[i].substr(dir.size()) : argv[i]);
  if (request.on_rerun) request.on_rerun(result.rerun);
  std::chrono::steady_clock::time_point rerun_ended{};
  // The comparison's time (from the rerun's end) stamped on every outcome after the rerun.
  auto done = [&]() {
    if (rerun_ended != std::chrono::steady_clock::time_point{})
      result.compare_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - rerun_ended).count();
    return result;
  };
  auto failed = [&](const std::string& why) {
    result.verdict = AuditVerdict::rerun_failed;
    result.message = why;
    return done();
  };
  const auto started = std::chrono::steady_clock::now();
  result.rerun_status = audit_detail::run_to_file(argv, dir + "/stdout", dir);
  rerun_ended = std::chrono::steady_clock::now();
  result.rerun_seconds = std::chrono::duration<double>(rerun_ended - started).count();
  if (result.rerun_status != 0) return failed("the rerun failed (exit status " + std::to_string(result.rerun_status) + ")");
  const std::optional<std::string> again = audit_detail::read_result(plan.compare_path);
  if (!again) return failed("the rerun wrote no result");
  if (plan.is_json) {
    json a = audit_detail::parse_exact(text), b = audit_detail::parse_exact(*again);
    if (b.is_discarded()) return failed("the rerun's output is not JSON");
    audit_detail::strip_volatile(a, true);
    audit_detail::strip_volatile(b, true);
    if (data) {  // the data's file name, as "files" elsewhere: where it was written
      if (a.is_object()) a.erase("npy");
      if (b.is_object()) b.erase("npy");
    }
    result.first = audit_detail::first_difference(a, b);
    if (data && result.first.identical) {
      const std::optional<std::string> data_again = audit_detail::read_result(plan.rerun_data_path);
      if (!data_again) return failed("the rerun wrote no npy data");
      result.first = compare_npy(plan.data_path, *data, *data_again);
    }
  } else {
    result.first = compare_text_results(text, *again);
  }
  result.verdict = result.first.identical ? AuditVerdict::identical : AuditVerdict::different;
  return done();
}

AuditResult audit_any(const AuditRequest& request) {
  namespace fs = std::filesystem;
  const std::string& path = request.file;
  // A `bouncer reproduce` directory: compared item by item (audit_reproduce.cpp).
  if (std::error_code ec; fs::is_directory(path, ec)) {
    if (fs::exists(fs::path(path) / "claims.json", ec)) return audit_detail::audit_reproduce(path, request);
    throw InputError("file", "'" + path + "' is a directory without claims.json; give a result file (JSON or CSV "
                             "written by bouncer) or a bouncer reproduce directory");
  }
  const std::string text = read_input_file("file", path, kMaxResultBytes);
  if (const json j = json::parse(text, nullptr, false); j.is_object() && j.contains("reproduce") && j.contains("claims")) {
    const fs::path parent = fs::path(path).parent_path();
    return audit_detail::audit_reproduce(parent.empty() ? std::string(".") : parent.string(), request);
  }
  return audit_result(request, text);
}

}  // namespace

std::optional<RecordedRun> read_provenance(const std::string& text) {
  std::optional<RecordedRun> rec = recorded_json(text);
  if (!rec) rec = recorded_text(text);
  return rec;
}

AuditPlan plan_rerun(const std::string& path, const std::string& text, const std::string& dir, const std::string& self) {
  // Kinds that carry no rerunnable provenance are refused up front, with what to do instead.
  if (text.rfind("\x89PNG", 0) == 0 || text.rfind("%PDF-", 0) == 0 ||
      (text.rfind("<?xml", 0) == 0 && text.find("<svg", 0) != std::string::npos))
    throw InputError("file", "'" + path + "' is a picture; audit the PREFIX.json or PREFIX.csv written beside it "
                             "(same provenance, exact numbers)");
  if (text.rfind("\x93NUMPY", 0) == 0)
    throw InputError("file", "'" + path + "' is the data of an npy orbit; audit its provenance '" + path + ".json' beside it");
  if (const json j = json::parse(text, nullptr, false); j.is_object() && j.contains("proof") && j.contains("claim"))
    throw InputError("file", "'" + path + "' is a proof certificate; rerun its proof (" + proof_prefix(self) + "proof_" +
                                 (j["proof"].is_string() && safe_name(j["proof"].get<std::string>()) ? j["proof"].get<std::string>()
                                                                                                   : std::string("NAME")) +
                                 " --json) and compare, as docs/guide/reproduce.md shows");
  const std::optional<RecordedRun> rec = read_provenance(text);
  if (!rec) throw InputError("file", "'" + path + "' is not a bouncer result (no provenance with command and inputs)");
  // The trust boundary (README, "Security"): audit reruns only what bouncer itself writes,
  // a computing command with its recorded inputs as options. Never reproduce, audit or
  // merge, never an input that names where to read tiles, a scene or a manifest: no bouncer
  // result records one, so a file that does was made by hand.
  if (!is_computing_command(rec->command))
    throw InputError("file", "'" + path + "' records the command '" + one_line(rec->command, 60) +
                                 "', which audit does not rerun (it reruns the results of bouncer's computing commands; "
                                 "a reproduce directory is audited as a directory)");
  static const std::set<std::string> never_recorded{"tiles-from", "keep-tiles", "shard", "scene", "manifest", "threads",
                                                    "trust-manifest", "force", "help", "version"};
  for (const auto& [k, v] : rec->inputs) {
    if (k.empty() || k.size() > 40 || k.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-") != std::string::npos ||
        k[0] == '-' || never_recorded.count(k))
      throw InputError("file", "'" + path + "' records the input '" + one_line(k, 60) +
                                   "', which no bouncer result records: audit does not rerun it");
    if (v.find('\0') != std::string::npos) throw InputError("file", "'" + path + "' records an input with a NUL byte");
  }
  AuditPlan plan;
  plan.is_json = rec->is_json;
  plan.command = rec->command;
  std::vector<std::string>& argv = plan.argv;
  argv = {self, rec->command};
  plan.compare_path = dir + "/stdout";
  bool has_out = false;
  for (const auto& [k, v] : rec->inputs) {
    if (k == "out") { has_out = true; continue; }
    if (k == "json") { if (v == "true") argv.push_back("--json"); continue; }
    if (k == "certify") { if (v == "true") argv.push_back("--certify"); continue; }  // a flag of continue
    // One word, --KEY=VALUE: the rerun's parser never reads a recorded value as an option of
    // its own (a value "--keep-tiles" or "--tiles-from=DIR" given as a separate word would be).
    argv.push_back("--" + k + "=" + v);
  }
  // A JSON written with --out PREFIX lists its files; a picture command's JSON exists only
  // that way (its --out is not an input: the job is the same wherever it is written).
  bool prefix_json = false;
  if (rec->is_json) {
    const json j = json::parse(text, nullptr, false);
    prefix_json = j.is_object() && j.contains("files") && j["files"].is_object();
  }
  if (prefix_json && !has_out) {
    argv.push_back("--out");
    argv.push_back(dir + "/result");
    plan.compare_path = dir + "/result.json";
  } else if (rec->is_json && !has_out) {
    // Commands that print JSON on stdout with --json; orbit chooses it with --format.
    bool chosen = false;
    for (const auto& [k, v] : rec->inputs) chosen = chosen || k == "json" || (k == "format" && rec->command == "orbit");  // elsewhere --format names pictures
    if (!chosen) argv.push_back("--json");
  }
  if (has_out) {
    argv.push_back("--out");
    argv.push_back(dir + "/result");
    plan.compare_path = dir + "/result";
    if (rec->command == "sweep" || rec->command == "continue")  // PREFIX.json / PREFIX.csv
      plan.compare_path += std::filesystem::path(path).extension().string();  // .json / .csv
  }
  // orbit --format npy --out PATH wrote PATH (the data) and PATH.json (this provenance).
  const bool npy = rec->command == "orbit" && std::any_of(rec->inputs.begin(), rec->inputs.end(), [](const auto& kv) {
                     return kv.first == "format" && kv.second == "npy";
                   });
  if (npy && has_out && rec->is_json) {
    const std::string suffix = ".json";
    if (path.size() <= suffix.size() || path.compare(path.size() - suffix.size(), suffix.size(), suffix) != 0)
      throw InputError("file", "'" + path + "' is the provenance of an npy orbit, which bouncer writes as PATH.json beside "
                                   "its data PATH: audit it under a name ending in .json, beside its data");
    plan.data_path = path.substr(0, path.size() - suffix.size());
    plan.rerun_data_path = dir + "/result";
    plan.compare_path = dir + "/result.json";
  }
  return plan;
}

AuditResult audit(const AuditRequest& request) {
  try {
    return audit_any(request);
  } catch (const InputError& e) {  // not a result audit reruns: the reason, about the field "file"
    AuditResult r;
    r.verdict = AuditVerdict::not_a_result;
    r.message = std::string(e.what()).substr(e.field.size() + 2);
    return r;
  } catch (const json::exception& e) {  // a crafted file whose parts have other types
    AuditResult r;
    r.verdict = AuditVerdict::not_a_result;
    r.message = "'" + request.file + "' is malformed: " + e.what();
    return r;
  }
}

}  // namespace bouncer
