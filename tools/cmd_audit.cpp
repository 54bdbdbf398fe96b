// bouncer audit FILE: rerun a recorded result from its provenance and report whether the
// new result is bit-identical.
//
// A result is a JSON output with "provenance": {"command", "inputs", ...} (orbit --format
// json, certify-sticking --json, sweep PREFIX.json) or a text/CSV output whose first line
// is "# bouncer VERSION (commit C) COMMAND" with an "# inputs: k=v ..." line (orbit csv and
// table, certify-sticking text, sweep PREFIX.csv; continue PREFIX.json and PREFIX.csv). The command is rerun with exactly the
// recorded inputs by this same binary, into a temporary directory, and the two outputs are
// compared.
//
// Compared: everything, numbers as the exact text they hold (not as parsed doubles), except
// these volatile fields:
//   * timings: JSON keys named "seconds" (at any depth); text lines starting "# time:";
//   * the invocation (binary path and command line): JSON provenance.invocation, text
//     line "# invocation:";
//   * the output location: JSON provenance.inputs.out and the top-level "files" of a
//     PREFIX.json, "out=..." in the text "# inputs:" line (the rerun writes elsewhere).
// Pictures (PNG, PDF, SVG) and proof certificates are refused with exit 2, naming what to audit or
// rerun instead.
// The version, commit, compiler, flags and library versions ARE compared: a result from
// another build is reported as different (with the field), even if its numbers agree.
//
// A `bouncer reproduce` directory is compared item by item (audit_reproduce below).
//
// Exit status: 0 identical, 1 different (the first difference is printed) or the rerun
// failed, 2 the file is not a result (or cannot be read).
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "audit.hpp"
#include "bouncer/base/cancel.hpp"
#include "bouncer/base/input.hpp"
#include "bouncer/workflow/child_process.hpp"
#include "bouncer/workflow/commands.hpp"
#include "cli_common.hpp"
#include "command_line.hpp"
#include "commands.hpp"
#include "run_command.hpp"

namespace bouncer::cli {

namespace {

using json = nlohmann::ordered_json;

struct Recorded {
  bool is_json = false;
  std::string command;
  std::vector<std::pair<std::string, std::string>> inputs;
};

// A file of the audited result or of the rerun (bounded, never a FIFO or device: a
// result file may come from a stranger). `ok` is false when it cannot be read.
std::string read_file(const std::string& path, bool& ok) {
  try {
    std::string text = read_input_file("file", path, kMaxResultBytes);
    ok = true;
    return text;
  } catch (const InputError&) {
    ok = false;
    return "";
  }
}

std::optional<Recorded> recorded_json(const std::string& text) {
  json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("provenance")) return std::nullopt;
  const json& p = j["provenance"];
  if (!p.is_object() || !p.contains("command") || !p["command"].is_string() || !p.contains("inputs") ||
      !p["inputs"].is_object())
    return std::nullopt;
  Recorded r;
  r.is_json = true;
  r.command = p["command"].get<std::string>();
  for (const auto& [k, v] : p["inputs"].items()) {
    if (!v.is_string()) return std::nullopt;
    r.inputs.emplace_back(k, v.get<std::string>());
  }
  return r;
}

// The "# inputs:" line's k=v tokens; a value may be quoted (provenance's quote_input).
// Empty on a malformed line.
std::optional<std::vector<std::pair<std::string, std::string>>> input_tokens(const std::string& line) {
  std::vector<std::pair<std::string, std::string>> out;
  size_t i = 0;
  while (true) {
    while (i < line.size() && line[i] == ' ') ++i;
    if (i >= line.size()) return out;
    const size_t eq = line.find('=', i);
    if (eq == std::string::npos) return std::nullopt;
    const std::string key = line.substr(i, eq - i);
    if (key.empty() || key.find(' ') != std::string::npos) return std::nullopt;
    i = eq + 1;
    std::string value;
    if (i < line.size() && line[i] == '"') {
      ++i;
      while (i < line.size() && line[i] != '"') {
        if (line[i] == '\\' && i + 1 < line.size()) ++i;
        value += line[i++];
      }
      if (i >= line.size()) return std::nullopt;  // no closing quote
      ++i;
    } else {
      while (i < line.size() && line[i] != ' ') value += line[i++];
    }
    out.emplace_back(key, value);
  }
}

std::optional<Recorded> recorded_text(const std::string& text) {
  std::istringstream in(text);
  std::string first;
  if (!std::getline(in, first) || first.rfind("# bouncer ", 0) != 0) return std::nullopt;
  // "# bouncer VERSION (commit C) COMMAND"
  const auto close = first.find(") ");
  if (close == std::string::npos) return std::nullopt;
  Recorded r;
  r.command = first.substr(close + 2);
  if (r.command.empty() || r.command.find(' ') != std::string::npos) return std::nullopt;
  std::string line;
  bool found = false;
  while (std::getline(in, line)) {
    if (line.rfind("# inputs:", 0) != 0) continue;
    const auto tokens = input_tokens(line.substr(9));
    if (!tokens) return std::nullopt;
    r.inputs = *tokens;
    found = true;
    break;
  }
  if (!found) return std::nullopt;
  return r;
}

// Runs argv in the directory `cwd` (audit's private temporary directory: a relative path in
// the command resolves there) with stdout into `out_path` (created there) and stderr
// discarded; returns the exit status (or -1). The child ends if audit is killed.
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

// audit's private temporary directory (mkdtemp: mode 0700, a new name), removed with all it
// holds when audit ends. Reruns write only here.
struct PrivateDir {
  std::string path;
  PrivateDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "bouncer-audit-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw OutputError("cannot create a temporary directory: " + std::string(std::strerror(errno)));
    path = tmpl;
  }
  ~PrivateDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  PrivateDir(const PrivateDir&) = delete;
  PrivateDir& operator=(const PrivateDir&) = delete;
};

