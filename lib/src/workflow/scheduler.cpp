#include "bouncer/workflow/scheduler.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include "bouncer/base/input.hpp"
#include "bouncer/base/output.hpp"
#include "bouncer/workflow/child_process.hpp"

namespace bouncer {

namespace {

namespace fs = std::filesystem;

// A file of the reproduce directory ("" when absent): a regular file of at most 1 GiB, never
// a FIFO or device planted there (InputError naming --out).
std::string read_text(const fs::path& p) {
  return read_input_file_if_present("out", p.string(), kMaxResultBytes).value_or("");
}

// SIGINT, SIGTERM and SIGHUP caught while run_jobs waits for its children (installed without
// SA_RESTART, so waitpid returns EINTR); restored on destruction.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void note_stop_signal(int sig) { g_stop_signal = sig; }
class StopSignals {
 public:
  StopSignals() {
    g_stop_signal = 0;
    struct sigaction sa {};
    sa.sa_handler = note_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    for (size_t i = 0; i < std::size(kSignals); ++i) {
      ::sigaction(kSignals[i], &sa, &old_[i]);
      // A signal ignored when reproduce started (nohup; SIGINT of a background job) stays so.
      if (old_[i].sa_handler == SIG_IGN) ::sigaction(kSignals[i], &old_[i], nullptr);
    }
  }
  ~StopSignals() {
    for (size_t i = 0; i < std::size(kSignals); ++i) ::sigaction(kSignals[i], &old_[i], nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  int caught() const { return g_stop_signal; }

 private:
  static constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction old_[std::size(kSignals)] {};
};

// A running job: its staging files (stdout and stderr) and when it started.
struct Running {
  size_t index;
  std::chrono::steady_clock::time_point start;
  std::unique_ptr<OutputSet> files;
};

}  // namespace

const char* state_name(ItemState s) {
  switch (s) {
    case ItemState::pending: return "pending";
    case ItemState::done: return "done";
    case ItemState::cached: return "cached";
    case ItemState::failed: return "failed";
    case ItemState::deferred: return "deferred";
    case ItemState::skipped: return "skipped";
  }
  return "?";
}

bool resumable(const Job& job, const std::string& dir) {
  bool have = read_text(job.key_path) == job.key;
  for (const std::string& f : job.outputs) have = have && fs::exists(fs::path(dir) / f);
  return have;
}

int run_jobs(std::vector<Job>& jobs, const std::string& dir, unsigned n, const JobProgress& progress) {
  const size_t total = jobs.size();
  size_t finished = 0;
  auto settled = [&](const Job& job) {
    ++finished;
    if (progress) progress(job, finished, total);
  };
  for (const Job& job : jobs)
    if (job.state != ItemState::pending) settled(job);
  std::map<pid_t, Running> running;
  std::vector<bool> started(jobs.size(), false);
  // The next job to start: in order, the first pending one whose `after` job (if any) has
  // ended.
  auto next_ready = [&]() -> std::optional<size_t> {
    for (size_t i = 0; i < jobs.size(); ++i) {
      if (started[i] || jobs[i].state != ItemState::pending) continue;
      if (jobs[i].after && jobs[*jobs[i].after].state == ItemState::pending) continue;
      return i;
    }
    return std::nullopt;
  };
  // A signal to reproduce alone (kill PID, a batch system's TERM) reaches its children too:
  // they stop, no key is written for them, and a rerun resumes (a terminal's Ctrl-C reaches
  // the whole process group anyway).
  const StopSignals stop;
  bool forwarded = false;
  while (true) {
    while (running.size() < n && !stop.caught()) {
      const auto ready = next_ready();
      if (!ready) break;
      const size_t idx = *ready;
      Job& job = jobs[idx];
      started[idx] = true;
      std::error_code rm;
      fs::remove(job.key_path, rm);
      if (!job.tiles_prefix.empty()) job.exec.push_back("--keep-tiles");
      if (job.after) {
        const std::string from = jobs[*job.after].tiles_prefix;
        if (fs::is_regular_file(from + ".tiles/job.key", rm)) job.exec.insert(job.exec.end(), {"--tiles-from", from});
      }
      // Its stdout and stderr go to staging files of the reproduce directory (created
      // afresh, never through a planted link), renamed into place when it ends.
      auto files = std::make_unique<OutputSet>();
      files->reserve("out", job.stdout_path);
      files->reserve("out", job.stderr_path);
      // The environment entry as a named string: GCC 12 reports a false -Warray-bounds on a
      // temporary `std::string(...) + "=1"` inside the braced list.
      const std::string in_reproduce = std::string(kInReproduceVariable) + "=1";
      const pid_t pid = start_child(job.exec, files->descriptor(job.stdout_path), files->descriptor(job.stderr_path), "",
                                    {in_reproduce});
      if (pid < 0) {
        job.state = ItemState::failed;
        job.problem = "could not start " + job.exec[0];
        settled(job);
        continue;
      }
      running[pid] = Running{idx, std::chrono::steady_clock::now(), std::move(files)};
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (stop.caught() && !forwarded) {  // (a signal just before waitpid: the next child's end wakes it)
      forwarded = true;
      for (const auto& child : running)
        if (child.first != pid) ::kill(child.first, stop.caught());
    }
    if (pid < 0 && errno == EINTR) continue;
    if (pid < 0) break;
    auto r = running.find(pid);
    if (r == running.end()) continue;
    Job& job = jobs[r->second.index];
    job.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - r->second.start).count();
    std::unique_ptr<OutputSet> files = std::move(r->second.files);
    running.erase(r);
    job.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    // Stopped: its staging files are removed (with `files`), no key written.
    if (stop.caught()) continue;
    files->commit();  // its stdout and stderr, into place
    files.reset();
    bool outputs_ok = true;
    for (const std::string& f : job.outputs) outputs_ok = outputs_ok && fs::exists(fs::path(dir) / f);
    if (job.exit_status == 0 && outputs_ok) {
      job.state = ItemState::done;
      write_output("out", job.key_path, [&](std::ostream& s) { s << job.key; });
    } else {
      job.state = ItemState::failed;
      std::string err = read_text(job.stderr_path);
      if (const auto nl = err.find_last_not_of("\n"); nl != std::string::npos) err = err.substr(0, nl + 1);
      if (const auto last = err.rfind('\n'); last != std::string::npos) err = err.substr(last + 1);
      job.problem = "exit status " + std::to_string(job.exit_status) + (outputs_ok ? "" : ", outputs missing") +
                    (err.empty() ? "" : ": " + one_line(err));
    }
    settled(job);
  }
  // Stopped: the staging files of the children still running are removed with `running`
  // (an OutputSet never committed removes its own); finished jobs keep their keys.
  return stop.caught();
}

void remove_kept_tiles(const std::vector<Job>& jobs) {
  for (const Job& src : jobs) {
    if (src.tiles_prefix.empty()) continue;
    bool needed = false;
    for (const Job& job : jobs)
      needed = needed || (job.after && jobs[*job.after].id == src.id && job.state != ItemState::done &&
                          job.state != ItemState::cached);
    std::error_code rm;
    if (!needed) fs::remove_all(src.tiles_prefix + ".tiles", rm);
  }
}

void reraise_stop_signal(int sig) {
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  std::cerr.flush();
  ::raise(sig);
  std::_Exit(128 + sig);
}

}  // namespace bouncer
