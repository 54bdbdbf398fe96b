// bouncer: command-line front end. One subcommand per experiment kind (tools/cmd_*.cpp);
// every subcommand takes its options from the command line and/or a TOML scene
// (--scene FILE, command line overrides). `bouncer --scene FILE` runs the scene's own
// command; `bouncer help CMD` is `bouncer CMD --help`. Parsing and running live in
// run_command.cpp, shared with the Python module.
//
// Exit status: 0 success (an orbit that stopped at an undecided step is a result, and is
// reported), 2 bad input (one line on stderr naming the option and the allowed range; no
// output file is left behind), 1 the computation or the output failed (a write to a file or
// to stdout that fails is never silent).
#include <iostream>
#include <string>
#include <vector>

#include "run_command.hpp"

int main(int argc, char** argv) {
  const bouncer::cli::CommandOutcome o = bouncer::cli::run_command(std::vector<std::string>(argv, argv + argc), true);
  if (!o.message.empty()) std::cerr << "bouncer: " << o.message << "\n";
  return o.status;
}
