// Output files (base/output.hpp).
#include "bouncer/base/output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <ctime>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <set>
#include <streambuf>
#include <vector>

#include "bouncer/base/input.hpp"
#include "bouncer/base/error.hpp"

namespace bouncer {

namespace fs = std::filesystem;

namespace {

bool under_proc_or_dev(const std::string& path) { return path.rfind("/dev/", 0) == 0 || path.rfind("/proc/", 0) == 0; }

// An ostream buffer over a file descriptor: write(2) in 64 KiB blocks, retried on EINTR and
// short writes; the first error is kept (errno) and makes every later write fail, so the
// stream's badbit is set and the caller reports it.
class FdBuf : public std::streambuf {
 public:
  explicit FdBuf(int fd) : fd_(fd), buf_(1 << 16) { setp(buf_.data(), buf_.data() + buf_.size()); }
  ~FdBuf() override = default;
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain() ? 0 : -1; }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n >= static_cast<std::streamsize>(buf_.size())) {  // large blocks go straight out
      if (!drain() || !put(s, static_cast<size_t>(n))) return 0;
      return n;
    }
    return std::streambuf::xsputn(s, n);
  }

 private:
  bool put(const char* p, size_t n) {
    if (error_) return false;
    while (n > 0) {
      const ssize_t w = ::write(fd_, p, n);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        error_ = w < 0 ? errno : EIO;
        return false;
      }
      p += w;
      n -= static_cast<size_t>(w);
    }
    return true;
  }
  bool drain() {
    const bool ok = put(pbase(), static_cast<size_t>(pptr() - pbase()));
    setp(buf_.data(), buf_.data() + buf_.size());
    return ok;
  }
  int fd_;
  std::vector<char> buf_;
  int error_ = 0;
};

// Writes `body` to fd; throws OutputError naming `name` on any failure.
void write_fd(int fd, const std::string& name, const std::function<void(std::ostream&)>& body) {
  FdBuf buf(fd);
  std::ostream s(&buf);
  body(s);
  s.flush();
  if (!s || buf.error())
    throw OutputError("writing '" + name + "' failed" + (buf.error() ? std::string(": ") + std::strerror(buf.error()) : std::string()));
}

// The lock of a staging file: an open file description lock (F_OFD_SETLK) on its bytes
// [0, 2^62), which excludes other processes and other threads of this process alike; false
// when another holds it. An OFD lock does not say who holds it (F_OFD_GETLK and /proc/locks
// give pid -1), so the holder also sets a classic record lock on the byte 2^62, outside that
// range, as a beacon: F_GETLK on it names the holder's pid for the message of a refused run.
// (A classic lock is dropped when its process closes any descriptor of the file; the beacon
// only ever serves messages, never exclusion.)
constexpr off_t kBeacon = off_t{1} << 62;
bool lock_file(int fd) {
  struct flock fl {};
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  fl.l_start = 0;
  fl.l_len = kBeacon;
  if (::fcntl(fd, F_OFD_SETLK, &fl) != 0) return false;
  struct flock beacon {};
  beacon.l_type = F_WRLCK;
  beacon.l_whence = SEEK_SET;
  beacon.l_start = kBeacon;
  beacon.l_len = 1;
  ::fcntl(fd, F_SETLK, &beacon);  // best effort: messages only
  return true;
}

long lock_holder(int fd) {
  struct flock probe {};
  probe.l_type = F_WRLCK;
  probe.l_whence = SEEK_SET;
  probe.l_start = kBeacon;
  probe.l_len = 1;
  if (::fcntl(fd, F_GETLK, &probe) == 0 && probe.l_type != F_UNLCK) return probe.l_pid;
  return 0;
}

