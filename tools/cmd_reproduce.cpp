// bouncer reproduce: the whole paper in one command. Reads the manifest data/paper/manifest.toml
// (compiled in; --manifest FILE for another), runs every figure panel and every claim as a
// subprocess of this same binary (/proc/self/exe) or of a proof binary next to it
// (build/proofs/proof_NAME beside build/tools/bouncer), N at a time, and writes
//   DIR/report.md, DIR/report.html  every panel beside the paper's caption, the claims table,
//                                   provenance per item; times only in the "Times" section
//   DIR/claims.json                 per claim: expected verdict, this run's verdict, checks;
//                                   per panel: status and files; times only in "seconds" keys
//   DIR/panels/NAME.{png,csv,json}  the panels' outputs;  DIR/claims/ID.json  claims' outputs
//   DIR/logs/ID.stdout|stderr       what each subprocess printed;  DIR/keys/ID.key  resume keys
// An item whose key (mode, argv, build version and commit) matches DIR/keys/ID.key and whose
// outputs exist is not rerun (resumable). Exit 0: every item ran and every claim's check
// reproduced its expected verdict; 1: an item failed or a check did not hold (the report says
// which); 2: bad options. `bouncer audit DIR` reruns a reproduce directory and compares it
// item by item (tools/cmd_audit.cpp).
#pragma GCC diagnostic push
#if !defined(__clang__)  // clang has no such warning (the fuzzing build, tests/fuzz/)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nlohmann/json.hpp>
#pragma GCC diagnostic pop
#include <toml++/toml.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <memory>
#include <sstream>
#include <thread>

#include "bouncer/base/input.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/workflow/child_process.hpp"
#include "bouncer/workflow/commands.hpp"
#include "cli_common.hpp"
#include "command_line.hpp"
#include "commands.hpp"
#include "bouncer/base/cancel.hpp"
#include "paper_manifest.hpp"
#include "run_command.hpp"

namespace bouncer::cli {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

struct Panel {
  // twin_of: not a panel of the paper but bouncer's certified twin of one (label
  // fig:NAME-certified): the same picture from `basin --certify`, with its artefact map.
  std::string label, figure, panel, caption, note, scene, status, reason, twin_of;
  // tiles_from: the label of an earlier panel whose grid is this one's too (only the
  // picture differs, e.g. --show): computed once, drawn twice.
  std::string tiles_from;
  std::vector<std::pair<std::string, std::string>> params;
  std::vector<std::string> quick, full;
  std::string name() const { return label.rfind("fig:", 0) == 0 ? label.substr(4) : label; }
};

struct Check {
  std::string path, op;
  json value;
  std::string text() const { return path + " " + op + " " + value.dump(); }
};

struct Claim {
  std::string id, row, text, paper, expected, verdict, evidence, rerun;
  std::vector<long> groups;
  std::vector<std::string> run, full_run;
  bool quick = true;
  std::vector<Check> checks;
};

// [[picture]]: a picture of bouncer's README (data/pictures/NAME.png), not of the paper.
struct Picture {
  std::string name, readme, about;
  std::vector<std::string> command;
  std::vector<std::string> files;  // the pictures it writes (default NAME.png)
  std::string id() const { return "picture:" + name; }
};

struct Manifest {
  std::vector<Panel> panels;
  std::vector<Claim> claims;
  std::vector<Picture> pictures;
};

std::string str(const toml::table& t, const std::string& key, const std::string& where, bool required = true) {
  if (auto v = t[key].value<std::string>()) return *v;
  if (required) throw InputError("manifest", where + ": missing string key '" + key + "'");
  return "";
}

std::vector<std::string> argv_of(const toml::table& t, const std::string& key, const std::string& where) {
  std::vector<std::string> out;
  const toml::array* a = t[key].as_array();
  if (!a) return out;
  for (const auto& e : *a) {
    auto s = e.value<std::string>();
    if (!s) throw InputError("manifest", where + ": '" + key + "' must be a list of strings");
    out.push_back(*s);
  }
  return out;
}

json to_json(const toml::node& n) {
  if (auto s = n.value_exact<std::string>()) return *s;
  if (auto b = n.value_exact<bool>()) return *b;
  if (auto i = n.value_exact<int64_t>()) return *i;
  if (auto d = n.value_exact<double>()) return *d;
  return nullptr;
}

const std::vector<std::string>& verdict_words() {
  static const std::vector<std::string> w{"confirmed", "refuted", "corrected", "not reproduced", "consistent"};
  return w;
}

// A manifest is data, and may come from someone else (`reproduce --manifest FILE`, or the
// manifest a reproduce directory names, which `audit DIR` reruns). What it may ask for is
// bounded here, for the built-in manifest too:
//   * its ids, labels and file names become file names in the reproduce directory: letters,
//     digits and . _ : + - only, no "..", at most 100 characters (no '/', so nothing is
//     written outside the directory);
//   * every command is one of bouncer's computing commands, or a proof program beside it
//     with --full, --json, --bits only: never reproduce, audit or merge (a manifest that ran
//     itself spawned hundreds of processes), and never an option that chooses where a
//     command reads tiles or writes (--out, --tiles-from, --keep-tiles, --shard): reproduce
//     gives each command its place in the directory. --scene names a scene built into
//     bouncer (data/scenes/), not a file.
std::string command_problem(const std::vector<std::string>& argv) {
  if (argv.empty()) return "";
  for (const std::string& w : argv)
    if (w.find('\0') != std::string::npos || w.size() > 4096) return "a word is longer than 4096 characters or holds a NUL byte";
  if (argv[0].rfind("proof_", 0) == 0) {
    const std::string name = argv[0].substr(6);
    if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos)
      return "'" + argv[0] + "' is not a proof program's name (proof_ and lower-case letters, digits, _)";
    for (size_t i = 1; i < argv.size(); ++i) {
      if (argv[i] == "--full" || argv[i] == "--json") continue;
      if (argv[i] == "--bits" && i + 1 < argv.size()) {
        ++i;
        continue;
      }
      return "a proof program takes only --full, --json and --bits N (got '" + argv[i] + "')";
    }
    return "";
  }
  if (argv[0] != "bouncer") return "must start with bouncer or proof_NAME, not '" + argv[0] + "'";
  if (argv.size() < 2 || !is_computing_command(argv[1])) {
    std::set<std::string> commands;  // (sorted, for the message)
    for (const CommandInfo& c : command_table())
      if (c.kind == CommandKind::computing) commands.emplace(c.name);
    std::string list;
    for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
    return "runs '" + (argv.size() < 2 ? std::string() : argv[1]) + "': a manifest runs only " + list;
  }
  static const std::set<std::string> placed{"--out", "--tiles-from", "--keep-tiles", "--shard", "--manifest"};
  for (size_t i = 2; i < argv.size(); ++i) {
    const std::string name = argv[i].substr(0, argv[i].find('='));
    if (placed.count(name)) return "gives " + name + ": reproduce chooses where each command writes";
    if (name == "--scene") {
      const std::string value = argv[i].size() > name.size() ? argv[i].substr(name.size() + 1)
                                : i + 1 < argv.size()         ? argv[i + 1]
                                                              : std::string();
      if (!paper_scenes().count(value)) return "--scene '" + value + "' is not a scene of data/scenes/ (built in)";
    }
  }
  return "";
}

