// Shared by the libFuzzer targets of tests/fuzz/: running a bouncer command line in this
// process the way `reproduce --check` and `audit` validate one (base/cancel.hpp: the flag is
// set before the command starts, so it validates its inputs as usual and stops at its first
// long step; its stdout is captured), in a private temporary directory, and the properties
// every outcome must have. A property that fails aborts, so libFuzzer records the input as a
// crash (its file and the message on stderr).
#pragma once

#include <sys/types.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "bouncer/base/cancel.hpp"
#include "cli_common.hpp"
#include "run_command.hpp"

// A fuzz target must never start a process (bouncer's only ones are audit's reruns and
// reproduce's items: tools/child_process.hpp). The targets map those command lines to a
// no-op; should one slip through, this definition (it takes the place of libc's fork in the
// executable) makes it a crash with its stack instead of a copy of the fuzzer.
extern "C" pid_t fork(void) {
  std::fprintf(stderr, "bouncer fuzz: a command tried to start a process (fork) inside the fuzzer\n");
  std::abort();
}

namespace bouncer::fuzz {

[[noreturn]] inline void violated(const std::string& what) {
  std::fprintf(stderr, "bouncer fuzz: PROPERTY VIOLATED: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

// The words of a command line as a readable string for messages (control characters escaped).
inline std::string shown(const std::vector<std::string>& words) {
  std::string s;
  for (const std::string& w : words) {
    s += s.empty() ? "[" : ", [";
    for (unsigned char c : w) {
      if (c < 0x20 || c == 0x7f) {
        char b[8];
        std::snprintf(b, sizeof b, "\\x%02x", c);
        s += b;
      } else {
        s += static_cast<char>(c);
      }
    }
    s += "]";
  }
  return s;
}

// True when the command line could start a process if it ran: `audit` (it reruns the result
// with this binary), and `reproduce` unless it only prints the claims table or checks the
// manifest in this process (--claims-table, --check given exactly as flags).
inline bool starts_processes(const std::vector<std::string>& words) {
  bool reproduce = false, audit = false, in_process = false, flag_with_value = false;
  for (const std::string& w : words) {
    if (w == "reproduce") reproduce = true;
    if (w == "audit") audit = true;
    if (w == "--check" || w == "--claims-table") in_process = true;
    if (w.rfind("--check=", 0) == 0 || w.rfind("--claims-table=", 0) == 0) flag_with_value = true;  // --check=false
  }
  return audit || (reproduce && (!in_process || flag_with_value));
}

// A command line run in this process, cancelled at its first long step, stdout captured.
inline bouncer::cli::CommandOutcome run_cancelled(const std::vector<std::string>& words) {
  const std::atomic<bool> stop{true};
  const CancelScope cancel(&stop);
  bouncer::cli::CommandCapture swallow;
  const bouncer::cli::CaptureScope capture(&swallow);
  return bouncer::cli::run_command(words, false);
}

// The properties of every outcome: never an internal error (an exception bouncer did not
// sort into bad input, an output failure or a cancellation is a bug), and bad input is
// reported in one non-empty line.
inline void check_outcome(const bouncer::cli::CommandOutcome& o, const std::vector<std::string>& words) {
  using Kind = bouncer::cli::CommandOutcome::Kind;
  if (o.kind == Kind::internal) violated("internal error for " + shown(words) + ": " + o.message);
  if (o.kind == Kind::input && (o.message.empty() || o.message.find('\n') != std::string::npos))
    violated("bad input not reported in one line for " + shown(words) + ": '" + o.message + "'");
}

// The private working directory of a fuzz target (mkdtemp; the current directory from the
// first input on, so every relative path an input names resolves inside it).
inline const std::filesystem::path& private_dir() {
  static const std::filesystem::path dir = [] {
    std::string tmpl = (std::filesystem::temp_directory_path() / "bouncer-fuzz-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) {
      std::perror("bouncer fuzz: mkdtemp");
      std::abort();
    }
    if (::chdir(tmpl.c_str()) != 0) {
      std::perror("bouncer fuzz: chdir");
      std::abort();
    }
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(private_dir(), ec);
    });
    return std::filesystem::path(tmpl);
  }();
  return dir;
}

// For LLVMFuzzerInitialize (called before libFuzzer reads its arguments): the corpus
// directories, input files and the paths of libFuzzer's file options become absolute, and
// crash files go to the directory the fuzzer was started in (-artifact_prefix, unless given),
// since the target then moves into its private directory, which is removed at exit.
inline void enter_private_dir(int* argc, char*** argv) {
  static std::vector<std::string> words;
  static std::vector<char*> pointers;
  const std::filesystem::path start = std::filesystem::current_path();
  bool artifact_prefix = false;
  for (int i = 0; i < *argc; ++i) {
    std::string w = (*argv)[i];
    if (i > 0 && !w.empty() && w[0] != '-') {
      w = (start / w).lexically_normal().string();
    } else {
      for (const char* option : {"-artifact_prefix=", "-exact_artifact_path=", "-dict=", "-merge_control_file="})
        if (w.rfind(option, 0) == 0) {
          const std::string value = w.substr(std::strlen(option));
          if (!value.empty() && value[0] != '/') w = option + (start / value).string();
          artifact_prefix = artifact_prefix || std::string(option) == "-artifact_prefix=";
        }
    }
    words.push_back(w);
  }
  if (!artifact_prefix) words.push_back("-artifact_prefix=" + start.string() + "/");
  for (std::string& w : words) pointers.push_back(w.data());
  pointers.push_back(nullptr);
  *argc = static_cast<int>(words.size());
  *argv = pointers.data();
  private_dir();
}

// Removes what an input left in the private directory, except the entries in `keep`.
inline void clean_private_dir(const std::vector<std::string>& keep = {}) {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(private_dir(), ec)) {
    const std::string name = e.path().filename().string();
    bool kept = false;
    for (const std::string& k : keep) kept = kept || name == k;
    if (!kept) std::filesystem::remove_all(e.path(), ec);
  }
}

// Splits the fuzzer's bytes into words at '\n' (a word may hold any other byte, NUL too).
inline std::vector<std::string> words_of(const uint8_t* data, size_t size) {
  std::vector<std::string> words;
  std::string w;
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') {
      words.push_back(w);
      w.clear();
    } else {
      w += static_cast<char>(data[i]);
    }
  }
  if (!w.empty() || (size > 0 && data[size - 1] != '\n')) words.push_back(w);
  return words;
}

// Paths outside the private directory: absolute ones and any with "..". An input naming one
// is skipped, so that the fuzzer never reads or writes a file of the machine it runs on.
inline bool names_outside(const std::string& w) {
  if (w.find("..") != std::string::npos) return true;
  for (size_t i = 0; i < w.size(); ++i)
    if (w[i] == '/' && (i == 0 || w[i - 1] == '=' || w[i - 1] == ',' || w[i - 1] == ':')) return true;
  return !w.empty() && w[0] == '~';
}

}  // namespace bouncer::fuzz