bool same_file(int fd, const std::string& path) {
  struct stat a {}, b {};
  return ::fstat(fd, &a) == 0 && ::lstat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

// The staging files this process holds (OutputSets of every thread): a classic lock never
// conflicts with its own process, so the beacon cannot name this process as the holder.
std::mutex held_mutex;
std::set<std::string> held_staging;
void hold(const std::string& staging, bool on) {
  const std::lock_guard<std::mutex> lock(held_mutex);
  if (on) held_staging.insert(staging);
  else held_staging.erase(staging);
}
bool held_here(const std::string& staging) {
  const std::lock_guard<std::mutex> lock(held_mutex);
  return held_staging.count(staging) != 0;
}

const char* special_kind(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISSOCK(m)) return "a socket";
  if (S_ISBLK(m)) return "a block device";
  return "a special file";
}

// Set by the interrupt handler first: no staging file is created after it.
std::atomic<bool> interrupted{false};

}  // namespace

OutputTarget output_target(const std::string& field, const std::string& path) {
  if (path.empty()) throw InputError(field, "is empty (give a file path)");
  if (path.back() == '/') throw InputError(field, "'" + path + "' ends in '/': give a file path, not a directory");
  check_path_name(field, path, std::strlen(".partial"));
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) {  // a new file: its folder must exist (a missing one is a typo, not a full disk)
      const fs::path parent = fs::path(path).parent_path();
      std::error_code ec;
      if (!parent.empty() && !fs::is_directory(parent, ec))
        throw InputError(field, "folder '" + parent.string() + "' does not exist (for '" + path + "')");
      return {OutputTarget::Kind::file, path};
    }
    throw InputError(field, "cannot use '" + path + "': " + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) return {OutputTarget::Kind::file, path};
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return {OutputTarget::Kind::stream, path};
  if (S_ISLNK(st.st_mode)) {
    struct stat to {};
    if (::stat(path.c_str(), &to) != 0)
      throw InputError(field, "'" + path + "' is a symbolic link to nothing that can be written (" + std::strerror(errno) + ")");
    if (S_ISCHR(to.st_mode) || S_ISFIFO(to.st_mode)) return {OutputTarget::Kind::stream, path};
    if (S_ISREG(to.st_mode) && under_proc_or_dev(path)) return {OutputTarget::Kind::stream, path};
    if (S_ISREG(to.st_mode))
      throw InputError(field, "'" + path + "' is a symbolic link: bouncer never writes a regular file through a link "
                              "(one planted in an output folder could point anywhere); remove the link or give the "
                              "file's own path");
    throw InputError(field, "'" + path + "' is a symbolic link to " + special_kind(to.st_mode) +
                                ": give a regular file (or a character device or pipe to write through)");
  }
  throw InputError(field, "'" + path + "' is " + special_kind(st.st_mode) +
                              ": give a regular file (or a character device or pipe to write through)");
}

// ---------------------------------------------------------------- OutputSet

struct OutputSet::Impl {
  struct Entry {
    std::string path, staging;  // staging empty for a stream
    bool stream = false;
    int fd = -1;                // the staging file, locked
    bool written = false, committed = false;
    std::unique_ptr<PartialFile> registered;
  };
  std::vector<Entry> entries;

  Entry* find(const std::string& path) {
    for (Entry& e : entries)
      if (e.path == path) return &e;
    return nullptr;
  }
  void drop(Entry& e) {
    if (e.fd >= 0) {
      if (!e.committed && same_file(e.fd, e.staging)) ::unlink(e.staging.c_str());
      ::close(e.fd);
      e.fd = -1;
      hold(e.staging, false);
    }
    e.registered.reset();
  }
};

OutputSet::OutputSet() : impl_(std::make_unique<Impl>()) {}

OutputSet::~OutputSet() { discard(); }

void OutputSet::discard() {
  for (Impl::Entry& e : impl_->entries) impl_->drop(e);
}

bool OutputSet::reserved(const std::string& path) const {
  return std::any_of(impl_->entries.begin(), impl_->entries.end(), [&](const Impl::Entry& e) { return e.path == path; });
}