// The JSON text with every number token turned into a string holding its exact text (marked
// by a leading U+0001), so that results are compared as the digits they hold: parsed as
// doubles, an edit of the 17th digit of a 20-digit number would compare equal.
std::string numbers_as_text(const std::string& in) {
  std::string out;
  out.reserve(in.size() + in.size() / 8);
  bool in_string = false;
  for (size_t i = 0; i < in.size(); ++i) {
    const char c = in[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < in.size()) out += in[++i];
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
      out += c;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      size_t j = i;
      while (j < in.size() && (std::isdigit(static_cast<unsigned char>(in[j])) || std::strchr("+-.eE", in[j]))) ++j;
      out += "\"\\u0001" + in.substr(i, j - i) + "\"";
      i = j - 1;
    } else {
      out += c;
    }
  }
  return out;
}

// Volatile JSON fields removed before comparing.
void strip_volatile(json& j, bool top) {
  if (j.is_object()) {
    j.erase("seconds");
    if (top) j.erase("files");  // where the outputs were written
    if (top && j.contains("provenance") && j["provenance"].is_object()) {
      j["provenance"].erase("invocation");
      if (j["provenance"].contains("inputs") && j["provenance"]["inputs"].is_object()) j["provenance"]["inputs"].erase("out");
    }
    for (auto& [k, v] : j.items()) strip_volatile(v, false);
  } else if (j.is_array()) {
    for (auto& v : j) strip_volatile(v, false);
  }
}

std::string short_dump(const json& j) {
  std::string s = j.dump();
  // Numbers were compared as their text (numbers_as_text): show them as numbers again.
  for (size_t at; (at = s.find("\"\\u0001")) != std::string::npos;) {
    const size_t end = s.find('"', at + 7);
    s = s.substr(0, at) + s.substr(at + 7, end - at - 7) + s.substr(end + 1);
  }
  return s.size() > 200 ? s.substr(0, 200) + "..." : s;
}

// Path of the first difference, or "" when equal.
std::string first_difference(const json& a, const json& b, const std::string& path, std::string& detail) {
  if (a.type() != b.type()) {
    detail = short_dump(a) + " vs " + short_dump(b);
    return path.empty() ? "(root)" : path;
  }
  if (a.is_object()) {
    for (const auto& [k, v] : a.items()) {
      const std::string p = path.empty() ? k : path + "." + k;
      if (!b.contains(k)) {
        detail = "present in the file, missing in the rerun";
        return p;
      }
      const std::string d = first_difference(v, b[k], p, detail);
      if (!d.empty()) return d;
    }
    for (const auto& [k, v] : b.items())
      if (!a.contains(k)) {
        detail = "missing in the file, present in the rerun";
        return path.empty() ? k : path + "." + k;
      }
    return "";
  }
  if (a.is_array()) {
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
      const std::string d = first_difference(a[i], b[i], path + "[" + std::to_string(i) + "]", detail);
      if (!d.empty()) return d;
    }
    if (a.size() != b.size()) {
      detail = std::to_string(a.size()) + " vs " + std::to_string(b.size()) + " elements";
      return path;
    }
    return "";
  }
  if (a != b) {
    detail = short_dump(a) + " vs " + short_dump(b);
    return path.empty() ? "(root)" : path;
  }
  return "";
}

