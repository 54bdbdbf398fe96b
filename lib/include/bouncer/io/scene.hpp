// Scenes: one experiment's options, from a TOML file and the command line, validated by
// one piece of code whichever way they came.
//
// A scene file is flat TOML whose keys are the command's long option names:
//     command = "orbit"
//     model = "constant"
//     a = "24"            # decimals as strings, so that they stay exact
//     eps = "0.5"
//     theta = ["0.25", "0.1"]   # several initial conditions: lists of equal length
//     v = ["12", "7"]
//     steps = 20
//     precision = "double"
// Command-line options override the scene's.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "bouncer/io/provenance.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/scalar/precision.hpp"

namespace bouncer {

struct Options {
  std::map<std::string, std::vector<std::string>> values;

  bool has(const std::string& key) const { return values.count(key) != 0; }
  void set(const std::string& key, std::vector<std::string> v) { values[key] = std::move(v); }
  void set(const std::string& key, const std::string& v) { values[key] = {v}; }
  // The single value of `key`; throws InputError if missing (`required`) or a list.
  std::string get(const std::string& key) const;
  std::string get_or(const std::string& key, const std::string& fallback) const;
  // Exact option texts for provenance, in key order.
  std::vector<std::pair<std::string, std::string>> inputs() const;
  // Options as a TOML scene that reproduces them.
  std::string as_toml(const std::string& command) const;
};

// The scenes of data/scenes/ compiled into the library (generated from lib/CMakeLists.txt;
// workflow/paper.hpp), key: the path from the source root ("data/scenes/NAME.toml"), value:
// the file's text.
const std::map<std::string, std::string>& built_in_scenes();
// Reads a scene file. Keys must be in `allowed`; decimals must be TOML strings or integers
// (a TOML float has already lost the exact decimal). Throws InputError. A PATH that names no
// file is looked up among the built-in scenes, so that scenes work from any directory and
// from an install: "data/scenes/NAME.toml", "NAME.toml", "NAME", and for the README's
// picture scenes (picture-NAME.toml) "NAME" alone too (e.g. bifurcation-eps096). An
// existing file is always the one read.
Options load_scene(const std::string& path, const std::string& command, const std::set<std::string>& allowed);
// The `command` key of a scene (for `bouncer --scene FILE`); throws InputError("scene", ...)
// when the file is unreadable, a directory, not TOML, or names no command.
std::string scene_command(const std::string& path);

// Scene values first, then command-line values on top.
Options merge(Options scene, const Options& command_line);

// Shared parsers of option groups (each throws InputError naming the option).
ModelSpec model_from(const Options& o);
Precision precision_from(const Options& o);
long long integer_from(const Options& o, const std::string& key, long long lo, long long hi, long long fallback);
std::vector<InitialCondition> initial_conditions_from(const Options& o, const ModelSpec& m);

// How decimal inputs become numbers at this precision (recorded in every output).
std::string decimal_note(const Precision& p);

// Keys of the model group, shared by every command.
const std::set<std::string>& model_keys();

}  // namespace bouncer
