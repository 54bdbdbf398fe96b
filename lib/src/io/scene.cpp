#include "bouncer/io/scene.hpp"
#include "bouncer/base/input.hpp"
#include "bouncer/base/text.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <sstream>

namespace bouncer {

std::string Options::get(const std::string& key) const {
  auto it = values.find(key);
  if (it == values.end() || it->second.empty()) {
    const std::string range = allowed_range(key);
    throw InputError(key, range.empty() ? "is required" : "is required (" + range + ")");
  }
  if (it->second.size() != 1) throw InputError(key, "takes one value, got a list");
  return it->second.front();
}

std::string Options::get_or(const std::string& key, const std::string& fallback) const {
  return has(key) ? get(key) : fallback;
}

std::vector<std::pair<std::string, std::string>> Options::inputs() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [k, vs] : values) {
    std::string joined;
    for (size_t i = 0; i < vs.size(); ++i) joined += (i ? "," : "") + vs[i];
    out.emplace_back(k, joined);
  }
  return out;
}

std::string Options::as_toml(const std::string& command) const {
  std::ostringstream s;
  s << "command = \"" << command << "\"\n";
  for (const auto& [k, vs] : values) {
    s << k << " = ";
    if (vs.size() == 1) {
      s << toml::value<std::string>(vs[0]);
    } else {
      s << "[";
      for (size_t i = 0; i < vs.size(); ++i) s << (i ? ", " : "") << toml::value<std::string>(vs[i]);
      s << "]";
    }
    s << "\n";
  }
  return s.str();
}

namespace {

std::string scalar_text(const std::string& key, const toml::node& n) {
  if (auto s = n.as_string()) return s->get();
  if (auto i = n.as_integer()) return std::to_string(i->get());
  if (auto b = n.as_boolean()) return b->get() ? "true" : "false";
  if (n.is_floating_point())
    throw InputError(key, "write decimals as strings (e.g. \"28.82\"): a TOML float is already rounded");
  throw InputError(key, "must be a string or an integer");
}

}  // namespace

