// Output files: where an --out path may be written, and how, so that a result is either
// complete or absent, never replaces what it should not, and never fails silently.
//
//   * a new path, or an existing regular file (or a symlink to one: the link's target is
//     written, the link survives): written to TARGET.partial and renamed over TARGET only
//     when every byte was written and the file closed without error;
//   * an existing character device or named pipe (/dev/null, /dev/stdout, a FIFO): written
//     through, never replaced (renaming over a device would replace it with a regular file);
//   * a directory, a path ending in '/', a socket or a block device (or a symlink to one):
//     refused as bad input (InputError naming the field, exit status 2).
// A failed write, flush, close or rename throws OutputError (exit status 1) after removing
// the partial file.
#pragma once

#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>

namespace bouncer {

// The computation was done, but its output could not be written (disk full, permissions,
// a closed pipe). Front ends report it in one line with exit status 1.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct OutputTarget {
  enum class Kind { file, stream } kind = Kind::file;
  std::string path;  // symlinks to regular files resolved
};

// Throws InputError(field, ...) for a path that must not be written.
OutputTarget output_target(const std::string& field, const std::string& path);

// Writes `body` to the target as described above; throws OutputError on any failure.
void write_output(const OutputTarget& target, const std::function<void(std::ostream&)>& body);

// Flushes std::cout and throws OutputError if anything written to it failed.
void check_stdout();

// Interrupts. install_interrupt_cleanup() makes SIGINT, SIGTERM and SIGHUP remove every
// partial file being written at that moment (PATH.partial of write_output, PNGs, tiles:
// never a finished file or a saved tile), print one line on stderr (with the hint set by
// set_interrupt_hint, e.g. how to resume), and end the process by the same signal (exit
// status 128 + N in a shell). The handler only unlinks and writes: async-signal-safe.
// A signal that was ignored when the process started (nohup, a background job of a
// script) stays ignored. A front end calls it once; the library never installs handlers.
void install_interrupt_cleanup();
void set_interrupt_hint(const std::string& text);

// Registers a partial file for that cleanup while it exists (write_output and the PNG
// writer use it; so should any other writer of PATH.partial files).
class PartialFile {
 public:
  explicit PartialFile(const std::string& path);
  ~PartialFile();
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace bouncer
