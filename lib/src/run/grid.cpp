#include "bouncer/run/grid.hpp"
#include "bouncer/run/workers.hpp"
#include "bouncer/base/cancel.hpp"
#include "bouncer/base/input.hpp"
#include "bouncer/base/output.hpp"
#include "bouncer/base/build_info.hpp"
#include "bouncer/scalar/thread_caches.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>
#include <functional>
#include <system_error>
#include <thread>

#include "bouncer/model/spec.hpp"

namespace bouncer {

namespace fs = std::filesystem;

Shard parse_shard(const std::string& field, const std::string& text) {
  const auto slash = text.find('/');
  auto whole = [](const std::string& s, long& out) {
    if (s.empty() || s.size() > 7 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::stol(s);
    return true;
  };
  Shard s;
  if (slash == std::string::npos || !whole(text.substr(0, slash), s.index) || !whole(text.substr(slash + 1), s.count) ||
      s.count < 1 || s.count > 1000000 || s.index >= s.count)
    throw InputError(field, "must be I/N with 0 <= I < N <= 1000000 (got '" + text + "')");
  return s;
}

bool GridResult::complete() const {
  for (bool b : have_tile)
    if (!b) return false;
  return true;
}

std::vector<long> GridResult::missing() const {
  std::vector<long> out;
  for (size_t t = 0; t < have_tile.size(); ++t)
    if (!have_tile[t]) out.push_back(static_cast<long>(t));
  return out;
}

std::string job_fingerprint(const std::string& text) {
  std::uint64_t h = 14695981039346656037ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

double available_memory_bytes() {
  double have = 0;
  {
    std::ifstream f("/proc/meminfo");
    std::string key, unit;
    double kb = 0;
    while (f >> key >> kb >> unit)
      if (key == "MemAvailable:") {
        have = kb * 1024;
        break;
      }
  }
  auto lower = [&](double limit) {
    if (limit > 0 && (have <= 0 || limit < have)) have = limit;
  };
  // This process's address-space limit (ulimit -v): allocations beyond it fail.
  struct rlimit rl {};
  if (::getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) lower(static_cast<double>(rl.rlim_cur));
  // A container's memory limit (cgroup v2): memory.max less what the cgroup already uses.
  std::ifstream cg("/proc/self/cgroup");
  std::string line;
  while (std::getline(cg, line)) {
    if (line.rfind("0::", 0) != 0) continue;
    const std::string dir = "/sys/fs/cgroup" + line.substr(3);
    std::ifstream mx(dir + "/memory.max"), cur(dir + "/memory.current");
    std::string max_text;
    double used = 0;
    if (mx >> max_text && max_text != "max" && cur >> used) lower(std::strtod(max_text.c_str(), nullptr) - used);
  }
  return have;
}

void run_workers(unsigned count, const std::function<void()>& work) {
  if (count <= 1) {
    work();
    return;
  }
  std::vector<std::thread> pool;
  for (unsigned i = 0; i < count; ++i) {
    try {
      pool.emplace_back([&work] {
        const MpfrThreadCaches caches;  // freed when this worker ends
        work();
      });
    } catch (const std::system_error&) {
      break;  // the running workers take this one's share of the queue
    }
  }
  if (pool.empty()) work();
  for (std::thread& t : pool) t.join();
}

unsigned worker_threads(unsigned requested) {
  if (requested > 0) return requested;
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : n;
}

std::string tile_path(const std::string& dir, long tile) {
  char name[32];
  std::snprintf(name, sizeof name, "tile-%06ld", tile);
  return (fs::path(dir) / name).string();
}

const std::string& tile_build() {
  static const std::string id = [] {
    const BuildInfo& b = build_info();
    return job_fingerprint(b.version + "\n" + b.commit + "\n" + b.compiler + "\n" + b.flags + "\n" + b.build_type);
  }();
  return id;
}

namespace {

// Format 2: the header names the job, the build and the item range; the last line is
// "end CHECKSUM", the FNV-1a fingerprint of every byte before it.
std::string tile_header(const std::string& key) {
  std::ostringstream h;
  h << "bouncer-tile 2\nkey " << key << "\n";
  return h.str();
}

std::string tile_range(long tile, const GridPlan& plan) {
  return "tile " + std::to_string(tile) + " items " + std::to_string(plan.begin(tile)) + " " + std::to_string(plan.end(tile)) + "\n";
}

}  // namespace

void write_tile(const std::string& dir, long tile, const GridPlan& plan, const std::string& key,
                const std::vector<std::string>& items, const std::string& build) {
  std::string body = tile_header(key) + "build " + build + "\n" + tile_range(tile, plan);
  for (long i = plan.begin(tile); i < plan.end(tile); ++i) {
    const std::string& s = items[static_cast<size_t>(i - plan.begin(tile))];
    body += "item " + std::to_string(i) + " " + std::to_string(s.size()) + "\n";
    body += s;
    body += "\n";
  }
  body += "end " + job_fingerprint(body) + "\n";
  write_output("out", tile_path(dir, tile), [&](std::ostream& f) { f << body; });
}

TileStatus load_tile(const std::string& dir, long tile, const GridPlan& plan, const std::string& key,
                     std::vector<std::string>& items_out, const std::string& build) {
  // A tile is a regular file bouncer wrote: anything else at its name (a directory, a FIFO
  // whose reader would wait forever, a device) is refused, never read or recomputed over.
  const std::string path = tile_path(dir, tile);
  const std::optional<std::string> file = read_input_file_if_present("out", path, kMaxTileBytes);
  if (!file) return TileStatus::absent;
  const std::string& text = *file;
  // The checksum first: a damaged or edited tile is reported as such, whatever it claims.
  const size_t end_at = text.rfind("end ");
  if (end_at == std::string::npos || (end_at > 0 && text[end_at - 1] != '\n') ||
      text.compare(end_at, std::string::npos, "end " + job_fingerprint(text.substr(0, end_at)) + "\n") != 0)
    return TileStatus::bad_checksum;
  const std::string header = tile_header(key);
  if (text.compare(0, header.size(), header) != 0) return TileStatus::other_job;
  size_t pos = header.size();
  const std::string build_line = "build " + build + "\n";
  if (text.compare(pos, build_line.size(), build_line) != 0) return TileStatus::other_build;
  pos += build_line.size();
  const std::string range = tile_range(tile, plan);
  if (text.compare(pos, range.size(), range) != 0) return TileStatus::other_job;
  pos += range.size();
  std::vector<std::string> items;
  for (long i = plan.begin(tile); i < plan.end(tile); ++i) {
    const std::string tag = "item " + std::to_string(i) + " ";
    if (text.compare(pos, tag.size(), tag) != 0) return TileStatus::bad_checksum;
    pos += tag.size();
    const size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) return TileStatus::bad_checksum;
    const std::string len_text = text.substr(pos, nl - pos);
    if (len_text.empty() || len_text.size() > 12 || len_text.find_first_not_of("0123456789") != std::string::npos)
      return TileStatus::bad_checksum;
    const size_t len = std::stoull(len_text);
    pos = nl + 1;
    if (pos + len + 1 > text.size() || text[pos + len] != '\n') return TileStatus::bad_checksum;
    items.push_back(text.substr(pos, len));
    pos += len + 1;
  }
  if (pos != end_at) return TileStatus::bad_checksum;
  items_out = std::move(items);
  return TileStatus::ok;
}

long import_tiles(const std::string& from, const std::string& to, const GridPlan& plan, const std::string& key) {
  long copied = 0;
  std::vector<std::string> items;
  for (long t = 0; t < plan.tiles(); ++t) {
    if (read_tile(to, t, plan, key, items)) continue;
    if (!read_tile(from, t, plan, key, items)) continue;
    write_tile(to, t, plan, key, items);
    ++copied;
  }
  return copied;
}

namespace {

// Sets a lock of `type` on [start, start + len) (len 0: to the end of the file): an open
// file description lock (F_OFD_SETLK), so that it excludes another thread of this process
// (two commands run by one Python interpreter) as it excludes another process, and closing
// some other descriptor of the file never drops it. False when another holds a conflicting lock.
bool ofd_lock(int fd, short type, off_t start, off_t len) {
  struct flock fl {};
  fl.l_type = type;
  fl.l_whence = SEEK_SET;
  fl.l_start = start;
  fl.l_len = len;
  return fcntl(fd, F_OFD_SETLK, &fl) == 0;
}

// Who holds the lock: the holder of a whole lock writes its pid into the lock file (an OFD
// lock does not say whose it is). A pid of a process that is gone, or none: "another process".
std::string holder_text(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  long pid = 0;
  if (n > 0) pid = std::strtol(buf, nullptr, 10);
  if (pid > 0 && pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) pid = 0;  // gone
  return pid > 0 ? process_text(pid) : "another process";
}

void record_holder(int fd) {
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) == 0) {
    const ssize_t ignored = ::pwrite(fd, pid.data(), pid.size(), 0);  // only for messages
    (void)ignored;
  }
}

}  // namespace