std::vector<std::string> normalized_lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# invocation:", 0) == 0 || line.rfind("# time:", 0) == 0) continue;
    if (line.rfind("# inputs:", 0) == 0) {
      std::string kept = "# inputs:";
      for (const auto& [k, v] : input_tokens(line.substr(9)).value_or(std::vector<std::pair<std::string, std::string>>{}))
        if (k != "out") kept += " " + k + "=" + quote_input(v);
      line = kept;
    }
    out.push_back(line);
  }
  return out;
}

std::string self_path() {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : p.string();
}

// `bouncer audit DIR` for a `bouncer reproduce` directory: reruns the same reproduce (mode,
// --only, manifest) into a temporary directory with this binary and compares item by item:
// each claim's status, verdict and every check's value; each claim's JSON output and each
// panel's PREFIX.json and PREFIX.csv with the volatile fields removed as for single results
// (times, invocation, output paths); of a proof certificate, its verdicts and statements
// (its evidence strings hold timings). Pictures are compared through their CSV and JSON, not
// as PNG bytes. Exit 0 identical, 1 different or the rerun failed, 2 not a reproduce directory.
int audit_reproduce(const std::filesystem::path& dir, bool trust_manifest) {
  namespace fs = std::filesystem;
  bool ok = false;
  const std::string claims_path = (dir / "claims.json").string();
  const json old = json::parse(read_file(claims_path, ok), nullptr, false);
  auto not_reproduce = [&](const std::string& why) {
    throw InputError("file", "'" + claims_path + "' is not the claims.json of bouncer reproduce (" + why + ")");
  };
  if (!ok || old.is_discarded() || !old.contains("reproduce") || !old["reproduce"].is_object() ||
      !old["reproduce"].contains("mode") || !old["reproduce"]["mode"].is_string())
    not_reproduce("no reproduce.mode");
  // Its parts have the shape reproduce writes, checked before anything runs (a crafted file
  // must not start a long rerun only to be found malformed afterwards).
  auto entries = [&](const char* list, const char* key) {
    if (!old.contains(list)) return;
    if (!old[list].is_array()) not_reproduce(std::string("'") + list + "' is not a list");
    for (const json& e : old[list])
      if (!e.is_object() || !e.contains(key) || !e[key].is_string() ||
          (e.contains("status") && !e["status"].is_string()) || (e.contains("output") && !e["output"].is_string()) ||
          (e.contains("files") && !e["files"].is_array()))
        not_reproduce(std::string("an entry of '") + list + "' without a string '" + key + "'");
  };
  entries("claims", "id");
  entries("panels", "label");
  entries("pictures", "label");
  const json& r = old["reproduce"];
  // The rerun is built from what reproduce records, each part checked: a mode, ids that are
  // names (not paths or options), and the built-in manifest unless --trust-manifest.
  const std::string mode = r["mode"].get<std::string>();
  if (mode != "quick" && mode != "full" && mode != "pictures") not_reproduce("mode '" + mode + "'");
  std::vector<std::string> argv{self_path(), "reproduce", "--" + mode};
  if (r.contains("only") && r["only"].is_array() && !r["only"].empty()) {
    std::string only;
    for (const json& id : r["only"]) {
      if (!id.is_string() || !safe_name(id.get<std::string>())) not_reproduce("an --only id that is not a name");
      only += (only.empty() ? "" : ",") + id.get<std::string>();
    }
    argv.push_back("--only=" + only);
  }
  if (r.contains("manifest") && !r["manifest"].is_string()) not_reproduce("a manifest that is not a string");
  const std::string manifest = r.value("manifest", "");
  if (!manifest.empty() && manifest.find("(built in)") == std::string::npos) {
    if (!trust_manifest)
      throw InputError("file", "'" + claims_path + "' was made from the manifest '" + manifest +
                                   "', not bouncer's built-in one; audit runs another manifest's commands only when "
                                   "told to (--trust-manifest; they are then still limited to bouncer's computing "
                                   "commands, writing into audit's temporary directory)");
    argv.push_back("--manifest=" + fs::absolute(manifest).string());
  }
  const PrivateDir private_dir;
  const fs::path tmp = private_dir.path;
  argv.push_back("--out=" + (tmp / "r").string());
  const int status = run_to_file(argv, (tmp / "stdout").string(), tmp.string());
  const json now = json::parse(read_file((tmp / "r" / "claims.json").string(), ok), nullptr, false);
  if ((status != 0 && status != 1) || !ok || now.is_discarded()) {
    std::cerr << "bouncer audit: the rerun of reproduce failed (exit status " << status << ")\n";
    return 1;
  }
  std::vector<std::string> differences;
  size_t compared = 0;
  if (r.value("build", "") != now["reproduce"].value("build", ""))
    differences.push_back("build: " + r.value("build", "") + " vs " + now["reproduce"].value("build", ""));
  auto by_id = [](const json& list, const char* key) {
    std::map<std::string, json> m;
    if (list.is_array())
      for (const json& e : list) m[e.value(key, "")] = e;
    return m;
  };
  auto compare_file = [&](const std::string& rel) {
    // A name from the audited claims.json: one of reproduce's own subdirectories and a file
    // name in it, nothing else (never a path out of the directory).
    const auto slash = rel.find('/');
    const std::string sub = slash == std::string::npos ? "" : rel.substr(0, slash);
    if ((sub != "claims" && sub != "panels" && sub != "pictures") || !safe_name(rel.substr(slash + 1)))
      return differences.push_back("'" + one_line(rel, 120) + "': not a file of a reproduce directory");
    const std::string a = read_file((dir / rel).string(), ok);
    if (!ok) return differences.push_back(rel + ": missing in " + dir.string());
    const std::string b = read_file((tmp / "r" / rel).string(), ok);
    if (!ok) return differences.push_back(rel + ": missing in the rerun");
    ++compared;
    if (rel.size() > 4 && rel.substr(rel.size() - 4) == ".csv") {
      if (normalized_lines(a) != normalized_lines(b)) differences.push_back(rel + ": rows differ");
      return;
    }
    json ja = json::parse(numbers_as_text(a), nullptr, false), jb = json::parse(numbers_as_text(b), nullptr, false);
    if (ja.is_discarded() || jb.is_discarded()) {
      if (a != b) differences.push_back(rel + ": differs");
      return;
    }
    // A proof certificate's evidence strings carry timings ("(0.33 s)"): compare what it
    // concludes (verdicts and statements, overall and per sub-claim), not its evidence.
    auto conclusions = [](const json& j) {
      if (!j.is_object() || !j.contains("proof") || !j.contains("subclaims")) return j;
      json c{{"verdict", j.value("verdict", json())}, {"statement", j.value("statement", json())}, {"subclaims", json::array()}};
      if (j["subclaims"].is_array())
        for (const json& s : j["subclaims"])
          c["subclaims"].push_back({{"name", s.value("name", json())}, {"verdict", s.value("verdict", json())},
                                    {"statement", s.value("statement", json())}});
      return c;
    };
    ja = conclusions(ja);
    jb = conclusions(jb);
    strip_volatile(ja, true);
    strip_volatile(jb, true);
    std::string detail;
    if (const std::string where = first_difference(ja, jb, "", detail); !where.empty())
      differences.push_back(rel + ": " + where + ": " + detail);
  };
  const auto old_claims = by_id(old["claims"], "id"), new_claims = by_id(now["claims"], "id");
  for (const auto& [id, c] : old_claims) {
    const auto it = new_claims.find(id);
    if (it == new_claims.end()) {
      differences.push_back("claim " + id + ": not in the rerun");
      continue;
    }
    for (const char* k : {"status", "verdict", "checks"})
      if (c.value(k, json()) != it->second.value(k, json()))
        differences.push_back("claim " + id + ": " + k + ": " + short_dump(c.value(k, json())) + " vs " + short_dump(it->second.value(k, json())));
    if (c.contains("output") && c["output"].is_string() && c["status"] != "failed") compare_file(c["output"].get<std::string>());
  }
  for (const auto& [id, c] : new_claims)
    if (!old_claims.count(id)) differences.push_back("claim " + id + ": only in the rerun");
  // The paper's panels, and with reproduce --pictures the README's pictures: the same shape.
  for (const char* kind : {"panels", "pictures"}) {
    const std::string what = kind == std::string("panels") ? "panel " : "picture ";
    const auto old_panels = by_id(old.value(kind, json::array()), "label"), new_panels = by_id(now.value(kind, json::array()), "label");
    for (const auto& [label, p] : old_panels) {
      const auto it = new_panels.find(label);
      if (it == new_panels.end()) {
        differences.push_back(what + label + ": not in the rerun");
        continue;
      }
      if (p.value("status", "") != it->second.value("status", ""))
        differences.push_back(what + label + ": status " + p.value("status", "") + " vs " + it->second.value("status", ""));
      if (p.contains("files") && p["files"].is_array())
        for (const json& f : p["files"]) {
          if (!f.is_string()) continue;
          const std::string rel = f.get<std::string>();
          // Pictures embed the command line (with its --out path) in their metadata, so they are
          // compared through the CSV and JSON they are drawn from, not byte for byte.
          const std::string ext = rel.size() > 4 ? rel.substr(rel.size() - 4) : "";
          if (ext == ".png" || ext == ".pdf" || ext == ".svg") continue;
          compare_file(rel);
        }
    }
    for (const auto& [label, p] : new_panels)
      if (!old_panels.count(label)) differences.push_back(what + label + ": only in the rerun");
  }
  if (differences.empty()) {
    command_out() << "bouncer audit: identical: " << old_claims.size() << " claims (verdicts and checks) and " << compared
              << " outputs of " << dir.string() << " match the rerun (times, invocations and output paths ignored; "
              "pictures compared through their CSV and JSON)\n";
    return 0;
  }
  command_out() << "bouncer audit: DIFFERENT: " << differences.size() << " difference(s) in " << dir.string() << "\n";
  for (const std::string& d : differences) command_out() << "  " << d << "\n";
  return 1;
}

}  // namespace

