// The output writer (base/output.hpp): what test_io_safety.cpp does not cover (planted links
// and FIFOs, a second writer in this process, stale staging files, TOML shapes are there).
// Here: the kinds output_target gives each path, OutputSet's contract (rewrites, bodies that
// throw, descriptors, commit preconditions), failed writes (/dev/full, a closed pipe),
// another process holding a path's lock, the interrupt clean-up, check_stdout and
// make_own_directory. Truth: the header's promises, checked on real files with POSIX calls
// (stat, fork, waitpid, pipes) in a fresh temporary directory; what runs in a forked child
// reports through its exit status or a file, never through gtest.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>

#include "bouncer/base/output.hpp"
#include "bouncer/model/spec.hpp"
#include "test_support.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace bouncer;
using namespace bouncer::test_support;

// The OutputError's message, or "" when none is thrown.
template <class F>
std::string output_error(F&& f) {
  try {
    f();
  } catch (const OutputError& e) {
    return e.what();
  }
  return "";
}

// Runs `child` in a forked process (its return value is the exit status) and returns the
// raw wait status.
template <class F>
int in_child(F&& child) {
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = ::fork();
  if (pid == 0) {
    int status = 99;
    try {
      status = child();
    } catch (...) {
      status = 98;
    }
    ::_exit(status);
  }
  int ws = 0;
  EXPECT_GT(pid, 0);
  EXPECT_EQ(::waitpid(pid, &ws, 0), pid);
  return ws;
}

int exit_status(int ws) { return WIFEXITED(ws) ? WEXITSTATUS(ws) : -WTERMSIG(ws); }

// ---- output_target -----------------------------------------------------------------------------

TEST(OutputTarget, EachKindOfPathIsClassifiedAsDocumented) {
  TempDir d;
  EXPECT_EQ(output_target("out", d / "new.csv").kind, OutputTarget::Kind::file);
  put(d / "old.csv", "x");
  EXPECT_EQ(output_target("out", d / "old.csv").kind, OutputTarget::Kind::file);
  EXPECT_EQ(output_target("out", "/dev/null").kind, OutputTarget::Kind::stream);
  EXPECT_EQ(output_target("out", d / "new.csv").path, d / "new.csv");
  // A /proc link to a regular file (a shell's redirected descriptor) is written through.
  const int fd = ::open((d / "redirected").c_str(), O_WRONLY | O_CREAT, 0600);
  ASSERT_GE(fd, 0);
  const std::string proc = "/proc/self/fd/" + std::to_string(fd);
  EXPECT_EQ(output_target("out", proc).kind, OutputTarget::Kind::stream);
  ::close(fd);
}