void OutputSet::reserve(const std::string& field, const std::string& path) {
  if (reserved(path)) return;
  const OutputTarget target = output_target(field, path);
  Impl::Entry e;
  e.path = path;
  if (target.kind == OutputTarget::Kind::stream) {
    e.stream = true;
    impl_->entries.push_back(std::move(e));
    return;
  }
  e.staging = path + ".partial";
  for (int attempt = 0;; ++attempt) {
    if (attempt == 20) throw OutputError("cannot create '" + e.staging + "': it keeps being replaced");
    if (interrupted.load()) throw OutputError("interrupted: '" + e.staging + "' not created");
    int fd = ::open(e.staging.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) {
      // Created here: registered for the interrupt cleanup at once (an interrupt between the
      // creation and a later registration left the file behind: cli.grid_edges saw it once
      // in a tiled run, whose worker threads create staging files all the time).
      e.registered = std::make_unique<PartialFile>(e.staging);
      // Locked, and still the file at that name (a racing run may have reclaimed it between
      // the two calls): then it is ours.
      if (lock_file(fd) && same_file(fd, e.staging)) {
        e.fd = fd;
        break;
      }
      e.registered.reset();  // no longer ours to remove
      ::close(fd);
      continue;
    }
    if (errno == EINTR) continue;
    if (errno != EEXIST) throw OutputError("cannot create '" + e.staging + "': " + std::strerror(errno));
    // Something is at the staging name already.
    struct stat st {};
    if (::lstat(e.staging.c_str(), &st) != 0) continue;  // gone meanwhile: try again
    if (S_ISDIR(st.st_mode))
      throw InputError(field, "'" + e.staging + "' (where bouncer stages '" + path + "') is a directory: remove it");
    if (!S_ISREG(st.st_mode)) {  // a planted link, FIFO, device or socket: remove the name, follow nothing
      if (::unlink(e.staging.c_str()) != 0 && errno != ENOENT)
        throw OutputError("cannot remove '" + e.staging + "': " + std::strerror(errno));
      continue;
    }
    fd = ::open(e.staging.c_str(), O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
      if (errno == ENOENT || errno == ELOOP || errno == EINTR) continue;
      throw OutputError("cannot open '" + e.staging + "': " + std::strerror(errno));
    }
    if (!lock_file(fd)) {
      const long pid = held_here(e.staging) ? static_cast<long>(::getpid()) : lock_holder(fd);
      ::close(fd);
      throw InputError(field, "'" + path + "' is in use by " + process_text(pid) +
                                  ", which is writing it (its staging file '" + e.staging +
                                  "' is locked): wait for it to finish, or choose another path");
    }
    // Unlocked: left by a run that was killed. Reclaimed (removed, then created afresh).
    if (same_file(fd, e.staging)) ::unlink(e.staging.c_str());
    ::close(fd);
  }
  hold(e.staging, true);
  impl_->entries.push_back(std::move(e));
}