AuditPlan plan_rerun(const std::string& path, const std::string& text, const std::string& dir, const std::string& self) {
  // Kinds that carry no rerunnable provenance are refused up front, with what to do instead.
  if (text.rfind("\x89PNG", 0) == 0 || text.rfind("%PDF-", 0) == 0 ||
      (text.rfind("<?xml", 0) == 0 && text.find("<svg", 0) != std::string::npos))
    throw InputError("file", "'" + path + "' is a picture; audit the PREFIX.json or PREFIX.csv written beside it "
                             "(same provenance, exact numbers)");
  if (const json j = json::parse(text, nullptr, false); j.is_object() && j.contains("proof") && j.contains("claim"))
    throw InputError("file", "'" + path + "' is a proof certificate; rerun its proof (build/proofs/proof_" +
                                 (j["proof"].is_string() && safe_name(j["proof"].get<std::string>()) ? j["proof"].get<std::string>()
                                                                                                   : std::string("NAME")) +
                                 " --json) and compare, as the README's proofs section shows");
  std::optional<Recorded> rec = recorded_json(text);
  if (!rec) rec = recorded_text(text);
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
  std::string& compare_path = plan.compare_path;
  compare_path = dir + "/stdout";
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
    compare_path = dir + "/result.json";
  } else if (rec->is_json && !has_out) {
    // Commands that print JSON on stdout with --json; orbit chooses it with --format.
    bool chosen = false;
    for (const auto& [k, v] : rec->inputs) chosen = chosen || k == "json" || (k == "format" && rec->command == "orbit");  // elsewhere --format names pictures
    if (!chosen) argv.push_back("--json");
  }
  if (has_out) {
    if (rec->command == "sweep" || rec->command == "continue") {  // PREFIX.json / PREFIX.csv
      const std::string ext = std::filesystem::path(path).extension().string();  // .json / .csv
      argv.push_back("--out");
      argv.push_back(dir + "/result");
      compare_path = dir + "/result" + ext;
    } else {
      argv.push_back("--out");
      argv.push_back(dir + "/result");
      compare_path = dir + "/result";
    }
  }
  return plan;
}