PrefixLock::PrefixLock(const std::string& field, const std::string& dir, const Shard& shard) {
  // The tile directory is bouncer's own: a symbolic link there (to any directory whose files
  // a later clean-up would delete) is refused, never followed.
  make_own_directory(field, dir);
  const std::string path = (fs::path(dir) / "lock").string();
  // The lock file may be removed by the holder as it finishes (with the tile directory):
  // a lock taken on a file that is no longer at `path` is retried on the new file.
  for (int attempt = 0; attempt < 20; ++attempt) {
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY, 0644);
    if (fd_ < 0) {
      if (errno == ENOENT) {
        make_own_directory(field, dir);
        continue;
      }
      if (errno == ELOOP) throw InputError(field, "'" + path + "' is a symbolic link: remove it");
      throw OutputError("cannot open lock file '" + path + "': " + std::strerror(errno));
    }
    struct stat held {};
    if (fstat(fd_, &held) != 0 || !S_ISREG(held.st_mode)) {
      ::close(fd_);
      fd_ = -1;
      throw InputError(field, "'" + path + "' is not a regular file: remove it");
    }
    bool ok = false;
    if (shard.all()) {
      ok = ofd_lock(fd_, F_WRLCK, 0, 0);
    } else {
      ok = ofd_lock(fd_, F_RDLCK, 0, 1) && ofd_lock(fd_, F_WRLCK, 1 + shard.index, 1);
    }
    if (!ok) {
      const std::string holder = holder_text(fd_);
      ::close(fd_);
      fd_ = -1;
      throw InputError(field, "'" + dir + "' is in use by " + holder + (shard.all() ? "" : " for shard " + shard.text()) +
                                  "; wait for it to finish, or choose another --out");
    }
    struct stat now {};
    if (::lstat(path.c_str(), &now) == 0 && held.st_dev == now.st_dev && held.st_ino == now.st_ino) {
      if (shard.all()) record_holder(fd_);
      return;
    }
    ::close(fd_);
    fd_ = -1;
  }
  throw OutputError("cannot lock '" + path + "': it keeps being replaced");
}

