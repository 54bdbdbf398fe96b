// The three ways a computation can fail, which every front end reports in one line: bad
// input (exit status 2), an output that could not be written, or a machine that could not
// give what the computation needs (exit status 1). The bottom layer: everything may throw
// them, nothing here depends on anything of bouncer's.
#pragma once

#include <stdexcept>
#include <string>

namespace bouncer {

// Bad input: names the field (command-line option or scene key) and the allowed range.
struct InputError : std::runtime_error {
  std::string field;
  InputError(std::string f, const std::string& what)
      : std::runtime_error(f + ": " + what), field(std::move(f)) {}
};

// The computation was done, but its output could not be written (disk full, permissions,
// a closed pipe). Front ends report it in one line with exit status 1.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The computation could not get what it needs from the machine (threads, memory): exit
// status 1, like a failed output, with a message that says what to ask for instead.
struct ResourceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace bouncer
