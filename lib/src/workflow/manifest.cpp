#include "bouncer/workflow/manifest.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <set>

#include "bouncer/base/error.hpp"
#include "bouncer/base/input.hpp"
#include "bouncer/workflow/commands.hpp"
#include "bouncer/workflow/paper.hpp"
#include "bouncer/io/scene.hpp"

namespace bouncer {

namespace {

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

// A check's VALUE: a TOML scalar as it is (no conversion between types); anything else null.
CheckValue check_value(const toml::node& n) {
  if (auto s = n.value_exact<std::string>()) return *s;
  if (auto b = n.value_exact<bool>()) return *b;
  if (auto i = n.value_exact<int64_t>()) return *i;
  if (auto d = n.value_exact<double>()) return *d;
  return std::monostate{};
}

std::string shell_word(const std::string& w) {
  if (!w.empty() && w.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.,:/=+") == std::string::npos)
    return w;
  std::string q = "'";
  for (char ch : w) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

Panel parse_panel(const toml::table& t, const std::string& source, const std::vector<Panel>& earlier) {
  Panel p;
  p.label = str(t, "label", source + " panel");
  const std::string where = source + " panel " + p.label;
  p.figure = str(t, "figure", where);
  p.panel = str(t, "panel", where, false);
  p.caption = str(t, "caption", where);
  p.note = str(t, "note", where, false);
  p.scene = str(t, "scene", where, false);
  p.status = str(t, "status", where);
  p.reason = str(t, "reason", where, false);
  p.twin_of = str(t, "twin_of", where, false);
  p.tiles_from = str(t, "tiles_from", where, false);
  p.beside = str(t, "beside", where, false);
  if (!p.beside.empty() &&
      std::none_of(earlier.begin(), earlier.end(), [&](const Panel& q) { return q.label == p.beside; }))
    throw InputError("manifest", where + ": beside '" + p.beside + "' is not the label of an earlier panel");
  if (!p.tiles_from.empty() &&
      std::none_of(earlier.begin(), earlier.end(), [&](const Panel& q) { return q.label == p.tiles_from; }))
    throw InputError("manifest", where + ": tiles_from '" + p.tiles_from + "' is not the label of an earlier panel");
  if (const toml::table* params = t["params"].as_table())
    for (const auto& kv : *params) p.params.emplace_back(std::string(kv.first.str()), kv.second.value<std::string>().value_or(""));
  if (!safe_name(p.label) || (!p.twin_of.empty() && !safe_name(p.twin_of)))
    throw InputError("manifest", where + ": a label must be a safe file name (letters, digits, . _ : + -; no '..')");
  p.quick = argv_of(t, "quick", where);
  p.full = argv_of(t, "full", where);
  for (const auto* argv : {&p.quick, &p.full})
    if (const std::string problem = command_problem(*argv); !problem.empty())
      throw InputError("manifest", where + ": command " + problem);
  if (p.status != "ready" && p.status != "pending") throw InputError("manifest", where + ": status must be ready or pending");
  if (p.status == "pending" && p.reason.empty()) throw InputError("manifest", where + ": a pending panel needs a reason");
  if (p.status == "ready" && (p.quick.empty() || p.full.empty()))
    throw InputError("manifest", where + ": a ready panel needs quick and full commands");
  return p;
}

Claim parse_claim(const toml::table& t, const std::string& source) {
  Claim c;
  c.id = str(t, "id", source + " claim");
  const std::string where = source + " claim " + c.id;
  if (!safe_name(c.id))
    throw InputError("manifest", where + ": an id must be a safe file name (letters, digits, . _ : + -; no '..')");
  c.row = str(t, "row", where);
  c.text = str(t, "text", where);
  c.paper = str(t, "paper", where);
  c.expected = str(t, "expected", where);
  c.verdict = str(t, "verdict", where);
  c.evidence = str(t, "evidence", where);
  c.rerun = str(t, "rerun", where);
  if (std::find(verdict_words().begin(), verdict_words().end(), c.expected) == verdict_words().end())
    throw InputError("manifest", where + ": expected must be confirmed, refuted, corrected, not reproduced or consistent");
  if (const toml::array* g = t["groups"].as_array())
    for (const auto& e : *g) c.groups.push_back(e.value<int64_t>().value_or(0));
  c.run = argv_of(t, "run", where);
  c.full_run = argv_of(t, "full_run", where);
  if (c.run.empty()) throw InputError("manifest", where + ": needs a run command");
  if (c.full_run.empty()) {
    c.full_run = c.run;
    if (c.run[0].rfind("proof_", 0) == 0) c.full_run.push_back("--full");
  }
  for (const auto* argv : {&c.run, &c.full_run})
    if (const std::string problem = command_problem(*argv); !problem.empty())
      throw InputError("manifest", where + ": command " + problem);
  c.quick = t["quick"].value<bool>().value_or(true);
  if (const toml::array* ch = t["checks"].as_array())
    for (const auto& e : *ch) {
      const toml::array* triple = e.as_array();
      if (!triple || triple->size() != 3 || !(*triple)[0].is_string() || !(*triple)[1].is_string())
        throw InputError("manifest", where + ": each check is [PATH, OP, VALUE]");
      Check k{*(*triple)[0].value<std::string>(), *(*triple)[1].value<std::string>(), check_value(*triple->get(2))};
      if (!is_check_operator(k.op))
        throw InputError("manifest", where + ": unknown check operator '" + k.op + "' (== != < <= > >= has lacks)");
      c.checks.push_back(std::move(k));
    }
  if (c.checks.empty()) throw InputError("manifest", where + ": needs at least one check");
  return c;
}

Picture parse_picture(const toml::table& t, const std::string& source) {
  Picture p;
  p.name = str(t, "name", source + " picture");
  const std::string where = source + " picture " + p.name;
  if (!safe_name(p.name))
    throw InputError("manifest", where + ": name must be a safe file name without extension (letters, digits, . _ : + -)");
  p.readme = str(t, "readme", where);
  p.about = str(t, "about", where);
  p.command = argv_of(t, "command", where);
  if (p.command.empty()) throw InputError("manifest", where + ": needs a command");
  p.files = argv_of(t, "files", where);
  if (p.files.empty()) p.files = {p.name + ".png"};
  for (const std::string& f : p.files)
    if (!safe_name(f)) throw InputError("manifest", where + ": file '" + f + "' must be a safe file name");
  if (const std::string problem = command_problem(p.command); !problem.empty())
    throw InputError("manifest", where + ": command " + problem);
  return p;
}

}  // namespace

const std::vector<std::string>& verdict_words() {
  static const std::vector<std::string> w{"confirmed", "refuted", "corrected", "not reproduced", "consistent"};
  return w;
}

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
      if (!built_in_scenes().count(value)) return "--scene '" + value + "' is not a scene of data/scenes/ (built in)";
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
      m.panels.push_back(parse_panel(*t, source, m.panels));
    }
  if (const toml::array* cs = root["claim"].as_array())
    for (const auto& node : *cs) {
      const toml::table* t = node.as_table();
      if (!t) throw InputError("manifest", source + ": [[claim]] must be tables");
      m.claims.push_back(parse_claim(*t, source));
    }
  if (const toml::array* ps = root["picture"].as_array())
    for (const auto& node : *ps) {
      const toml::table* t = node.as_table();
      if (!t) throw InputError("manifest", source + ": [[picture]] must be tables");
      m.pictures.push_back(parse_picture(*t, source));
    }
  return m;
}

std::string command_text(const std::vector<std::string>& argv, const std::string& proof_prefix) {
  std::string s;
  for (size_t i = 0; i < argv.size(); ++i) {
    std::string w = argv[i];
    if (i == 0 && w.rfind("proof_", 0) == 0) w.insert(0, proof_prefix);
    if (i) s += ' ';
    s += shell_word(w);
  }
  return s;
}

std::string rerun_text(const std::string& rerun, const std::string& proof_prefix) {
  std::string s;
  // build/proofs/ as the reader's proof directory.
  const std::string from = kBuildProofPrefix;
  size_t at = 0;
  for (size_t k; (k = rerun.find(from, at)) != std::string::npos; at = k + from.size()) s += rerun.substr(at, k - at) + proof_prefix;
  s += rerun.substr(at);
  // --scene data/scenes/NAME.toml of a built-in scene as --scene NAME (picture- dropped):
  // found by name from any directory and from an install, where the checkout's path is not.
  const std::string scene = "--scene data/scenes/";
  for (size_t k = 0; (k = s.find(scene, k)) != std::string::npos;) {
    size_t end = k + scene.size();
    while (end < s.size() && (std::isalnum(static_cast<unsigned char>(s[end])) || std::strchr("._-", s[end]))) ++end;
    const std::string file = s.substr(k + 8, end - k - 8);  // data/scenes/NAME.toml
    if (file.size() > 17 && file.ends_with(".toml") && built_in_scenes().count(file)) {
      std::string name = file.substr(12, file.size() - 17);
      if (name.rfind("picture-", 0) == 0) name = name.substr(8);
      s.replace(k, end - k, "--scene " + name);
    }
    k += scene.size() - 12;
  }
  // ctest runs in a build tree of the sources, named as build/ is for the proofs.
  const std::string ctest = "`ctest -R ";
  for (size_t k = 0; (k = s.find(ctest, k)) != std::string::npos;) {
    s.replace(k, ctest.size(), "`ctest --test-dir build -R ");
    k = s.find('`', k + 1);
    if (k == std::string::npos) break;
    if (proof_prefix != kBuildProofPrefix) s.insert(k + 1, " (in a build tree of the sources)");
    ++k;
  }
  return s;
}

}  // namespace bouncer