PrefixLock::~PrefixLock() {
  if (fd_ >= 0) ::close(fd_);
}

bool PrefixLock::make_whole() {
  if (fd_ < 0 || !ofd_lock(fd_, F_WRLCK, 0, 0)) return false;
  record_holder(fd_);
  return true;
}

bool stderr_is_terminal() { return isatty(2) != 0; }

struct ProgressBar::State {
  std::string label;
  long total = 0, done = 0;
  bool enabled = false, drawn = false;
  std::chrono::steady_clock::time_point start, last;
  std::mutex m;
  void draw(bool final) {
    const auto now = std::chrono::steady_clock::now();
    if (!final && now - last < std::chrono::milliseconds(100)) return;
    last = now;
    const int width = 30;
    const double frac = total > 0 ? static_cast<double>(done) / total : 1.0;
    const int fill = static_cast<int>(frac * width);
    const double secs = std::chrono::duration<double>(now - start).count();
    std::string bar(static_cast<size_t>(fill), '#');
    bar.resize(width, '.');
    char eta[48] = "";
    if (done > 0 && done < total) std::snprintf(eta, sizeof eta, " eta %.0fs", secs / done * (total - done));
    std::fprintf(stderr, "\r%s [%s] %3.0f%% %ld/%ld %.1fs%s   ", label.c_str(), bar.c_str(), 100 * frac, done, total, secs, eta);
    if (final) std::fputc('\n', stderr);
    std::fflush(stderr);
    drawn = true;
  }
};

ProgressBar::ProgressBar(std::string label, long total, bool enabled) : s_(new State) {
  s_->label = std::move(label);
  s_->total = total;
  s_->enabled = enabled;
  s_->start = std::chrono::steady_clock::now();
  s_->last = s_->start - std::chrono::seconds(1);
}

ProgressBar::~ProgressBar() {
  finish();
  delete s_;
}

void ProgressBar::advance(long n) {
  std::lock_guard<std::mutex> lock(s_->m);
  s_->done += n;
  if (s_->enabled) s_->draw(false);
}

void ProgressBar::finish() {
  std::lock_guard<std::mutex> lock(s_->m);
  if (s_->enabled) {
    if (s_->total > 0) s_->draw(true);
    s_->enabled = false;
  }
}

GridResult run_grid(const GridPlan& plan, const std::function<std::string(long)>& item, const GridOptions& opt) {
  return run_grid(plan, 1, [&item](long i, long, std::string* out) { *out = item(i); }, opt);
}

