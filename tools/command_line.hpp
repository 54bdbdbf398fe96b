// The command line before CLI11 sees it: bouncer's own one-line messages for what CLI11
// would reject with a message that names no allowed values (unknown commands and options,
// with a did-you-mean; `--opt=` with no value), and every error line made safe to print
// (control characters escaped, long echoed values cut).
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "bouncer/base/input.hpp"
#include "bouncer/base/text.hpp"

namespace bouncer::cli {

// Edit distance (Levenshtein), for suggestions (base/text.hpp: reproduce suggests ids with it too).
using bouncer::edit_distance;

// The closest of names to a word, if close enough to be a typo (base/text.hpp).
using bouncer::closest;

// One printable line (base/input.hpp): control characters escaped, at most `limit` characters.
using bouncer::one_line;

// Checks argv against the registered commands and their options; returns the message of
// the first problem ("" if none). Runs before CLI11, whose messages for these cases name
// no allowed values.
inline std::string check_command_line(CLI::App& app, int argc, char** argv) {
  if (argc < 2) return "";
  const std::string first = argv[1];
  if (first.empty() || first[0] == '-') return "";  // --help, --version
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
  names.push_back("help");  // bouncer help CMD (tools/run_command.cpp)
  CLI::App* sub = nullptr;
  for (CLI::App* c : app.get_subcommands({}))
    if (c->get_name() == first) sub = c;
  if (!sub) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    const auto guess = closest(first, names);
    return "unknown command '" + first + "'" + (guess ? " (did you mean '" + *guess + "'?)" : "") + "; commands: " + list;
  }
  std::vector<std::string> options;
  bool positionals = false;
  for (const CLI::Option* o : sub->get_options()) {
    for (const std::string& n : o->get_lnames()) options.push_back("--" + n);
    positionals = positionals || o->get_positional();
  }
  auto find_option = [&](const std::string& name) -> const CLI::Option* {
    for (const CLI::Option* o : sub->get_options())
      for (const std::string& n : o->get_lnames())
        if ("--" + n == name) return o;
    return nullptr;
  };
  std::string last_option;
  std::vector<std::string> given;  // options with one value seen so far
  for (int i = 2; i < argc; ++i) {
    const std::string tok = argv[i];
    if (tok == "--") break;
    if (tok.rfind("--", 0) != 0) {
      // A word no option takes: CLI11 would say "argument was not expected", naming nothing.
      if (!positionals)
        return first + ": unexpected value '" + tok + "'" +
               (last_option.empty() ? "" : " after " + last_option + " (options take one value; lists are comma-separated)") +
               "; see bouncer " + first + " --help";
      continue;
    }
    const auto eq = tok.find('=');
    const std::string name = tok.substr(0, eq);
    if (eq != std::string::npos && eq + 1 == tok.size())
      return name.substr(2) + ": '" + tok + "' gives no value (write " + name + " VALUE)";
    if (name == "--help" || name == "--version") continue;
    const CLI::Option* opt = find_option(name);
    if (!opt) {
      const auto guess = closest(name, options);
      return first + ": unknown option '" + name + "'" + (guess ? " (did you mean " + *guess + "?)" : "") +
             "; see bouncer " + first + " --help";
    }
    last_option = name;
    // An option of one value given twice: which one was meant is not for bouncer to guess
    // (a list option, --theta 0.1 --theta 0.2, collects both; a repeated flag is harmless).
    if (opt->get_items_expected_max() != 0 && opt->get_expected_max() <= 1) {
      if (std::find(given.begin(), given.end(), name) != given.end())
        return name.substr(2) + ": " + name + " is given twice; give it once; see bouncer " + first + " --help";
      given.push_back(name);
    }
    if (opt->get_items_expected_max() == 0 || eq != std::string::npos) continue;  // a flag, or --opt=value
    // The option's value(s): the next word(s) up to the next option. A value may start
    // with '-' (a negative number) but not with "--".
    if (i + 1 >= argc || std::string(argv[i + 1]).rfind("--", 0) == 0) {
      if (opt->get_expected_min() == 0) continue;  // its value may be left out (--confirm)
      return name.substr(2) + ": " + name + " needs a value; see bouncer " + first + " --help";
    }
    ++i;
    if (opt->get_expected_max() > 1)
      while (i + 1 < argc && std::string(argv[i + 1]).rfind("--", 0) != 0) ++i;
  }
  return "";
}

}  // namespace bouncer::cli