// The scene file as a TOML table; a directory, a missing file, a FIFO, a file over 1 MiB,
// nesting deeper than any scene (base/input.hpp) or bad TOML is InputError("scene").
// The built-in scene a PATH that is no file names (scene.hpp), if any.
static const std::string* built_in_scene(const std::string& path) {
  std::error_code ec;
  if (path.empty() || std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return nullptr;
  const auto& scenes = built_in_scenes();
  std::vector<std::string> keys{path};
  if (path.find('/') == std::string::npos) {
    const std::string stem = path.size() > 5 && path.ends_with(".toml") ? path.substr(0, path.size() - 5) : path;
    keys.push_back("data/scenes/" + stem + ".toml");
    keys.push_back("data/scenes/picture-" + stem + ".toml");
  }
  for (const std::string& k : keys)
    if (const auto it = scenes.find(k); it != scenes.end()) return &it->second;
  return nullptr;
}

// For a PATH that is neither a file nor a built-in scene: " (did you mean NAME?)" with the
// built-in scene's name closest to PATH's name (picture- dropped, as --scene accepts it), or "".
static std::string scene_suggestion(const std::string& path) {
  std::string stem = std::filesystem::path(path).filename().string();
  if (stem.size() > 5 && stem.ends_with(".toml")) stem.resize(stem.size() - 5);
  if (stem.rfind("picture-", 0) == 0) stem = stem.substr(8);
  std::vector<std::string> names;
  for (const auto& [key, text] : built_in_scenes()) {
    std::string name = std::filesystem::path(key).stem().string();
    if (name.rfind("picture-", 0) == 0) name = name.substr(8);
    names.push_back(name);
  }
  const std::optional<std::string> guess = closest(stem, names);
  return guess && *guess != stem ? " (did you mean " + *guess + "?)" : "";
}

static toml::table read_scene_file(const std::string& path) {
  const std::string* built_in = built_in_scene(path);
  if (std::error_code ec; !built_in && !path.empty() && !std::filesystem::exists(std::filesystem::symlink_status(path, ec)))
    if (const std::string guess = scene_suggestion(path); !guess.empty())
      throw InputError("scene", "'" + path + "' not found: no such file and no built-in scene" + guess);
  const std::string text = built_in ? *built_in : read_input_file("scene", path, kMaxSceneBytes);
  check_toml_text("scene", text, "'" + path + "'", kMaxSceneBytes);
  toml::table table;
  try {
    table = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "cannot read scene '" << path << "': " << e.description() << " (line " << e.source().begin.line << ")";
    throw InputError("scene", msg.str());
  }
  return table;
}

Options load_scene(const std::string& path, const std::string& command, const std::set<std::string>& allowed) {
  const toml::table table = read_scene_file(path);
  Options o;
  for (const auto& [k, node] : table) {
    const std::string key(k.str());
    if (key == "command") {
      auto s = node.as_string();
      if (!s || s->get() != command)
        throw InputError("scene", "'" + path + "' is a scene for '" + (s ? s->get() : std::string("?")) + "', not '" + command + "'");
      continue;
    }
    if (!allowed.count(key)) throw InputError("scene", "unknown key '" + key + "' in '" + path + "' for command " + command);
    if (auto arr = node.as_array()) {
      std::vector<std::string> items;
      for (const auto& item : *arr) items.push_back(scalar_text(key, item));
      if (items.empty()) throw InputError(key, "an empty list");
      o.set(key, items);
    } else {
      o.set(key, scalar_text(key, node));
    }
  }
  return o;
}

std::string scene_command(const std::string& path) {
  const toml::table table = read_scene_file(path);
  const auto command = table["command"].value<std::string>();
  if (!command || command->empty())
    throw InputError("scene", "'" + path + "' has no command = \"...\" line: give the command (bouncer COMMAND --scene FILE)");
  return *command;
}

Options merge(Options scene, const Options& command_line) {
  for (const auto& [k, v] : command_line.values) scene.values[k] = v;
  return scene;
}

const std::set<std::string>& model_keys() {
  static const std::set<std::string> keys{"model", "a", "eps", "c", "wall", "downward-sticking", "veldep-collapse"};
  return keys;
}

ModelSpec model_from(const Options& o) {
  ModelSpec m;
  m.law = parse_law("model", o.get("model"));
  m.a = parse_decimal("a", o.get("a"));
  if (m.law == Law::constant) {
    m.eps = parse_decimal("eps", o.get("eps"));
  } else if (o.has("eps")) {
    throw InputError("eps", "is only used with --model constant");
  }
  if (m.law == Law::veldep) {
    m.c = parse_decimal("c", o.get("c"));
  } else if (o.has("c")) {
    throw InputError("c", "is only used with --model veldep");
  }
  m.wall = parse_wall("wall", o.get_or("wall", "triangle"));
  m.downward = parse_downward("downward-sticking", o.get_or("downward-sticking", "paper"));
  const std::string collapse = o.get_or("veldep-collapse", "off");
  if (collapse != "on" && collapse != "off")
    throw InputError("veldep-collapse", "must be on or off (got '" + collapse + "')");
  m.veldep_collapse = collapse == "on";
  if (m.veldep_collapse && m.law != Law::veldep)
    throw InputError("veldep-collapse", "is only used with --model veldep");
  validate(m);
  return m;
}

Precision precision_from(const Options& o) { return parse_precision("precision", o.get_or("precision", "double")); }

long long integer_from(const Options& o, const std::string& key, long long lo, long long hi, long long fallback) {
  if (!o.has(key)) return fallback;
  const std::string text = o.get(key);
  auto d = Decimal::parse(text);
  const std::string range = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!d || d->value().get_den() != 1) throw InputError(key, "must be " + range + " (got '" + text + "')");
  const mpz_class n = d->value().get_num();
  if (n < mpz_class(std::to_string(lo)) || n > mpz_class(std::to_string(hi))) throw InputError(key, "must be " + range + " (got " + text + ")");
  return std::stoll(n.get_str());
}

std::vector<InitialCondition> initial_conditions_from(const Options& o, const ModelSpec& m) {
  auto list = [&](const std::string& key) {
    auto it = o.values.find(key);
    if (it == o.values.end()) throw InputError(key, "is required (" + allowed_range(key) + ")");
    return it->second;
  };
  const auto thetas = list("theta"), vs = list("v");
  if (thetas.size() != vs.size())
    throw InputError("v", "needs as many values as theta (" + std::to_string(thetas.size()) + ")");
  std::vector<InitialCondition> out;
  for (size_t i = 0; i < thetas.size(); ++i) {
    InitialCondition ic{parse_decimal("theta", thetas[i]), parse_decimal("v", vs[i])};
    validate(m, ic, "theta", "v");
    out.push_back(ic);
  }
  return out;
}

std::string decimal_note(const Precision& p) {
  if (p.is_interval())
    return "each decimal input is enclosed exactly (outward rounding); results are enclosures for the exact decimals";
  return "each decimal input is rounded to the nearest " + p.text() + " value; results are about those values";
}

}  // namespace bouncer