GridResult run_grid(const GridPlan& plan, long group, const std::function<void(long, long, std::string*)>& items,
                    const GridOptions& opt) {
  if (plan.tile_items < 1) throw std::invalid_argument("run_grid: tile_items must be >= 1");
  if (group < 1) throw std::invalid_argument("run_grid: group must be >= 1");
  GridResult r;
  const long ntiles = plan.tiles();
  r.items.assign(static_cast<size_t>(plan.items), std::string());
  r.have_tile.assign(static_cast<size_t>(ntiles), false);
  const bool saving = !opt.tile_dir.empty();
  if (saving) make_own_directory("out", opt.tile_dir);

  // Saved tiles first (any shard's: a merge loads them all).
  std::vector<long> todo;
  std::vector<std::string> buf;
  for (long t = 0; t < ntiles; ++t) {
    const TileStatus st = saving ? load_tile(opt.tile_dir, t, plan, opt.job_key, buf) : TileStatus::absent;
    if (st == TileStatus::other_build) ++r.tiles_other_build;
    if (st == TileStatus::bad_checksum) ++r.tiles_bad_checksum;
    if (st == TileStatus::ok) {
      for (long i = plan.begin(t); i < plan.end(t); ++i) r.items[static_cast<size_t>(i)] = std::move(buf[static_cast<size_t>(i - plan.begin(t))]);
      r.have_tile[static_cast<size_t>(t)] = true;
      ++r.tiles_loaded;
    } else if (opt.compute && GridPlan::in_shard(t, opt.shard)) {
      todo.push_back(t);
    }
  }
  if (todo.empty()) return r;

  long todo_items = 0;
  for (long t : todo) todo_items += plan.end(t) - plan.begin(t);
  ProgressBar progress(opt.label.empty() ? "bouncer" : opt.label, todo_items, opt.progress);
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::atomic<long> computed{0};

  // vector<bool> packs bits, so concurrent writes to neighbouring tiles would race:
  // record finished tiles in a byte vector and copy afterwards.
  std::vector<unsigned char> done(static_cast<size_t>(ntiles), 0);
  const std::atomic<bool>* cancel = current_cancel_flag();  // the caller's, for every worker
  // Workers start computing only once every thread exists: a thread that cannot be created
  // then stops a run in which no tile was computed, so nothing is left to resume or clean.
  std::atomic<bool> go{false};
  auto safe_worker = [&] {
    go.wait(false);
    const MpfrThreadCaches caches;  // freed when this worker ends
    const CancelScope scope(cancel);
    for (;;) {
      if (failed.load()) return;
      const size_t k = next.fetch_add(1);
      if (k >= todo.size()) return;
      const long t = todo[k];
      try {
        std::vector<std::string> tile(static_cast<size_t>(plan.end(t) - plan.begin(t)));
        for (long i = plan.begin(t); i < plan.end(t); i += group) {
          if (failed.load()) return;
          throw_if_cancelled();
          const long e = std::min(plan.end(t), i + group);
          items(i, e, &tile[static_cast<size_t>(i - plan.begin(t))]);
          progress.advance(e - i);
        }
        if (saving) write_tile(opt.tile_dir, t, plan, opt.job_key, tile);
        for (long i = plan.begin(t); i < plan.end(t); ++i)
          r.items[static_cast<size_t>(i)] = std::move(tile[static_cast<size_t>(i - plan.begin(t))]);
        done[static_cast<size_t>(t)] = 1;
        computed.fetch_add(1);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed.store(true);
        return;
      }
    }
  };
  const unsigned nthreads = std::min<unsigned>(worker_threads(opt.threads), static_cast<unsigned>(todo.size()));
  if (nthreads <= 1) {
    go.store(true);
    safe_worker();
  } else {
    // A thread that cannot be created (a process or memory limit) stops the run with a
    // message before any tile is computed: the threads already created see `failed` when
    // released, and are joined (a std::thread destroyed while running would abort the process).
    std::vector<std::thread> pool;
    std::string no_thread;
    for (unsigned i = 0; i < nthreads; ++i) {
      try {
        pool.emplace_back(safe_worker);
      } catch (const std::system_error& e) {
        no_thread = "cannot start worker thread " + std::to_string(i + 1) + " of " + std::to_string(nthreads) + " (" +
                    e.code().message() + "): give fewer --threads";
        failed.store(true);
        break;
      }
    }
    go.store(true);
    go.notify_all();
    for (auto& th : pool) th.join();
    if (!no_thread.empty()) {
      progress.finish();
      throw ResourceError(no_thread);
    }
  }
  progress.finish();
  for (long t : todo)
    if (done[static_cast<size_t>(t)]) r.have_tile[static_cast<size_t>(t)] = true;
  r.tiles_computed = computed.load();
  if (error) std::rethrow_exception(error);
  return r;
}

}  // namespace bouncer
