// Output files (io/output.hpp).
#include "bouncer/io/output.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <csignal>

#include <cerrno>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "bouncer/model/spec.hpp"

namespace bouncer {

namespace fs = std::filesystem;

OutputTarget output_target(const std::string& field, const std::string& path) {
  if (path.empty()) throw InputError(field, "is empty (give a file path)");
  if (path.back() == '/') throw InputError(field, "'" + path + "' ends in '/': give a file path, not a directory");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) {  // a new file: its folder must exist (a missing one is a typo, not a full disk)
      const fs::path parent = fs::path(path).parent_path();
      std::error_code ec;
      if (!parent.empty() && !fs::is_directory(parent, ec))
        throw InputError(field, "folder '" + parent.string() + "' does not exist (for '" + path + "')");
      return {OutputTarget::Kind::file, path};
    }
    throw InputError(field, "cannot use '" + path + "': " + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) {
    std::error_code ec;
    const fs::path real = fs::canonical(path, ec);  // write the link's target, keep the link
    return {OutputTarget::Kind::file, ec ? path : real.string()};
  }
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return {OutputTarget::Kind::stream, path};
  const char* what = S_ISDIR(st.st_mode) ? "a directory" : S_ISSOCK(st.st_mode) ? "a socket" : "a block device or special file";
  throw InputError(field, "'" + path + "' is " + what + ": give a regular file (or a character device or pipe to write through)");
}

void write_output(const OutputTarget& target, const std::function<void(std::ostream&)>& body) {
  if (target.kind == OutputTarget::Kind::stream) {
    std::ofstream f(target.path, std::ios::binary);
    if (!f) throw OutputError("cannot open '" + target.path + "' for writing: " + std::strerror(errno));
    body(f);
    f.flush();
    if (!f) throw OutputError("writing '" + target.path + "' failed");
    f.close();
    if (!f) throw OutputError("closing '" + target.path + "' failed");
    return;
  }
  const std::string tmp = target.path + ".partial";
  const PartialFile registered(tmp);
  try {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw OutputError("cannot write '" + target.path + "': " + std::strerror(errno));
    body(f);
    f.flush();
    if (!f) throw OutputError("writing '" + target.path + "' failed (disk full?)");
    f.close();
    if (!f) throw OutputError("closing '" + target.path + "' failed (disk full?)");
    std::error_code ec;
    fs::rename(tmp, target.path, ec);
    if (ec) throw OutputError("cannot rename '" + tmp + "' to '" + target.path + "': " + ec.message());
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

namespace {

// The partial-file registry: fixed slots, so that the signal handler reads it without
// allocating or locking. A slot is 0 free, 1 being filled, 2 holding a path.
constexpr int kSlots = 256;
constexpr size_t kPathMax = 4096;
std::atomic<int> slot_state[kSlots];
char slot_path[kSlots][kPathMax];
std::atomic<int> hint_state{0};
char hint_text[2048];

void on_interrupt(int sig) {
  for (int i = 0; i < kSlots; ++i)
    if (slot_state[i].load() == 2) ::unlink(slot_path[i]);
  const char* name = sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP";
  auto say = [](const char* t) {
    size_t n = 0;
    while (t[n]) ++n;
    ssize_t ignored = ::write(2, t, n);
    (void)ignored;
  };
  say("\nbouncer: interrupted by ");
  say(name);
  say("; partial files removed");
  if (hint_state.load() == 2) {
    say("; ");
    say(hint_text);
  }
  say("\n");
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

PartialFile::PartialFile(const std::string& path) {
  if (path.size() >= kPathMax) return;  // no such path can be created anyway
  for (int i = 0; i < kSlots; ++i) {
    int free_slot = 0;
    if (slot_state[i].compare_exchange_strong(free_slot, 1)) {
      std::memcpy(slot_path[i], path.c_str(), path.size() + 1);
      slot_state[i].store(2);
      slot_ = i;
      return;
    }
  }
  // More than kSlots files written at once: this one is not cleaned up on an interrupt.
}

PartialFile::~PartialFile() {
  if (slot_ >= 0) slot_state[slot_].store(0);
}

void set_interrupt_hint(const std::string& text) {
  hint_state.store(1);
  const size_t n = std::min(text.size(), sizeof hint_text - 1);
  std::memcpy(hint_text, text.data(), n);
  hint_text[n] = '\0';
  hint_state.store(2);
}

void install_interrupt_cleanup() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    // A signal ignored by whoever started us stays ignored (nohup, `cmd &` in a script).
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(sig, &sa, nullptr);
  }
}

void check_stdout() {
  std::cout.flush();
  if (!std::cout) throw OutputError("writing to standard output failed");
  if (std::fflush(stdout) != 0) throw OutputError(std::string("writing to standard output failed: ") + std::strerror(errno));
}

}  // namespace bouncer