Manifest parse_manifest(const std::string& text, const std::string& source) {
  check_toml_text("manifest", text, source, kMaxManifestBytes);
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw InputError("manifest", source + ": " + std::string(e.description()));
  }
  Manifest m;
  if (const toml::array* ps = root["panel"].as_array())
    for (const auto& node : *ps) {
      const toml::table* t = node.as_table();
      if (!t) throw InputError("manifest", source + ": [[panel]] must be tables");
      Panel p;
      p.label = str(*t, "label", source + " panel");
      const std::string where = source + " panel " + p.label;
      p.figure = str(*t, "figure", where);
      p.panel = str(*t, "panel", where, false);
      p.caption = str(*t, "caption", where);
      p.note = str(*t, "note", where, false);
      p.scene = str(*t, "scene", where, false);
      p.status = str(*t, "status", where);
      p.reason = str(*t, "reason", where, false);
      p.twin_of = str(*t, "twin_of", where, false);
      p.tiles_from = str(*t, "tiles_from", where, false);
      if (!p.tiles_from.empty() &&
          std::none_of(m.panels.begin(), m.panels.end(), [&](const Panel& q) { return q.label == p.tiles_from; }))
        throw InputError("manifest", where + ": tiles_from '" + p.tiles_from + "' is not the label of an earlier panel");
      if (const toml::table* params = (*t)["params"].as_table())
        for (const auto& [k, v] : *params) p.params.emplace_back(std::string(k.str()), v.value<std::string>().value_or(""));
      if (!safe_name(p.label) || (!p.twin_of.empty() && !safe_name(p.twin_of)))
        throw InputError("manifest", where + ": a label must be a safe file name (letters, digits, . _ : + -; no '..')");
      p.quick = argv_of(*t, "quick", where);
      p.full = argv_of(*t, "full", where);
      for (const auto* argv : {&p.quick, &p.full})
        if (const std::string problem = command_problem(*argv); !problem.empty())
          throw InputError("manifest", where + ": command " + problem);
      if (p.status != "ready" && p.status != "pending") throw InputError("manifest", where + ": status must be ready or pending");
      if (p.status == "pending" && p.reason.empty()) throw InputError("manifest", where + ": a pending panel needs a reason");
      if (p.status == "ready" && (p.quick.empty() || p.full.empty()))
        throw InputError("manifest", where + ": a ready panel needs quick and full commands");
      m.panels.push_back(std::move(p));
    }
  if (const toml::array* cs = root["claim"].as_array())
    for (const auto& node : *cs) {
      const toml::table* t = node.as_table();
      if (!t) throw InputError("manifest", source + ": [[claim]] must be tables");
      Claim c;
      c.id = str(*t, "id", source + " claim");
      const std::string where = source + " claim " + c.id;
      if (!safe_name(c.id))
        throw InputError("manifest", where + ": an id must be a safe file name (letters, digits, . _ : + -; no '..')");
      c.row = str(*t, "row", where);
      c.text = str(*t, "text", where);
      c.paper = str(*t, "paper", where);
      c.expected = str(*t, "expected", where);
      c.verdict = str(*t, "verdict", where);
      c.evidence = str(*t, "evidence", where);
      c.rerun = str(*t, "rerun", where);
      if (std::find(verdict_words().begin(), verdict_words().end(), c.expected) == verdict_words().end())
        throw InputError("manifest", where + ": expected must be confirmed, refuted, corrected, not reproduced or consistent");
      if (const toml::array* g = (*t)["groups"].as_array())
        for (const auto& e : *g) c.groups.push_back(e.value<int64_t>().value_or(0));
      c.run = argv_of(*t, "run", where);
      c.full_run = argv_of(*t, "full_run", where);
      if (c.run.empty()) throw InputError("manifest", where + ": needs a run command");
      if (c.full_run.empty()) {
        c.full_run = c.run;
        if (c.run[0].rfind("proof_", 0) == 0) c.full_run.push_back("--full");
      }
      for (const auto* argv : {&c.run, &c.full_run})
        if (const std::string problem = command_problem(*argv); !problem.empty())
          throw InputError("manifest", where + ": command " + problem);
      c.quick = (*t)["quick"].value<bool>().value_or(true);
      if (const toml::array* ch = (*t)["checks"].as_array())
        for (const auto& e : *ch) {
          const toml::array* triple = e.as_array();
          if (!triple || triple->size() != 3 || !(*triple)[0].is_string() || !(*triple)[1].is_string())
            throw InputError("manifest", where + ": each check is [PATH, OP, VALUE]");
          Check k{*(*triple)[0].value<std::string>(), *(*triple)[1].value<std::string>(), to_json(*triple->get(2))};
          static const std::vector<std::string> ops{"==", "!=", "<", "<=", ">", ">=", "has", "lacks"};
          if (std::find(ops.begin(), ops.end(), k.op) == ops.end())
            throw InputError("manifest", where + ": unknown check operator '" + k.op + "' (== != < <= > >= has lacks)");
          c.checks.push_back(std::move(k));
        }
      if (c.checks.empty()) throw InputError("manifest", where + ": needs at least one check");
      m.claims.push_back(std::move(c));
    }
  if (const toml::array* ps = root["picture"].as_array())
    for (const auto& node : *ps) {
      const toml::table* t = node.as_table();
      if (!t) throw InputError("manifest", source + ": [[picture]] must be tables");
      Picture p;
      p.name = str(*t, "name", source + " picture");
      const std::string where = source + " picture " + p.name;
      if (!safe_name(p.name))
        throw InputError("manifest", where + ": name must be a safe file name without extension (letters, digits, . _ : + -)");
      p.readme = str(*t, "readme", where);
      p.about = str(*t, "about", where);
      p.command = argv_of(*t, "command", where);
      if (p.command.empty()) throw InputError("manifest", where + ": needs a command");
      p.files = argv_of(*t, "files", where);
      if (p.files.empty()) p.files = {p.name + ".png"};
      for (const std::string& f : p.files)
        if (!safe_name(f)) throw InputError("manifest", where + ": file '" + f + "' must be a safe file name");
      if (const std::string problem = command_problem(p.command); !problem.empty())
        throw InputError("manifest", where + ": command " + problem);
      m.pictures.push_back(std::move(p));
    }
  return m;
}

// ---------------------------------------------------------------- the check language
// Resolves PATH in j: "a.b.0.c"; a "*" segment maps over an array (the result is then an
// array of the values found). Returns nullopt when the path does not exist.
std::optional<json> resolve(const json& j, const std::vector<std::string>& segs, size_t i) {
  if (i == segs.size()) return j;
  const std::string& s = segs[i];
  if (s == "*") {
    if (!j.is_array()) return std::nullopt;
    json out = json::array();
    for (const json& e : j)
      if (auto r = resolve(e, segs, i + 1)) {
        if (std::find(segs.begin() + i + 1, segs.end(), "*") != segs.end() && r->is_array())
          for (const json& x : *r) out.push_back(x);
        else
          out.push_back(*r);
      }
    return out;
  }
  if (j.is_object()) {
    if (!j.contains(s)) return std::nullopt;
    return resolve(j[s], segs, i + 1);
  }
  if (j.is_array() && !s.empty() && std::all_of(s.begin(), s.end(), ::isdigit)) {
    const size_t k = std::stoul(s);
    if (k >= j.size()) return std::nullopt;
    return resolve(j[k], segs, i + 1);
  }
  return std::nullopt;
}

