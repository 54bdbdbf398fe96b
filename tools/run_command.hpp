// One `bouncer` command line run in this process: parsing (bouncer's own messages for typos,
// CLI11 for the rest), the command, and its errors sorted by kind. main() (bouncer.cpp) and
// the Python module (python/module.cpp) both run commands through it, so a module call
// validates and answers exactly as the command line does.
#pragma once

#include <string>
#include <vector>

namespace bouncer::cli {

struct CommandOutcome {
  enum class Kind {
    ok,         // status 0
    help,       // --help or --version was printed (status 0)
    input,      // bad input: status 2, `message` is the one-line error
    output,     // the output failed: status 1
    internal,   // an unexpected error: status 1
    cancelled,  // the host's CancelScope flag was set (base/cancel.hpp): status 130
  };
  Kind kind = Kind::ok;
  int status = 0;
  std::string message;  // without the "bouncer: " prefix; empty when ok
  // An unknown option, as CLI11 / check_command_line name it ("--epss"), for hosts that
  // report it in their own words (the Python module: an unexpected keyword argument).
  std::string unknown_option;
};

// Runs WORDS (words[0] is the program name, words[1] the command or --scene). With
// `standalone` (the command-line tool) SIGINT/SIGTERM/SIGHUP remove partial files and end
// the process, and --help prints; a host leaves its signals alone.
CommandOutcome run_command(std::vector<std::string> words, bool standalone);

}  // namespace bouncer::cli