TEST(OutputTarget, RefusedPathsNameTheField) {
  TempDir d;
  EXPECT_TRUE(contains(expect_input_error([&] { output_target("png", ""); }, "png"), "is empty"));
  fs::create_symlink(d / "nowhere", d / "dangling");
  EXPECT_TRUE(contains(expect_input_error([&] { output_target("png", d / "dangling"); }, "png"), "symbolic link to nothing"));
  fs::create_directory(d / "dir");
  fs::create_directory_symlink(d / "dir", d / "dirlink");
  EXPECT_TRUE(contains(expect_input_error([&] { output_target("json", d / "dirlink"); }, "json"), "symbolic link to a directory"));
  // A socket.
  const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(s, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  const std::string sock = d / "sock";
  ASSERT_LT(sock.size(), sizeof addr.sun_path);
  std::strcpy(addr.sun_path, sock.c_str());
  ASSERT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  EXPECT_TRUE(contains(expect_input_error([&] { output_target("out", sock); }, "out"), "is a socket"));
  ::close(s);
  // Nothing was created beside what the test made.
  EXPECT_EQ(d.entries(), 4);
}

// ---- OutputSet ---------------------------------------------------------------------------------

TEST(OutputSet, ASecondWriteReplacesTheFirstCompletely) {
  TempDir d;
  OutputSet set;
  set.write(d / "o.txt", text("a long first version\n"));  // reserves on first use
  EXPECT_TRUE(set.reserved(d / "o.txt"));
  set.write(d / "o.txt", text("short\n"));
  set.commit();
  EXPECT_EQ(slurp(d / "o.txt"), "short\n");
  EXPECT_EQ(d.entries(), 1);
  EXPECT_THROW(set.write(d / "o.txt", text("again")), std::logic_error);  // committed already
  EXPECT_EQ(slurp(d / "o.txt"), "short\n");
}

TEST(OutputSet, ReservingTwiceIsOneReservation) {
  TempDir d;
  OutputSet set;
  set.reserve("out", d / "o.csv");
  set.reserve("out", d / "o.csv");  // not "in use by another command": the same set
  EXPECT_TRUE(set.reserved(d / "o.csv"));
  EXPECT_FALSE(set.reserved(d / "p.csv"));
  set.write(d / "o.csv", text("x"));
  set.commit();
  EXPECT_EQ(slurp(d / "o.csv"), "x");
}

TEST(OutputSet, ABodyThatThrowsLeavesNothingAndKeepsOldFiles) {
  TempDir d;
  put(d / "old.csv", "previous\n");
  OutputSet set;
  set.reserve("out", d / "old.csv");
  set.reserve("out", d / "new.json");
  set.write(d / "new.json", text("{}"));
  EXPECT_THROW(set.write(d / "old.csv", [](std::ostream& s) {
    s << std::string(200000, 'x');  // more than the 64 KiB buffer: some bytes reached the file
    throw std::runtime_error("computation failed");
  }),
               std::runtime_error);
  EXPECT_EQ(slurp(d / "old.csv"), "previous\n");
  EXPECT_EQ(d.entries(), 1);  // both staging files gone, new.json never appeared
}

TEST(OutputSet, CommitOfAReservedButUnwrittenPathIsALogicErrorAndCleansUp) {
  TempDir d;
  OutputSet set;
  set.reserve("out", d / "a.csv");
  set.reserve("out", d / "b.csv");
  set.write(d / "a.csv", text("a"));
  EXPECT_THROW(set.commit(), std::logic_error);
  EXPECT_EQ(d.entries(), 0);
}

TEST(OutputSet, DiscardRemovesTheStagingFiles) {
  TempDir d;
  OutputSet set;
  set.reserve("out", d / "a.csv");
  set.write(d / "a.csv", text("a"));
  EXPECT_TRUE(fs::exists(d / "a.csv.partial"));
  set.discard();
  EXPECT_EQ(d.entries(), 0);
  // The path is free for another writer at once.
  write_output("out", d / "a.csv", text("b"));
  EXPECT_EQ(slurp(d / "a.csv"), "b");
}

TEST(OutputSet, ADescriptorWrittenDirectlyCountsAsWritten) {
  TempDir d;
  OutputSet set;
  set.reserve("out", d / "child.txt");
  set.reserve("out", "/dev/null");
  EXPECT_EQ(set.descriptor("/dev/null"), -1);  // a device: the child opens it itself
  const int fd = set.descriptor(d / "child.txt");
  ASSERT_GE(fd, 0);
  const std::string bytes = "written by a child process\n";
  ASSERT_EQ(::write(fd, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  EXPECT_FALSE(fs::exists(d / "child.txt"));
  set.commit();
  EXPECT_EQ(slurp(d / "child.txt"), bytes);
  EXPECT_THROW(set.descriptor(d / "other.txt"), std::logic_error);
}

TEST(OutputSet, CommitReplacesTheFileNotItsContents) {
  // rename(2) puts a new file in place: a reader of the old one keeps reading the old bytes.
  TempDir d;
  put(d / "o.csv", "old\n");
  std::ifstream reader(d / "o.csv");
  write_output("out", d / "o.csv", text("new\n"));
  std::string line;
  std::getline(reader, line);
  EXPECT_EQ(line, "old");
  EXPECT_EQ(slurp(d / "o.csv"), "new\n");
}

// ---- failed writes ----------------------------------------------------------------------------

TEST(FailedWrite, AFullDeviceIsAnOutputError) {
  // /dev/full: every write fails with ENOSPC. Small bodies fail at the flush, large ones at
  // once; neither may pass silently.
  for (size_t n : {size_t{10}, size_t{300000}}) {
    const std::string m = output_error([&] { write_output("out", "/dev/full", text(std::string(n, 'x'))); });
    EXPECT_TRUE(contains(m, "writing '/dev/full' failed")) << n << ": " << m;
    EXPECT_TRUE(contains(m, std::strerror(ENOSPC))) << m;
  }
}

TEST(FailedWrite, AClosedPipeIsAnOutputErrorNotAKill) {
  // install_interrupt_cleanup ignores SIGPIPE, so a reader that went away makes the write
  // fail with EPIPE (exit status 1 in the tool) instead of killing the process. The reader
  // opens the FIFO, reads a little and closes it; the body is larger than the pipe's buffer,
  // so the writer is still writing when the reader is gone.
  TempDir d;
  const std::string fifo = d / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int ws = in_child([&] {
    install_interrupt_cleanup();
    std::thread reader([&] {
      const int fd = ::open(fifo.c_str(), O_RDONLY);
      char buf[16];
      if (fd >= 0) {
        (void)!::read(fd, buf, sizeof buf);
        ::close(fd);
      }
    });
    int status = 12;
    try {
      write_output("out", fifo, text(std::string(4 << 20, 'x')));
    } catch (const OutputError& e) {
      status = contains(e.what(), std::strerror(EPIPE)) ? 0 : 11;
    }
    reader.join();
    return status;
  });
  EXPECT_EQ(exit_status(ws), 0) << "status " << exit_status(ws) << " (negative: killed by that signal)";
}

// ---- locks across processes ---------------------------------------------------------------------

TEST(Lock, AnotherProcessHoldingThePathIsNamedAndItsDeathFreesIt) {
  TempDir d;
  const std::string path = d / "o.csv";
  int ready[2], release[2];
  ASSERT_EQ(::pipe(ready), 0);
  ASSERT_EQ(::pipe(release), 0);
  std::cout.flush();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(ready[0]);
    ::close(release[1]);
    int status = 0;
    try {
      OutputSet set;
      set.reserve("out", path);
      set.write(path, text("child\n"));
      char c = 1;
      if (::write(ready[1], &c, 1) != 1) status = 20;
      (void)!::read(release[0], &c, 1);  // until the parent closes its end
    } catch (...) {
      status = 21;
    }
    ::_exit(status);  // killed-run style: no destructor removes the staging file
  }
  ASSERT_GT(pid, 0);
  ::close(ready[1]);
  ::close(release[0]);
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  OutputSet mine;
  const std::string m = expect_input_error([&] { mine.reserve("out", path); }, "out");
  EXPECT_TRUE(contains(m, "is in use by process " + std::to_string(pid))) << m;
  EXPECT_TRUE(contains(m, "is locked")) << m;
  EXPECT_EQ(slurp(path + ".partial"), "child\n");  // the other run's work is untouched
  ::close(release[1]);
  int ws = 0;
  ASSERT_EQ(::waitpid(pid, &ws, 0), pid);
  EXPECT_EQ(exit_status(ws), 0);
  ::close(ready[0]);
  // The holder is gone (its lock with it): its staging file is reclaimed.
  mine.reserve("out", path);
  mine.write(path, text("parent\n"));
  mine.commit();
  EXPECT_EQ(slurp(path), "parent\n");
  EXPECT_FALSE(fs::exists(path + ".partial"));
}

TEST(Lock, ProcessTextNamesTheHolder) {
  EXPECT_EQ(process_text(0), "another bouncer run");
  EXPECT_EQ(process_text(::getpid()), "another command of this process (pid " + std::to_string(::getpid()) + ")");
  // A real other process: its pid and its command line as /proc shows it.
  pid_t pid = 0;
  char arg0[] = "/bin/sleep", arg1[] = "30";
  char* argv[] = {arg0, arg1, nullptr};
  ASSERT_EQ(::posix_spawn(&pid, "/bin/sleep", nullptr, nullptr, argv, environ), 0);
  // posix_spawn may return before the kernel has set up the new program's arguments: wait
  // until /proc shows them (read here independently).
  for (int i = 0; i < 200 && slurp("/proc/" + std::to_string(pid) + "/cmdline").empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(process_text(pid), "process " + std::to_string(pid) + " (/bin/sleep 30)");
  ::kill(pid, SIGKILL);
  int ws = 0;
  ::waitpid(pid, &ws, 0);
}

// ---- interrupts ----------------------------------------------------------------------------------

TEST(Interrupt, ASignalRemovesStagingFilesOnlyAndSaysSo) {
  TempDir d;
  const std::string err = d / "stderr.txt";
  const int ws = in_child([&] {
    const int fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd < 0 || ::dup2(fd, 2) < 0) return 30;
    install_interrupt_cleanup();
    set_interrupt_hint("rerun the same command to resume");
    write_output("out", d / "done.csv", text("finished\n"));
    OutputSet set;
    set.reserve("out", d / "a.csv");
    set.write(d / "a.csv", text("half"));
    set.reserve("out", d / "b.png");
    ::raise(SIGTERM);
    return 31;  // not reached: the handler ends the process by the same signal
  });
  ASSERT_TRUE(WIFSIGNALED(ws)) << "status " << exit_status(ws);
  EXPECT_EQ(WTERMSIG(ws), SIGTERM);
  EXPECT_EQ(slurp(d / "done.csv"), "finished\n");  // a finished file stays
  EXPECT_FALSE(fs::exists(d / "a.csv.partial"));
  EXPECT_FALSE(fs::exists(d / "b.png.partial"));
  EXPECT_FALSE(fs::exists(d / "a.csv"));
  EXPECT_EQ(slurp(err), "\nbouncer: interrupted by SIGTERM; partial files removed; rerun the same command to resume\n");
}

TEST(Interrupt, ASignalIgnoredAtStartStaysIgnored) {
  TempDir d;
  const int ws = in_child([&] {
    ::signal(SIGHUP, SIG_IGN);  // nohup
    install_interrupt_cleanup();
    OutputSet set;
    set.reserve("out", d / "a.csv");
    ::raise(SIGHUP);
    return fs::exists(d / "a.csv.partial") ? 0 : 40;
  });
  EXPECT_EQ(exit_status(ws), 0);
}

// ---- standard output and own directories -----------------------------------------------------------

TEST(CheckStdout, AFailedStandardOutputIsAnOutputError) {
  auto with_stdout = [](const char* device) {
    return exit_status(in_child([device] {
      const int fd = ::open(device, O_WRONLY);
      if (fd < 0 || ::dup2(fd, 1) < 0) return 50;
      std::cout << "result line\n";
      try {
        check_stdout();
      } catch (const OutputError&) {
        return 1;
      }
      return 0;
    }));
  };
  EXPECT_EQ(with_stdout("/dev/full"), 1);
  EXPECT_EQ(with_stdout("/dev/null"), 0);
}

TEST(OwnDirectory, ExistingDirectoriesAreKeptAndOtherThingsRefused) {
  TempDir d;
  fs::create_directory(d / "p.tiles");
  put(d / "p.tiles/tile-0", "saved\n");
  make_own_directory("out", d / "p.tiles");
  EXPECT_EQ(slurp(d / "p.tiles/tile-0"), "saved\n");
  put(d / "file", "x");
  EXPECT_TRUE(contains(expect_input_error([&] { make_own_directory("out", d / "file"); }, "out"), "exists and is not a directory"));
  EXPECT_EQ(slurp(d / "file"), "x");
  // Its parent must exist: that is a failure to create, not a path to guess.
  EXPECT_FALSE(output_error([&] { make_own_directory("out", d / "missing/p.tiles"); }).empty());
  EXPECT_FALSE(fs::exists(d / "missing"));
}

}  // namespace