std::optional<double> number(const json& v) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    char* end = nullptr;
    const double d = std::strtod(s.c_str(), &end);
    if (!s.empty() && end == s.c_str() + s.size() && std::isfinite(d)) return d;
  }
  return std::nullopt;
}

bool equal(const json& a, const json& b) {
  if (a.is_number() && b.is_number()) return a.get<double>() == b.get<double>();
  return a == b;
}

// Evaluates one check; `got` receives the value found (or "missing").
bool holds(const Check& c, const json& doc, std::string& got) {
  std::vector<std::string> segs;
  std::stringstream ss(c.path);
  for (std::string s; std::getline(ss, s, '.');) segs.push_back(s);
  const std::optional<json> v = resolve(doc, segs, 0);
  if (!v) {
    got = "missing";
    return false;
  }
  got = v->dump();
  if (got.size() > 200) got = got.substr(0, 200) + "...";
  if (c.op == "has" || c.op == "lacks") {
    if (!v->is_array()) return false;
    const bool found = std::any_of(v->begin(), v->end(), [&](const json& x) { return equal(x, c.value); });
    return c.op == "has" ? found : !found;
  }
  if (c.op == "==") return equal(*v, c.value);
  if (c.op == "!=") return !equal(*v, c.value);
  const auto x = number(*v), y = number(c.value);
  if (!x || !y) return false;
  if (c.op == "<") return *x < *y;
  if (c.op == "<=") return *x <= *y;
  if (c.op == ">") return *x > *y;
  return *x >= *y;
}

// ---------------------------------------------------------------- running items
struct Item {
  std::string id;         // claim id or panel label
  bool is_claim = false;
  bool is_picture = false;  // a README picture (index into pictures)
  bool is_panel() const { return !is_claim && !is_picture; }
  size_t index = 0;       // into panels or claims
  std::vector<std::string> argv;  // as in the manifest (display)
  std::vector<std::string> exec;  // resolved
  std::string stdout_path, stderr_path, key_path, key;
  std::vector<std::string> outputs;  // must exist after success (relative to DIR)
  std::shared_ptr<OutputSet> files;  // stdout and stderr, staged while it runs
  // A panel drawn from the grid of an earlier item (manifest tiles_from): that item's index,
  // and the tile prefix it keeps for this one. It starts when that item has finished.
  std::optional<size_t> after;
  std::string tiles_prefix;  // set on the item that keeps its tiles (DIR/panels/NAME)
  // results
  std::string state = "pending";  // pending, done, cached, failed, deferred, skipped
  std::string problem;
  int exit_status = 0;
  double seconds = 0;
};

// Set in the environment of reproduce's children: a reproduce started inside one refuses.
constexpr const char* kInReproduce = "BOUNCER_IN_REPRODUCE";

