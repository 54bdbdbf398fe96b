// Running reproduce's items: each one a child process (workflow/child_process.hpp), N at a
// time, in the order given, with its stdout and stderr staged in the reproduce directory and
// a resume key written when it has finished and its outputs exist.
//   * Resume: an item whose key file holds its key (mode, build, command) and whose outputs
//     exist is not rerun (resumable()).
//   * Staging: an item's stdout and stderr are written to staging files created afresh
//     (base/output.hpp: never through a planted link) and renamed into place when it ends.
//   * Shared grids: an item with `after` starts once that item has ended, and reads its
//     tiles (--tiles-from) when they were kept (--keep-tiles on the item with tiles_prefix).
//   * Signals: while run_jobs waits for its children it catches SIGINT, SIGTERM and SIGHUP
//     (and restores the handlers it found when it returns; a signal ignored when it started
//     stays ignored). A signal sent to reproduce alone (kill PID, a batch system's TERM) is
//     passed to the running children: they stop, their staging files are removed, no key is
//     written for them, and run_jobs returns the signal, for the caller to end by it
//     (reraise_stop_signal) after saying how to resume. This is the one place the library
//     installs signal handlers, for the time it waits, because only it knows its children.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace bouncer {

enum class ItemState {
  pending,   // to run
  done,      // ran, exit 0, outputs present
  cached,    // resumed: ran before with the same key
  failed,    // could not run, exited non-zero, or left outputs missing
  deferred,  // a claim not settled in --quick
  skipped,   // a pending panel (the manifest's status)
};
// "pending", "done", ...: the words of the progress lines, reports and claims.json.
const char* state_name(ItemState s);

// One item to run (state pending), or settled before running (any other state).
struct Job {
  std::string id;
  std::vector<std::string> exec;            // exec[0]: the program's path
  std::string key, key_path;                // the resume key and its file
  std::string stdout_path, stderr_path;     // staged while it runs
  std::vector<std::string> outputs;         // relative to the directory: must exist after success
  std::optional<std::size_t> after;         // starts once that job has ended
  std::string tiles_prefix;                 // keeps its tiles at PREFIX.tiles for a later job
  ItemState state = ItemState::pending;
  std::string problem;                      // why it failed, was deferred or skipped
  int exit_status = 0;                      // 128 + N for a child ended by signal N
  double seconds = 0;
};

// Set (to 1) in the environment of every child run_jobs starts: a reproduce started inside
// one refuses (refuse_nested_reproduce, workflow/reproduce.hpp).
inline constexpr const char* kInReproduceVariable = "BOUNCER_IN_REPRODUCE";

// Called once per job as it is settled: jobs not pending first, then each as it ends.
using JobProgress = std::function<void(const Job& job, std::size_t finished, std::size_t total)>;

// True when `job`'s key file in `dir` holds job.key and all its outputs exist.
bool resumable(const Job& job, const std::string& dir);

// Runs the pending jobs, `n` at a time; returns 0, or the signal that stopped the run.
int run_jobs(std::vector<Job>& jobs, const std::string& dir, unsigned n, const JobProgress& progress);

// Removes the tiles kept for later jobs once every job drawn from them is done or cached;
// otherwise they stay, for a rerun.
void remove_kept_tiles(const std::vector<Job>& jobs);

// Ends the process by `sig` with its default action (the shell sees 128 + sig).
[[noreturn]] void reraise_stop_signal(int sig);

}  // namespace bouncer