void OutputSet::write(const std::string& path, const std::function<void(std::ostream&)>& body) {
  Impl::Entry* e = impl_->find(path);
  if (!e) {
    reserve("out", path);
    e = impl_->find(path);
  }
  if (e->committed) throw std::logic_error("OutputSet::write: '" + path + "' was already committed");
  if (e->stream) {
    int fd;
    do fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    while (fd < 0 && errno == EINTR);
    if (fd < 0) throw OutputError("cannot open '" + path + "' for writing: " + std::strerror(errno));
    try {
      write_fd(fd, path, body);
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (::close(fd) != 0 && errno != EINTR) throw OutputError("closing '" + path + "' failed: " + std::strerror(errno));
    e->written = true;
    return;
  }
  try {
    if (e->written && (::ftruncate(e->fd, 0) != 0 || ::lseek(e->fd, 0, SEEK_SET) != 0))
      throw OutputError("cannot rewrite '" + e->staging + "': " + std::strerror(errno));
    write_fd(e->fd, path, body);
  } catch (...) {
    discard();
    throw;
  }
  e->written = true;
}

int OutputSet::descriptor(const std::string& path) {
  Impl::Entry* e = impl_->find(path);
  if (!e) throw std::logic_error("OutputSet::descriptor: '" + path + "' was not reserved");
  if (e->stream) return -1;
  e->written = true;
  return e->fd;
}

void OutputSet::commit() {
  try {
    // Every file must be written before any is renamed into place: a set is all or none.
    for (const Impl::Entry& e : impl_->entries)
      if (!e.stream && !e.committed && !e.written)
        throw std::logic_error("OutputSet::commit: '" + e.path + "' was reserved but never written");
    for (Impl::Entry& e : impl_->entries) {
      if (e.stream || e.committed) continue;
      // close() reports errors of deferred writes (NFS); a duplicate keeps the lock until
      // the file is in place.
      const int keep = ::dup(e.fd);
      if (keep < 0) throw OutputError("cannot finish '" + e.path + "': " + std::strerror(errno));
      const int closed = ::close(e.fd);
      e.fd = keep;
      if (closed != 0 && errno != EINTR) throw OutputError("closing '" + e.path + "' failed: " + std::strerror(errno));
      if (!same_file(e.fd, e.staging)) throw OutputError("'" + e.staging + "' was replaced while bouncer wrote it");
      if (::rename(e.staging.c_str(), e.path.c_str()) != 0)
        throw OutputError("cannot rename '" + e.staging + "' to '" + e.path + "': " + std::strerror(errno));
      e.committed = true;
      ::close(e.fd);
      e.fd = -1;
      hold(e.staging, false);
      e.registered.reset();
    }
  } catch (...) {
    discard();
    throw;
  }
}

std::string process_text(long pid) {
  if (pid <= 0) return "another bouncer run";
  if (pid == ::getpid()) return "another command of this process (pid " + std::to_string(pid) + ")";
  std::string text = "process " + std::to_string(pid);
  const int fd = ::open(("/proc/" + std::to_string(pid) + "/cmdline").c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return text;
  char buf[512];
  const ssize_t n = ::read(fd, buf, sizeof buf);
  ::close(fd);
  std::string cmd(buf, n > 0 ? static_cast<size_t>(n) : 0);
  for (char& c : cmd)
    if (c == '\0') c = ' ';
  while (!cmd.empty() && cmd.back() == ' ') cmd.pop_back();
  if (cmd.size() > 200) cmd = cmd.substr(0, 200) + "...";
  if (!cmd.empty()) text += " (" + cmd + ")";
  return text;
}

void write_output(const std::string& field, const std::string& path, const std::function<void(std::ostream&)>& body) {
  OutputSet set;
  set.reserve(field, path);
  set.write(path, body);
  set.commit();
}

void make_own_directory(const std::string& field, const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return;
    if (S_ISLNK(st.st_mode))
      throw InputError(field, "'" + path + "' is a symbolic link: bouncer keeps its files only in a directory it made "
                              "(a link could point at any directory); remove the link");
    throw InputError(field, "'" + path + "' exists and is not a directory");
  }
  if (errno != ENOENT) throw InputError(field, "cannot use '" + path + "': " + std::strerror(errno));
  if (::mkdir(path.c_str(), 0777) != 0 && errno != EEXIST)
    throw OutputError("cannot create '" + path + "': " + std::strerror(errno));
  if (::lstat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw InputError(field, "'" + path + "' is not a directory");
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

void remove_registered() {
  for (int i = 0; i < kSlots; ++i)
    if (slot_state[i].load() == 2) ::unlink(slot_path[i]);
}

void on_interrupt(int sig) {
  interrupted.store(true);
  remove_registered();
  // Another thread may have created a staging file just before the flag and register it just
  // after the scan: wait a moment and remove again (nanosleep is async-signal-safe).
  struct timespec pause {0, 50 * 1000 * 1000};
  ::nanosleep(&pause, nullptr);
  remove_registered();
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
  // A closed pipe is a failed write (EPIPE, exit status 1, staging files removed), not a kill.
  std::signal(SIGPIPE, SIG_IGN);
}

void check_stdout() {
  std::cout.flush();
  if (!std::cout) throw OutputError("writing to standard output failed");
  if (std::fflush(stdout) != 0) throw OutputError(std::string("writing to standard output failed: ") + std::strerror(errno));
}

}  // namespace bouncer