namespace {

int audit(const std::string& path, bool trust_manifest) {
  // A `bouncer reproduce` directory: compared item by item (audit_reproduce).
  if (std::error_code ec; std::filesystem::is_directory(path, ec)) {
    if (std::filesystem::exists(std::filesystem::path(path) / "claims.json", ec)) return audit_reproduce(path, trust_manifest);
    throw InputError("file", "'" + path + "' is a directory without claims.json; give a result file (JSON or CSV "
                             "written by bouncer) or a bouncer reproduce directory");
  }
  const std::string text = read_input_file("file", path, kMaxResultBytes);
  if (const json j = json::parse(text, nullptr, false); j.is_object() && j.contains("reproduce") && j.contains("claims")) {
    return audit_reproduce(std::filesystem::path(path).parent_path().empty() ? std::filesystem::path(".")
                                                                              : std::filesystem::path(path).parent_path(),
                           trust_manifest);
  }
  const PrivateDir private_dir;
  const std::string dir = private_dir.path;
  const AuditPlan plan = plan_rerun(path, text, dir, self_path());
  const std::vector<std::string>& argv = plan.argv;
  const std::string& compare_path = plan.compare_path;
  // The rebuilt command is validated as the command line validates it, in this process and
  // before anything is started: its options parsed and checked, stopped at its first step.
  {
    std::vector<std::string> words{"bouncer"};
    words.insert(words.end(), argv.begin() + 1, argv.end());
    const std::atomic<bool> stop{true};
    const CancelScope cancel(&stop);
    CommandCapture swallow;
    const CaptureScope capture(&swallow);
    const CommandOutcome r = run_command(words, false);
    if (r.kind == CommandOutcome::Kind::input)
      throw InputError("file", "'" + path + "' records inputs that bouncer refuses: " + r.message);
  }
  const auto* rec = &plan;
  command_out() << "audit: rerunning `bouncer " << rec->command;
  for (size_t i = 2; i < argv.size(); ++i) command_out() << " " << (argv[i].rfind(dir, 0) == 0 ? "<tmp>" + argv[i].substr(dir.size()) : argv[i]);
  command_out() << "`\n";
  const int status = run_to_file(argv, dir + "/stdout", dir);
  if (status != 0) {
    command_out() << "audit: DIFFERENT: the rerun failed (exit status " << status << ")\n";
    return 1;
  }
  bool ok2 = false;
  const std::string again = read_file(compare_path, ok2);
  if (!ok2) {
    command_out() << "audit: DIFFERENT: the rerun wrote no result\n";
    return 1;
  }
  if (rec->is_json) {
    json a = json::parse(numbers_as_text(text), nullptr, false), b = json::parse(numbers_as_text(again), nullptr, false);
    if (b.is_discarded()) {
      command_out() << "audit: DIFFERENT: the rerun's output is not JSON\n";
      return 1;
    }
    strip_volatile(a, true);
    strip_volatile(b, true);
    std::string detail;
    const std::string where = first_difference(a, b, "", detail);
    if (!where.empty()) {
      command_out() << "audit: DIFFERENT: first difference at " << where << ": " << detail << " (file vs rerun)\n";
      return 1;
    }
  } else {
    const std::vector<std::string> a = normalized_lines(text), b = normalized_lines(again);
    for (size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
      const std::string la = i < a.size() ? a[i] : "<end of file>", lb = i < b.size() ? b[i] : "<end of output>";
      if (la != lb) {
        command_out() << "audit: DIFFERENT: first difference at line " << i + 1 << " (volatile lines skipped):\n  file:  "
                  << la << "\n  rerun: " << lb << "\n";
        return 1;
      }
    }
  }
  command_out() << "audit: IDENTICAL: the rerun reproduces '" << path
            << "' bit for bit (volatile fields skipped: timings, invocation, output location)\n";
  return 0;
}

}  // namespace

CommandRunner setup_audit(CLI::App* sub) {
  auto file = std::make_shared<std::string>();
  auto trust = std::make_shared<bool>(false);
  sub->add_option("file", *file, "A JSON or CSV/text result written by bouncer, or a bouncer reproduce directory")->required();
  sub->add_flag("--trust-manifest", *trust,
                "Rerun a reproduce directory made from another manifest than bouncer's built-in one (its commands are "
                "still limited to bouncer's computing commands, writing into audit's temporary directory)");
  auto run = [file, trust](const std::string&) {
    try {
      return audit(*file, *trust);
    } catch (const nlohmann::json::exception& e) {  // a crafted file whose parts have other types
      throw InputError("file", "'" + *file + "' is malformed: " + e.what());
    }
  };
  return run;
}

}  // namespace bouncer::cli
