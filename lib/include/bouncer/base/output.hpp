// Output files: the one way bouncer writes a file (CSV, JSON, text, PNG, PDF, SVG, tiles,
// job files, claims, reports), so that a result is complete or absent, never replaces what it
// should not, never follows a link someone planted, never interleaves with another run, and
// never fails silently.
//
// What an output path may be (output_target):
//   * a new path in an existing folder, or an existing regular file: written to the staging
//     file PATH.partial and renamed over PATH when every byte is written (rename replaces a
//     directory entry; it never writes through a link that appears at PATH meanwhile);
//   * an existing character device or named pipe (/dev/null, /dev/stdout, a FIFO), or a
//     symbolic link to one: written through, never replaced (a FIFO's reader gets the data);
//   * a path under /dev/ or /proc/ that is a link to a regular file (/dev/stdout of a shell
//     redirected to a file): written through, as the shell's redirection asked;
//   * refused as bad input (InputError naming the field, exit status 2): a symbolic link to a
//     regular file elsewhere (bouncer never writes through a link in an output folder: it may
//     have been planted to point anywhere; give the file's own path), a dangling link, a
//     directory or a path ending in '/', a socket or block device, a missing folder, a name
//     the file system cannot hold (a component over 255 bytes once ".partial" is added).
//
// Staging files are created with O_CREAT | O_EXCL | O_NOFOLLOW, so a link, FIFO or file
// planted at PATH.partial is never written through: a link or special file there is removed
// (the name only; nothing it points to changes) and the staging file created afresh. Each
// staging file is locked (an open file description lock, F_OFD_SETLK: it excludes other
// processes and other threads of this process alike) for as long as the run holds it, so a
// second run writing the same path is refused at its start (InputError: "being written by
// another bouncer run"), and a staging file left by a killed run (unlocked) is reclaimed.
// The staging files of an OutputSet are created when it reserves its paths, before the
// computation: a path that cannot be written is found at once, not after hours of work.
//
// A failed write, flush, close or rename throws OutputError (exit status 1) after removing
// the staging files; a closed pipe is a failed write (EPIPE: the command-line tool ignores
// SIGPIPE, so the write fails instead of killing the process).
#pragma once

#include <functional>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>

#include "bouncer/base/error.hpp"

namespace bouncer {

struct OutputTarget {
  enum class Kind { file, stream } kind = Kind::file;
  std::string path;
};

// Checks an output path as described above; throws InputError(field, ...) for a path that
// must not be written.
OutputTarget output_target(const std::string& field, const std::string& path);

// Output files written all or none. reserve() checks each path and creates its locked
// staging file at once; write() fills one file completely (reserving it first if needed);
// commit() renames every written staging file into place, in reservation order. A set
// destroyed before commit() (an exception, a cancellation) removes its staging files, so
// nothing of it is left; files written through (devices, pipes) cannot be taken back.
class OutputSet {
 public:
  OutputSet();
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  void reserve(const std::string& field, const std::string& path);
  bool reserved(const std::string& path) const;
  void write(const std::string& path, const std::function<void(std::ostream&)>& body);
  // The staging file of a reserved path, for a child process to write into (dup2 onto its
  // stdout): the file then counts as written. -1 for a path written through (a device or
  // pipe), which the child should open itself.
  int descriptor(const std::string& path);
  void commit();
  // Removes every staging file not yet committed (as the destructor does).
  void discard();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One file, written as an OutputSet of one.
void write_output(const std::string& field, const std::string& path, const std::function<void(std::ostream&)>& body);

// Flushes std::cout and throws OutputError if anything written to it failed.
void check_stdout();

// Interrupts. install_interrupt_cleanup() makes SIGINT, SIGTERM and SIGHUP remove every
// staging file being written at that moment (PATH.partial of an OutputSet: never a finished
// file or a saved tile), print one line on stderr (with the hint set by set_interrupt_hint,
// e.g. how to resume), and end the process by the same signal (exit status 128 + N in a
// shell). It also ignores SIGPIPE, so that a closed pipe is a failed write (exit status 1),
// not a kill that leaves staging files. The handler only unlinks and writes:
// async-signal-safe. A signal that was ignored when the process started (nohup, a background
// job of a script) stays ignored. A front end calls it once; the library installs no other
// handlers, but for reproduce's scheduler (workflow/scheduler.hpp), which catches SIGINT,
// SIGTERM and SIGHUP while it waits for its children, and restores the previous ones.
void install_interrupt_cleanup();
void set_interrupt_hint(const std::string& text);

// Registers a staging file for that cleanup while it exists (OutputSet does).
class PartialFile {
 public:
  explicit PartialFile(const std::string& path);
  ~PartialFile();
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;

 private:
  int slot_ = -1;
};

// "process PID (its command line)", or "another command of this process" for this one's
// pid, or "another bouncer run" when the pid is unknown (0): the holder of a lock, in messages.
std::string process_text(long pid);

// A directory bouncer keeps its own files in (PREFIX.tiles/, a reproduce directory's
// panels/ and claims/): created if missing (its parent must exist); an existing one must be
// a real directory, not a symbolic link (which could point at any directory whose files a
// later clean-up would delete). Throws InputError(field, ...) or OutputError.
void make_own_directory(const std::string& field, const std::string& path);

}  // namespace bouncer
