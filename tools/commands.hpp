// The command line's side of the table of commands (lib/include/bouncer/workflow/commands.hpp):
// each tools/cmd_NAME.cpp defines setup_NAME, which adds the command's options to the
// subcommand the table made and returns the function that runs it. Adding a command = one
// row of the table, one file and one row of the binding in tools/commands.cpp.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <string_view>

namespace bouncer::cli {

// Runs the parsed command; `invocation` is the command line as typed. Returns the exit status.
using CommandRunner = std::function<int(const std::string& invocation)>;
using CommandSetup = CommandRunner (*)(CLI::App* sub);

// The setup of the command named `name` (a name of command_table()), or nullptr.
CommandSetup command_setup(std::string_view name);

#define BOUNCER_COMMAND(name) CommandRunner setup_##name(CLI::App* sub);
BOUNCER_COMMAND(orbit)
BOUNCER_COMMAND(certify_sticking)
BOUNCER_COMMAND(certify_periodic)
BOUNCER_COMMAND(certify_chaos)
BOUNCER_COMMAND(check_certificate)
BOUNCER_COMMAND(sweep)
BOUNCER_COMMAND(audit)
BOUNCER_COMMAND(periodic)
BOUNCER_COMMAND(lyapunov)
BOUNCER_COMMAND(classify)
BOUNCER_COMMAND(bifurcation)
BOUNCER_COMMAND(portrait)
BOUNCER_COMMAND(basin)
BOUNCER_COMMAND(attractors)
BOUNCER_COMMAND(scan)
BOUNCER_COMMAND(merge)
BOUNCER_COMMAND(continue)
BOUNCER_COMMAND(trajectory)
BOUNCER_COMMAND(tongues)
BOUNCER_COMMAND(reproduce)
#undef BOUNCER_COMMAND

}  // namespace bouncer::cli