std::string shell_word(const std::string& w) {
  if (!w.empty() && w.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.,:/=+") == std::string::npos)
    return w;
  std::string q = "'";
  for (char ch : w) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

std::string command_text(const std::vector<std::string>& argv) {
  std::string s;
  for (size_t i = 0; i < argv.size(); ++i) {
    std::string w = argv[i];
    if (i == 0 && w.rfind("proof_", 0) == 0) w = "build/proofs/" + w;
    s += (i ? " " : "") + shell_word(w);
  }
  return s;
}

// A file of the reproduce directory ("" when absent): a regular file of at most 1 GiB, never
// a FIFO or device planted there (InputError naming --out).
std::string read_text(const fs::path& p) {
  return read_input_file_if_present("out", p.string(), kMaxResultBytes).value_or("");
}

void write_text(const fs::path& p, const std::string& text) {
  write_output_set({{p.string(), [&](std::ostream& s) { s << text; }}});
}

std::optional<fs::path> find_proof(const fs::path& exe_dir, const std::string& name) {
  for (const fs::path& p : {exe_dir / ".." / "proofs" / name, exe_dir / name}) {
    std::error_code ec;
    if (fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0) return fs::weakly_canonical(p, ec);
  }
  return std::nullopt;
}

// SIGINT, SIGTERM and SIGHUP caught while reproduce waits for its children (installed
// without SA_RESTART, so waitpid returns EINTR); restored on destruction. reraise() ends the
// process by the caught signal, with the default action, as the shell expects.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void note_stop_signal(int sig) { g_stop_signal = sig; }
class StopSignals {
 public:
  StopSignals() {
    g_stop_signal = 0;
    struct sigaction sa {};
    sa.sa_handler = note_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    for (size_t i = 0; i < std::size(kSignals); ++i) {
      ::sigaction(kSignals[i], &sa, &old_[i]);
      // A signal ignored when reproduce started (nohup; SIGINT of a background job) stays so.
      if (old_[i].sa_handler == SIG_IGN) ::sigaction(kSignals[i], &old_[i], nullptr);
    }
  }
  ~StopSignals() {
    for (size_t i = 0; i < std::size(kSignals); ++i) ::sigaction(kSignals[i], &old_[i], nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  int caught() const { return g_stop_signal; }
  [[noreturn]] void reraise() const {
    const int sig = g_stop_signal;
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    ::sigaction(sig, &dfl, nullptr);
    std::cerr.flush();
    ::raise(sig);
    std::_Exit(128 + sig);
  }

 private:
  static constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction old_[std::size(kSignals)] {};
};

// A `--scene data/scenes/NAME.toml` of a manifest command names a scene compiled into the
// binary (tools/CMakeLists.txt), so reproduce runs from any directory: the scene is written
// to SCENE_DIR/NAME.toml and the command reads it there. Returns a problem, or "".
std::string resolve_scenes(std::vector<std::string>& exec, const fs::path& scene_dir) {
  for (size_t i = 1; i < exec.size(); ++i) {
    if (exec[i - 1] != "--scene") continue;
    const auto it = paper_scenes().find(exec[i]);
    if (it == paper_scenes().end()) return "scene '" + exec[i] + "' is not one of data/scenes/ (built in)";
    const fs::path file = scene_dir / fs::path(exec[i]).filename();
    make_own_directory("out", scene_dir.string());
    write_text(file, it->second);
    exec[i] = file.string();
  }
  return "";
}

// Starts an item: its stdout and stderr go to staging files of the reproduce directory
// (created afresh, never through a planted link), renamed into place when it ends.
pid_t spawn(Item& it) {
  it.files = std::make_shared<OutputSet>();
  it.files->reserve("out", it.stdout_path);
  it.files->reserve("out", it.stderr_path);
  return start_child(it.exec, it.files->descriptor(it.stdout_path), it.files->descriptor(it.stderr_path), "",
                     {std::string(kInReproduce) + "=1"});
}

std::string html_escape(const std::string& s) {
  std::string o;
  for (char ch : s) switch (ch) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += ch;
    }
  return o;
}

// The Markdown inline marks the manifest's texts use (`code`, **bold**, \| inside a table
// cell) as HTML, everything else escaped: the HTML report shows what report.md shows.
std::string md_inline_html(const std::string& s) {
  std::string o;
  bool bold = false;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '`') {
      const size_t end = s.find('`', i + 1);
      if (end != std::string::npos) {
        o += "<code>" + html_escape(s.substr(i + 1, end - i - 1)) + "</code>";
        i = end;
        continue;
      }
    }
    if (s.compare(i, 2, "**") == 0) {
      o += bold ? "</strong>" : "<strong>";
      bold = !bold;
      ++i;
      continue;
    }
    if (s.compare(i, 2, "\\|") == 0) {
      o += "|";
      ++i;
      continue;
    }
    o += html_escape(std::string(1, s[i]));
  }
  if (bold) o += "</strong>";
  return o;
}

std::string md_cell(std::string s) {
  for (char& ch : s)
    if (ch == '\n') ch = ' ';
  return s;
}

std::string fixed(double x, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

struct Options_ {
  bool quick = false, full = false, claims_table = false, check = false, pictures = false;
  std::string out = "reproduction", only, jobs, manifest;
};

std::string claims_table(const Manifest& m) {
  std::string t = "| # | Claim (paper) | Verdict | Evidence | Rerun |\n|---|---|---|---|---|\n";
  for (const Claim& c : m.claims)
    t += "| " + c.row + " | " + md_cell(c.text) + " | " + md_cell(c.verdict) + " | " + md_cell(c.evidence) + " | " +
         md_cell(c.rerun) + " |\n";
  return t;
}

// --check: every command of the manifest, quick and full, is parsed and validated without
// being run: each bouncer command runs in this process with its cancellation flag already
// set (base/cancel.hpp), so it validates its options and inputs as it always does and stops at
// its first step; proof binaries must exist. Prints one line per command; exit 1 if any
// command is refused.
int check_manifest(const Manifest& m, const fs::path& exe_dir) {
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
  long checked = 0, refused = 0;
  auto check = [&](const std::string& id, const std::string& which, std::vector<std::string> argv, bool panel) {
    if (argv.empty()) return;
    ++checked;
    std::string verdict;
    if (argv[0].rfind("proof_", 0) == 0) {
      verdict = find_proof(exe_dir, argv[0]) ? "ok (proof binary found)" : "refused: proof binary " + argv[0] + " not found";
    } else if (argv[0] != "bouncer") {
      verdict = "refused: must start with bouncer or proof_NAME";
    } else if (const std::string problem = resolve_scenes(argv, tmp / "scenes"); !problem.empty()) {
      verdict = "refused: " + problem;
    } else {
      if (panel) argv.insert(argv.end(), {"--out", (tmp / (std::to_string(checked) + "-x")).string(), "--quiet", "--format", "png,pdf,svg"});
      const std::atomic<bool> stop{true};
      const CancelScope cancel(&stop);
      CommandCapture swallow;
      const CaptureScope capture(&swallow);
      const CommandOutcome r = run_command(argv, false);
      using K = CommandOutcome::Kind;
      verdict = r.kind == K::cancelled ? "ok (validated; stopped at its first step)"
                : r.kind == K::ok      ? "ok (ran: nothing long to stop)"
                                       : "refused (exit " + std::to_string(r.status) + "): " + r.message;
    }
    if (verdict.rfind("ok", 0) != 0) ++refused;
    command_out() << id << " " << which << ": " << verdict << "\n";
  };
  for (const Panel& p : m.panels) {
    check(p.label, "quick", p.quick, true);
    check(p.label, "full", p.full, true);
  }
  for (const Claim& c : m.claims) {
    check(c.id, "run", c.run, false);
    if (c.full_run != c.run) check(c.id, "full_run", c.full_run, false);
  }
  for (const Picture& p : m.pictures) check(p.id(), "command", p.command, true);
  command_out() << checked << " commands checked, " << refused << " refused\n";
  return refused ? 1 : 0;
}

int run_reproduce(const Options_& o) {
  if (const char* inside = std::getenv(kInReproduce); inside && *inside)
    throw InputError("reproduce", "runs no reproduce inside another (a manifest runs bouncer's computing commands only)");
  if (o.quick && o.full) throw InputError("quick", "give one of --quick or --full, not both");
  if (o.pictures && (o.quick || o.full))
    throw InputError("pictures", "draws the README's pictures, the same in every mode: give it without --quick or --full");
  const std::string mode = o.pictures ? "pictures" : o.full ? "full" : "quick";
  std::string text = kPaperManifest, source = "data/paper/manifest.toml (built in)";
  if (!o.manifest.empty()) {
    text = read_input_file("manifest", o.manifest, kMaxManifestBytes);
    source = o.manifest;
  }
  const Manifest m = parse_manifest(text, source);
  if (o.claims_table) {
    command_out() << claims_table(m);
    return 0;
  }
  if (o.check) {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw OutputError("cannot locate this binary (/proc/self/exe): " + ec.message());
    return check_manifest(m, exe.parent_path());
  }
  unsigned jobs = std::max(1u, std::thread::hardware_concurrency());
  if (!o.jobs.empty()) {
    const bool digits = std::all_of(o.jobs.begin(), o.jobs.end(), ::isdigit);
    if (!digits || o.jobs.size() > 4 || std::stoi(o.jobs) < 1 || std::stoi(o.jobs) > 1024)
      throw InputError("jobs", "must be an integer in [1, 1024], got '" + o.jobs + "'");
    jobs = static_cast<unsigned>(std::stoi(o.jobs));
  }
  // Every item's id: claims by id, panels by label (also accepted without "fig:"); with
  // --pictures, the README pictures (picture:NAME, also accepted as NAME).
  std::vector<std::string> ids;
  if (o.pictures) {
    for (const Picture& p : m.pictures) ids.push_back(p.id());
  } else {
    for (const Panel& p : m.panels) ids.push_back(p.label);
    for (const Claim& c : m.claims) ids.push_back(c.id);
  }
  std::set<std::string> only;
  if (!o.only.empty()) {
    std::stringstream ss(o.only);
    for (std::string w; std::getline(ss, w, ',');) {
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
                                     (o.pictures ? "; with --pictures, items are the README pictures (picture:NAME) of data/paper/manifest.toml"
                                                 : "; items are the panel labels (fig:...) and claim ids of data/paper/manifest.toml"));
      }
      only.insert(id);
    }
    if (only.empty()) throw InputError("only", "give a comma list of panel labels and claim ids");
  }
  // The output directory.
  const fs::path dir = o.out;
  if (o.out.empty()) throw InputError("out", "must name a directory");
  {
    // DIR is the user's (it may be a link to a directory they chose); its subdirectories are
    // bouncer's own, and a link planted there is refused, never followed.
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw InputError("out", "'" + o.out + "' exists and is not a directory");
    check_path_name("out", o.out);
    fs::create_directories(dir, ec);
    if (ec) throw OutputError("cannot create '" + dir.string() + "': " + ec.message());
    // (scenes/ is made when a command's scene is written there)
    const std::vector<std::string> subs =
        o.pictures ? std::vector<std::string>{"pictures", "logs", "keys"} : std::vector<std::string>{"panels", "claims", "logs", "keys"};
    for (const std::string& sub : subs) make_own_directory("out", (dir / sub).string());
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw OutputError("cannot locate this binary (/proc/self/exe): " + ec.message());
  const fs::path exe_dir = exe.parent_path();
  const std::string build = build_info().version + " (commit " + build_info().commit + ")";

  std::vector<Item> items;
  auto selected = [&](const std::string& id) {
    return std::find(ids.begin(), ids.end(), id) != ids.end() && (only.empty() || only.count(id));
  };
  for (size_t i = 0; i < m.panels.size(); ++i) {
    const Panel& p = m.panels[i];
    if (!selected(p.label)) continue;
    Item it;
    it.id = p.label;
    it.index = i;
    if (p.status == "pending") {
      it.state = "skipped";
      it.problem = "pending: " + p.reason;
      items.push_back(it);
      continue;
    }
    it.argv = o.full ? p.full : p.quick;
    const std::string prefix = (dir / "panels" / p.name()).string();
    // Every panel in the three formats a journal takes: PNG for the report, PDF and SVG
    // (vector) for print. All picture commands take --format.
    it.outputs = {"panels/" + p.name() + ".png", "panels/" + p.name() + ".pdf", "panels/" + p.name() + ".svg",
                  "panels/" + p.name() + ".json", "panels/" + p.name() + ".csv"};
    if (!p.twin_of.empty())  // a certified twin also draws where double is wrong
      for (const char* ext : {".png", ".pdf", ".svg"}) it.outputs.push_back("panels/" + p.name() + "-artefacts" + ext);
    it.exec = it.argv;
    if (const std::string problem = resolve_scenes(it.exec, dir / "scenes"); !problem.empty()) {
      it.state = "failed";
      it.problem = problem;
      items.push_back(it);
      continue;
    }
    it.exec.insert(it.exec.end(), {"--out", prefix, "--quiet", "--format", "png,pdf,svg"});
    it.stdout_path = (dir / "logs" / (p.name() + ".stdout")).string();
    it.stderr_path = (dir / "logs" / (p.name() + ".stderr")).string();
    it.key_path = (dir / "keys" / (p.name() + ".key")).string();
    if (!p.tiles_from.empty())
      for (size_t k = 0; k < items.size(); ++k)
        if (items[k].id == p.tiles_from && items[k].state == "pending") {
          it.after = k;
          items[k].tiles_prefix = (dir / "panels" / m.panels[items[k].index].name()).string();
        }
    items.push_back(it);
  }
  for (size_t i = 0; i < m.claims.size(); ++i) {
    const Claim& c = m.claims[i];
    if (!selected(c.id)) continue;
    Item it;
    it.id = c.id;
    it.is_claim = true;
    it.index = i;
    if (!o.full && !c.quick) {
      it.state = "deferred";
      it.problem = "not settled in --quick: run `" + command_text(c.full_run) + "` (or bouncer reproduce --full --only " + c.id + ")";
      it.argv = c.full_run;
      items.push_back(it);
      continue;
    }
    it.argv = o.full ? c.full_run : c.run;
    it.exec = it.argv;
    if (const std::string problem = resolve_scenes(it.exec, dir / "scenes"); !problem.empty()) {
      it.state = "failed";
      it.problem = problem;
      items.push_back(it);
      continue;
    }
    it.outputs = {"claims/" + c.id + ".json"};
    it.stdout_path = (dir / "claims" / (c.id + ".json")).string();
    it.stderr_path = (dir / "logs" / (c.id + ".stderr")).string();
    it.key_path = (dir / "keys" / (c.id + ".key")).string();
    items.push_back(it);
  }
  for (size_t i = 0; i < m.pictures.size(); ++i) {
    const Picture& p = m.pictures[i];
    if (!selected(p.id())) continue;
    Item it;
    it.id = p.id();
    it.is_picture = true;
    it.index = i;
    it.argv = p.command;  // the README's pictures are the same in --quick and --full
    it.exec = it.argv;
    if (const std::string problem = resolve_scenes(it.exec, dir / "scenes"); !problem.empty()) {
      it.state = "failed";
      it.problem = problem;
      items.push_back(it);
      continue;
    }
    it.exec.insert(it.exec.end(), {"--out", (dir / "pictures" / p.name).string(), "--quiet"});
    for (const std::string& f : p.files) it.outputs.push_back("pictures/" + f);
    it.outputs.push_back("pictures/" + p.name + ".json");
    it.outputs.push_back("pictures/" + p.name + ".csv");
    it.stdout_path = (dir / "logs" / (p.name + ".picture.stdout")).string();
    it.stderr_path = (dir / "logs" / (p.name + ".picture.stderr")).string();
    it.key_path = (dir / "keys" / (p.name + ".picture.key")).string();
    items.push_back(it);
  }
  // Resolve the binaries and the resume keys.
  for (Item& it : items) {
    if (it.state != "pending") continue;
    if (it.exec[0] == "bouncer") {
      it.exec[0] = exe.string();
    } else if (it.exec[0].rfind("proof_", 0) == 0) {
      if (auto p = find_proof(exe_dir, it.exec[0])) {
        it.exec[0] = p->string();
      } else {
        it.state = "failed";
        it.problem = "not reproduced: proof binary not found (" + it.exec[0] + " next to " + exe_dir.string() +
                     " or in ../proofs; build it: cmake --build build --target " + it.exec[0] + ")";
        continue;
      }
    } else {
      it.state = "failed";
      it.problem = "manifest command must start with bouncer or proof_NAME, not '" + it.exec[0] + "'";
      continue;
    }
    it.key = "mode " + mode + "\nbuild " + build + "\ncommand " + command_text(it.argv) + "\n";
    bool have = read_text(it.key_path) == it.key;
    for (const std::string& f : it.outputs) have = have && fs::exists(dir / f);
    if (have) it.state = "cached";
  }

  // Run, `jobs` at a time. Progress: one line per finished item on stderr.
  const auto t0 = std::chrono::steady_clock::now();
  const size_t total = items.size();
  size_t finished = 0;
  auto report_line = [&](const Item& it) {
    ++finished;
    std::cerr << "reproduce [" << finished << "/" << total << "] " << it.id << ": " << it.state;
    if (it.state == "done" || it.state == "failed") std::cerr << " (" << fixed(it.seconds, 1) << " s)";
    if (!it.problem.empty()) std::cerr << ": " << it.problem;
    std::cerr << "\n";
  };
  std::map<pid_t, std::pair<size_t, std::chrono::steady_clock::time_point>> running;
  std::vector<bool> started(items.size(), false);
  for (Item& it : items)
    if (it.state != "pending") report_line(it);
  // The next item to start: in manifest order, the first pending one whose grid source (if
  // any) has finished.
  auto next_ready = [&]() -> std::optional<size_t> {
    for (size_t i = 0; i < items.size(); ++i) {
      if (started[i] || items[i].state != "pending") continue;
      if (items[i].after && (items[*items[i].after].state == "pending")) continue;
      return i;
    }
    return std::nullopt;
  };
  // A signal to reproduce alone (kill PID, a batch system's TERM) reaches its children too:
  // they stop, no key is written for them, and a rerun resumes (a terminal's Ctrl-C reaches
  // the whole process group anyway).
  const StopSignals stop;
  bool forwarded = false;
  while (true) {
    while (running.size() < jobs && !stop.caught()) {
      const auto ready = next_ready();
      if (!ready) break;
      const size_t idx = *ready;
      Item& it = items[idx];
      started[idx] = true;
      std::error_code rm;
      fs::remove(it.key_path, rm);
      if (!it.tiles_prefix.empty()) it.exec.push_back("--keep-tiles");
      if (it.after) {
        const std::string from = items[*it.after].tiles_prefix;
        if (fs::is_regular_file(from + ".tiles/job.key", rm)) it.exec.insert(it.exec.end(), {"--tiles-from", from});
      }
      const pid_t pid = spawn(it);
      if (pid < 0) {
        it.state = "failed";
        it.problem = "could not start " + it.exec[0];
        report_line(it);
        continue;
      }
      running[pid] = {idx, std::chrono::steady_clock::now()};
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (stop.caught() && !forwarded) {  // (a signal just before waitpid: the next child's end wakes it)
      forwarded = true;
      for (const auto& [child, what] : running)
        if (child != pid) ::kill(child, stop.caught());
    }
    if (pid < 0 && errno == EINTR) continue;
    if (pid < 0) break;
    auto r = running.find(pid);
    if (r == running.end()) continue;
    Item& it = items[r->second.first];
    it.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - r->second.second).count();
    running.erase(r);
    it.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (stop.caught()) continue;  // stopped: its staging files are removed below, no key written
    it.files->commit();  // its stdout and stderr, into place
    it.files.reset();
    bool outputs_ok = true;
    for (const std::string& f : it.outputs) outputs_ok = outputs_ok && fs::exists(dir / f);
    if (it.exit_status == 0 && outputs_ok) {
      it.state = "done";
      write_text(it.key_path, it.key);
    } else {
      it.state = "failed";
      std::string err = read_text(it.stderr_path);
      if (const auto nl = err.find_last_not_of("\n"); nl != std::string::npos) err = err.substr(0, nl + 1);
      if (const auto last = err.rfind('\n'); last != std::string::npos) err = err.substr(last + 1);
      it.problem = "exit status " + std::to_string(it.exit_status) + (outputs_ok ? "" : ", outputs missing") +
                   (err.empty() ? "" : ": " + one_line(err));
    }
    report_line(it);
  }
  const double total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (const int sig = stop.caught()) {
    // No report: it would call the stopped items failed. Finished items keep their keys.
    for (Item& it : items)
      if (it.files) it.files->discard();
    std::cerr << "reproduce: stopped by signal " << sig << " (" << ::strsignal(sig) << "); finished items are kept in "
              << dir.string() << ": run the same command again to resume\n";
    stop.reraise();
  }
  // Grids kept for a later panel (tiles_from) are removed once every panel drawn from them
  // is done; otherwise they stay for a rerun.
  for (const Item& src : items) {
    if (src.tiles_prefix.empty()) continue;
    bool needed = false;
    for (const Item& it : items)
      needed = needed || (it.after && items[*it.after].id == src.id && it.state != "done" && it.state != "cached");
    std::error_code rm;
    if (!needed) fs::remove_all(src.tiles_prefix + ".tiles", rm);
  }

  // Evaluate the claims' checks.
  json jclaims = json::array();
  json jpanels = json::array();
  json times = json::object();
  size_t failed_items = 0, not_reproduced = 0, reproduced = 0, deferred = 0;
  struct Outcome {
    std::string verdict, status;
    std::vector<std::string> failed_checks;
  };
  std::map<std::string, Outcome> outcome;
  json jpictures = json::array();
  for (Item& it : items) {
    if (it.state == "failed") ++failed_items;
    times[it.id] = {{"state", it.state}, {"seconds", it.seconds}};
    if (it.is_picture) {
      const Picture& p = m.pictures[it.index];
      json j{{"label", p.id()}, {"readme", p.readme}, {"status", it.state == "cached" ? "done" : it.state},
             {"command", command_text(it.argv)}};
      if (it.state == "done" || it.state == "cached") j["files"] = it.outputs;
      if (it.state == "failed") j["problem"] = it.problem;
      jpictures.push_back(j);
      continue;
    }
    if (!it.is_claim) {
      const Panel& p = m.panels[it.index];
      json j{{"label", p.label}, {"figure", p.figure}, {"status", it.state == "skipped" ? "pending" : it.state == "cached" ? "done" : it.state}};
      // (a resumed item is "done" here: whether it was rerun is a run detail, kept under times)
      if (it.state == "skipped") j["reason"] = p.reason;
      if (!p.twin_of.empty()) j["twin_of"] = p.twin_of;
      if (!it.argv.empty()) j["command"] = command_text(it.argv);
      if (it.state == "done" || it.state == "cached") j["files"] = it.outputs;
      if (it.state == "failed") j["problem"] = it.problem;
      jpanels.push_back(j);
      continue;
    }
    const Claim& c = m.claims[it.index];
    Outcome oc;
    json jchecks = json::array();
    if (it.state == "deferred") {
      oc.status = "deferred";
      oc.verdict = "not checked in --quick";
      ++deferred;
    } else if (it.state == "failed") {
      oc.status = "failed";
      oc.verdict = it.problem.rfind("not reproduced", 0) == 0 ? it.problem : "not reproduced: the command failed (" + it.problem + ")";
      ++not_reproduced;
    } else {
      const json doc = json::parse(read_text(dir / it.outputs[0]), nullptr, false);
      if (doc.is_discarded()) {
        oc.status = "failed";
        oc.verdict = "not reproduced: the output is not JSON";
        ++not_reproduced;
        ++failed_items;
      } else {
        for (const Check& k : c.checks) {
          std::string got;
          const bool ok = holds(k, doc, got);
          jchecks.push_back({{"check", k.text()}, {"got", got}, {"held", ok}});
          if (!ok) oc.failed_checks.push_back(k.text() + " (got " + got + ")");
        }
        if (oc.failed_checks.empty()) {
          oc.status = "reproduced";
          oc.verdict = c.expected;
          ++reproduced;
        } else {
          oc.status = "not reproduced";
          oc.verdict = "not reproduced: check " + oc.failed_checks[0] + " failed";
          ++not_reproduced;
        }
      }
    }
    outcome[c.id] = oc;
    json j{{"id", c.id}, {"row", c.row}, {"paper", c.paper}, {"groups", c.groups}, {"claim", c.text},
           {"expected", c.expected}, {"verdict", oc.verdict}, {"status", oc.status}, {"evidence", c.evidence},
           {"command", command_text(it.argv)}, {"rerun", c.rerun}, {"checks", jchecks}};
    if (!it.outputs.empty()) j["output"] = it.outputs[0];
    jclaims.push_back(j);
  }
  const bool ok = failed_items == 0 && not_reproduced == 0;
  const std::string summary = o.pictures ? std::to_string(jpictures.size() - failed_items) + " of " +
                                               std::to_string(jpictures.size()) + " README pictures drawn; " +
                                               std::to_string(failed_items) + " items failed"
                                         : std::to_string(reproduced) + " of " + std::to_string(outcome.size()) +
                                               " claims reproduced their expected verdict" +
                                               (deferred ? " (" + std::to_string(deferred) + " deferred to --full)" : "") +
                                               "; " + std::to_string(failed_items) + " items failed";

  json doc;
  doc["reproduce"] = {{"paper", "Langer & Miller 2014"}, {"mode", mode}, {"build", build}, {"manifest", source},
                      {"only", std::vector<std::string>(only.begin(), only.end())}, {"result", ok ? "reproduced" : "not reproduced"},
                      {"summary", summary}};
  doc["claims"] = jclaims;
  doc["panels"] = jpanels;
  if (!jpictures.empty()) doc["pictures"] = jpictures;
  doc["times"] = {{"seconds", total_seconds}, {"items", times}};

  // report.md
  std::ostringstream md;
  const std::string title = o.pictures ? "bouncer's README pictures" : "Reproduction of Langer & Miller 2014";
  md << "# " << title << "\n\n";
  md << "Mode: `" << mode << "`. Built by bouncer " << build << ". Manifest: " << source << ".\n\n";
  const std::string result_text = !ok         ? (o.pictures ? "NOT every picture was drawn" : "NOT fully reproduced")
                                  : o.pictures ? "every picture was drawn"
                                               : "every item ran and every claim reproduced its expected verdict";
  md << "**Result: " << result_text
     << "** (" << summary << ").\n\n";
  const bool paper = !o.pictures;  // the paper's sections (claims, figures); --pictures has none
  if (paper) md << "## Claims\n\n| # | Claim | Paper | Expected | This run | Evidence | Rerun |\n|---|---|---|---|---|---|---|\n";
  for (const Item& it : items) {
    if (!it.is_claim) continue;
    const Claim& c = m.claims[it.index];
    const Outcome& oc = outcome[c.id];
    md << "| " << c.row << " | " << md_cell(c.text) << " | " << md_cell(c.paper) << " | " << c.expected << " | "
       << (oc.status == "reproduced" ? "**" + oc.verdict + "**" : md_cell(oc.verdict)) << " | " << md_cell(c.evidence)
       << " | " << md_cell(c.rerun) << " |\n";
  }
  if (paper) md << "\n## Figures\n";
  std::string figure;
  for (const Item& it : items) {
    if (!it.is_panel()) continue;
    const Panel& p = m.panels[it.index];
    if (p.figure != figure) {
      figure = p.figure;
      md << "\n### " << figure << "\n\n> " << md_cell(p.caption) << "\n";
    }
    md << "\n#### " << p.label << (p.panel.empty() ? "" : " " + p.panel)
       << (p.twin_of.empty() ? "" : " (certified twin of " + p.twin_of + ", not a panel of the paper)") << "\n\n";
    if (it.state == "done" || it.state == "cached") {
      md << "![" << p.label << "](panels/" << p.name() << ".png)\n\n";
      if (!p.twin_of.empty()) md << "![where double is wrong](panels/" << p.name() << "-artefacts.png)\n\n";
      md << "[PDF](panels/" << p.name() << ".pdf) · [SVG](panels/" << p.name() << ".svg) · [CSV](panels/" << p.name()
         << ".csv)\n\n";
    }
    else if (it.state == "skipped")
      md << "**Pending:** " << p.reason << ".\n\n";
    else
      md << "**Failed:** " << md_cell(it.problem) << "\n\n";
    if (!p.params.empty()) {
      md << "Parameters:";
      for (const auto& [k, v] : p.params) md << " " << k << " = " << v << ";";
      md << "\n\n";
    }
    if (!p.note.empty()) md << "Note: " << p.note << "\n\n";
    if (!it.argv.empty())
      md << "Provenance: `" << command_text(it.argv) << " --out panels/" << p.name() << "` (bouncer " << build
         << "); outputs panels/" << p.name() << ".{png,csv,json}\n";
  }
  const bool any_picture = std::any_of(items.begin(), items.end(), [](const Item& it) { return it.is_picture; });
  if (any_picture) {
    md << "\n## The pictures (data/pictures)\n\nNot figures of the paper: the pictures the README shows, "
          "drawn by the same build (`cp pictures/*.png` into data/pictures/ regenerates them).\n";
    for (const Item& it : items) {
      if (!it.is_picture) continue;
      const Picture& p = m.pictures[it.index];
      md << "\n#### " << p.name << " (README: " << p.readme << ")\n\n" << p.about << "\n\n";
      if (it.state == "done" || it.state == "cached")
        for (const std::string& f : p.files) md << "![" << p.name << "](pictures/" << f << ")\n\n";
      else
        md << "**Failed:** " << md_cell(it.problem) << "\n\n";
      md << "Provenance: `" << command_text(it.argv) << " --out pictures/" << p.name << "`\n";
    }
  }
  if (paper) md << "\n## Claims: provenance\n\n";
  for (const Item& it : items) {
    if (!it.is_claim) continue;
    md << "- " << it.id << ": `" << command_text(it.argv) << "`" << (it.outputs.empty() ? "" : " → " + it.outputs[0]);
    const Outcome& oc = outcome[it.id];
    for (const std::string& f : oc.failed_checks) md << "; failed check: " << f;
    md << "\n";
  }
  md << "\n## Times\n\n(Volatile: the only part of this report that changes between identical runs.)\n\n";
  md << "| item | state | seconds |\n|---|---|---|\n";
  for (const Item& it : items) md << "| " << it.id << " | " << it.state << " | " << fixed(it.seconds, 2) << " |\n";
  md << "\nTotal: " << fixed(total_seconds, 1) << " s with " << jobs << " jobs.\n";

  // report.html
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << html_escape(title) << "</title>\n"
    << "<style>body{font-family:sans-serif;max-width:1100px;margin:auto}table{border-collapse:collapse}"
       "td,th{border:1px solid #999;padding:4px;vertical-align:top}img{max-width:100%}"
       ".ok{color:#060}.bad{color:#a00}figure{margin:1em 0}figcaption{font-style:italic}</style>\n</head>\n<body>\n";
  h << "<h1>" << html_escape(title) << "</h1>\n";
  h << "<p>Mode: <code>" << mode << "</code>. Built by bouncer " << html_escape(build) << ". Manifest: "
    << html_escape(source) << ".</p>\n";
  h << "<p class=\"" << (ok ? "ok" : "bad") << "\"><strong>Result: "
    << result_text << "</strong> ("
    << html_escape(summary) << ").</p>\n";
  if (paper) h << "<h2>Claims</h2>\n<table>\n<tr><th>#</th><th>Claim</th><th>Paper</th><th>Expected</th><th>This run</th><th>Evidence</th><th>Rerun</th></tr>\n";
  for (const Item& it : items) {
    if (!it.is_claim) continue;
    const Claim& c = m.claims[it.index];
    const Outcome& oc = outcome[c.id];
    h << "<tr><td>" << html_escape(c.row) << "</td><td>" << md_inline_html(c.text) << "</td><td>" << html_escape(c.paper)
      << "</td><td>" << html_escape(c.expected) << "</td><td class=\"" << (oc.status == "reproduced" ? "ok" : "bad") << "\">"
      << html_escape(oc.verdict) << "</td><td>" << md_inline_html(c.evidence) << "</td><td>" << md_inline_html(c.rerun)
      << "</td></tr>\n";
  }
  if (paper) h << "</table>\n<h2>Figures</h2>\n";
  figure.clear();
  for (const Item& it : items) {
    if (!it.is_panel()) continue;
    const Panel& p = m.panels[it.index];
    if (p.figure != figure) {
      figure = p.figure;
      h << "<h3>" << html_escape(figure) << "</h3>\n";
    }
    h << "<figure id=\"" << html_escape(p.label) << "\">\n";
    if (it.state == "done" || it.state == "cached")
      h << "<img src=\"panels/" << html_escape(p.name()) << ".png\" alt=\"" << html_escape(p.label) << "\">\n"
        << (p.twin_of.empty() ? std::string()
                              : "<img src=\"panels/" + html_escape(p.name()) + "-artefacts.png\" alt=\"where double is wrong\">\n")
        << "<p class=\"files\"><a href=\"panels/" << html_escape(p.name()) << ".pdf\">PDF</a> · <a href=\"panels/"
        << html_escape(p.name()) << ".svg\">SVG</a> · <a href=\"panels/" << html_escape(p.name()) << ".csv\">CSV</a></p>\n";
    else if (it.state == "skipped")
      h << "<p><strong>Pending:</strong> " << html_escape(p.reason) << ".</p>\n";
    else
      h << "<p class=\"bad\"><strong>Failed:</strong> " << html_escape(it.problem) << "</p>\n";
    h << "<figcaption>" << html_escape(p.label) << (p.panel.empty() ? "" : " " + html_escape(p.panel))
      << (p.twin_of.empty() ? "" : " (certified twin of " + html_escape(p.twin_of) + ", not a panel of the paper)") << ". Paper: "
      << html_escape(p.caption) << "</figcaption>\n";
    if (!p.params.empty()) {
      h << "<p>Parameters:";
      for (const auto& [k, v] : p.params) h << " " << html_escape(k) << " = " << html_escape(v) << ";";
      h << "</p>\n";
    }
    if (!p.note.empty()) h << "<p>Note: " << html_escape(p.note) << "</p>\n";
    if (!it.argv.empty())
      h << "<p>Provenance: <code>" << html_escape(command_text(it.argv)) << " --out panels/" << html_escape(p.name())
        << "</code> (bouncer " << html_escape(build) << ")</p>\n";
    h << "</figure>\n";
  }
  if (any_picture) {
    h << "<h2>The pictures (data/pictures)</h2>\n<p>Not figures of the paper: the pictures the README shows, "
         "drawn by the same build (<code>cp pictures/*.png</code> into data/pictures/ regenerates them).</p>\n";
    for (const Item& it : items) {
      if (!it.is_picture) continue;
      const Picture& p = m.pictures[it.index];
      h << "<figure id=\"" << html_escape(p.id()) << "\">\n";
      if (it.state == "done" || it.state == "cached")
        for (const std::string& f : p.files)
          h << "<img src=\"pictures/" << html_escape(f) << "\" alt=\"" << html_escape(p.name) << "\">\n";
      else
        h << "<p class=\"bad\"><strong>Failed:</strong> " << html_escape(it.problem) << "</p>\n";
      h << "<figcaption>" << html_escape(p.name) << " (README: " << html_escape(p.readme) << "). " << md_inline_html(p.about)
        << "</figcaption>\n<p>Provenance: <code>" << html_escape(command_text(it.argv)) << " --out pictures/"
        << html_escape(p.name) << "</code></p>\n</figure>\n";
    }
  }
  if (paper) h << "<h2>Claims: provenance</h2>\n<ul>\n";
  for (const Item& it : items) {
    if (!it.is_claim) continue;
    h << "<li>" << html_escape(it.id) << ": <code>" << html_escape(command_text(it.argv)) << "</code>";
    for (const std::string& f : outcome[it.id].failed_checks) h << "; failed check: " << html_escape(f);
    h << "</li>\n";
  }
  if (paper) h << "</ul>\n";
  h << "<section id=\"times\">\n<h2>Times</h2>\n<p>Volatile: the only part of this report that changes between identical runs.</p>\n"
    << "<table>\n<tr><th>item</th><th>state</th><th>seconds</th></tr>\n";
  for (const Item& it : items)
    h << "<tr><td>" << html_escape(it.id) << "</td><td>" << it.state << "</td><td>" << fixed(it.seconds, 2) << "</td></tr>\n";
  h << "</table>\n<p>Total: " << fixed(total_seconds, 1) << " s with " << jobs << " jobs.</p>\n</section>\n</body>\n</html>\n";

  write_output_set({{(dir / "report.md").string(), [&](std::ostream& s) { s << md.str(); }},
                    {(dir / "report.html").string(), [&](std::ostream& s) { s << h.str(); }},
                    {(dir / "claims.json").string(), [&](std::ostream& s) { s << doc.dump(2) << "\n"; }}});
  std::cerr << "reproduce: " << summary << "; " << fixed(total_seconds, 1) << " s; report in " << (dir / "report.md").string()
            << "\n";
  if (!ok)
    for (const auto& [id, oc] : outcome)
      if (oc.status != "reproduced" && oc.status != "deferred") std::cerr << "reproduce: " << id << ": " << oc.verdict << "\n";
  return ok ? 0 : 1;
}

}  // namespace

