// bouncer: command-line front end. One subcommand per experiment kind (tools/cmd_*.cpp);
// every subcommand takes its options from the command line and/or a TOML scene
// (--scene FILE, command line overrides). `bouncer --scene FILE` runs the scene's own
// command; `bouncer help CMD` is `bouncer CMD --help`.
//
// Exit status: 0 success (an orbit that stopped at an undecided step is a result, and is
// reported), 2 bad input (one line on stderr naming the option and the allowed range; no
// output file is left behind), 1 the computation or the output failed (a write to a file or
// to stdout that fails is never silent).
#include <iostream>
#include <vector>

#include "bouncer/io/output.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/io/scene.hpp"
#include "bouncer/model/spec.hpp"
#include "cli_common.hpp"
#include "command_line.hpp"
#include "commands.hpp"

namespace {

// `bouncer help [CMD]` is `bouncer [CMD] --help`; `bouncer --scene FILE ...` is
// `bouncer CMD --scene FILE ...` with CMD the scene's `command` key.
std::vector<std::string> front_end_words(int argc, char** argv) {
  std::vector<std::string> w(argv, argv + argc);
  if (w.size() >= 2 && w[1] == "help") {
    w.erase(w.begin() + 1);
    w.push_back("--help");
  } else if (w.size() >= 2 && (w[1] == "--scene" || w[1].rfind("--scene=", 0) == 0)) {
    const std::string path = w[1] == "--scene" ? (w.size() >= 3 ? w[2] : "") : w[1].substr(8);
    if (path.empty()) throw bouncer::InputError("scene", "give a scene file: bouncer --scene FILE");
    w.insert(w.begin() + 1, bouncer::scene_command(path));
  }
  return w;
}

}  // namespace

int main(int argc_in, char** argv_in) {
  using namespace bouncer;
  using namespace bouncer::cli;
  std::vector<std::string> words;
  try {
    words = front_end_words(argc_in, argv_in);
  } catch (const InputError& e) {
    std::cerr << "bouncer: " << one_line(e.what()) << "\n";
    return 2;
  }
  std::vector<char*> word_ptrs;
  for (std::string& w : words) word_ptrs.push_back(w.data());
  word_ptrs.push_back(nullptr);
  const int argc = static_cast<int>(words.size());
  char** argv = word_ptrs.data();
  CLI::App app{"bouncer: verified numerics for the piecewise linear bouncer (Langer & Miller 2014)"};
  app.require_subcommand(1);
  std::vector<Command> commands{add_orbit(app), add_certify_sticking(app), add_certify_periodic(app), add_sweep(app), add_audit(app), add_periodic(app), add_lyapunov(app), add_classify(app), add_bifurcation(app), add_portrait(app), add_basin(app), add_scan(app), add_merge(app), add_continue(app), add_trajectory(app), add_tongues(app), add_reproduce(app)};

  const std::string version = build_info().version + " (commit " + build_info().commit + ")";
  app.set_version_flag("--version", version);
  for (const Command& c : commands) c.app->set_version_flag("--version", version);
  if (const std::string problem = check_command_line(app, argc, argv); !problem.empty()) {
    std::cerr << "bouncer: " << one_line(problem) << "\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "bouncer: " << one_line(e.what()) << " (see bouncer --help)\n";
    return 2;
  }
  install_interrupt_cleanup();  // SIGINT/SIGTERM/SIGHUP remove partial files (io/output.hpp)
  try {
    for (const Command& c : commands)
      if (c.app->parsed()) {
        const int status = c.run(invocation(argc, argv));
        check_stdout();  // whatever a command printed must have arrived
        return status;
      }
  } catch (const InputError& e) {
    std::cerr << "bouncer: " << one_line(e.what()) << "\n";
    return 2;
  } catch (const OutputError& e) {
    std::cerr << "bouncer: " << one_line(e.what()) << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "bouncer: internal error: " << one_line(e.what()) << "\n";
    return 1;
  }
  return 0;
}
