// Subcommand registry: each tools/cmd_*.cpp adds one subcommand to the CLI11 app and
// returns the function that runs it. Adding a command = one file + one line in bouncer.cpp.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace bouncer::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<int(const std::string& invocation)> run;  // returns the exit status
};

Command add_orbit(CLI::App& app);
Command add_certify_sticking(CLI::App& app);
Command add_certify_periodic(CLI::App& app);
Command add_sweep(CLI::App& app);
Command add_audit(CLI::App& app);
Command add_periodic(CLI::App& app);
Command add_lyapunov(CLI::App& app);
Command add_classify(CLI::App& app);
Command add_bifurcation(CLI::App& app);
Command add_portrait(CLI::App& app);
Command add_basin(CLI::App& app);
Command add_scan(CLI::App& app);
Command add_merge(CLI::App& app);
Command add_continue(CLI::App& app);
Command add_trajectory(CLI::App& app);
Command add_tongues(CLI::App& app);
Command add_reproduce(CLI::App& app);

}  // namespace bouncer::cli