CommandRunner setup_reproduce(CLI::App* sub) {
  auto o = std::make_shared<Options_>();
  sub->add_flag("--quick", o->quick, "Small grids and few steps (default; under 3 minutes on 2 cores)");
  sub->add_flag("--full", o->full, "Paper resolution: 5000 transient + 500 recorded steps, 10 x 10 starts per scan point");
  sub->add_option("--out", o->out, "Output directory (default: reproduction)");
  sub->add_option("--only", o->only, "Comma list of panel labels (fig:basin1 or basin1) and claim ids");
  sub->add_option("--jobs", o->jobs, "Items run at once, integer in [1, 1024] (default: cores)");
  sub->add_flag("--claims-table", o->claims_table, "Print the README's Markdown claims table from the manifest and exit");
  sub->add_flag("--pictures", o->pictures,
                "Draw the README's pictures (data/pictures/) instead of the paper, into DIR/pictures/; "
                "cp DIR/pictures/*.png data/pictures/ regenerates them");
  sub->add_flag("--check", o->check,
                "Validate every command of the manifest (quick and full) without running it: one line each; exit 1 if any is refused");
  sub->add_option("--manifest", o->manifest, "")->group("");  // hidden: another manifest (tests)
  auto run = [o](const std::string&) { return run_reproduce(*o); };
  return run;
}

}  // namespace bouncer::cli
