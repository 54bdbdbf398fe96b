// Deterministic parallel grids: a list of independent work items (grid points, parameter
// values) split into tiles of consecutive items, computed by std::thread workers.
//
// Determinism: every item is computed on its own from its index and written into its own
// slot, so the result is the same bytes whatever the thread count, the order in which
// tiles finish, or how the grid was split into shards. A shard i/N owns the tiles t with
// t mod N == i (round robin, so costly regions are shared out).
//
// Resume: with a tile directory, each finished tile is saved there as one small file
// (written to NAME.partial and renamed), stamped with the job's key, the build that
// computed it (tile_build()) and a checksum of its content. A later run of the same job
// loads the finished tiles and computes only the missing ones, so an interrupted run
// resumes, and the tiles of several shards can be merged. A tile from another build, or
// whose checksum fails (damaged, or edited by hand), is recomputed and counted, so that
// outputs never carry the current build's provenance over numbers another build made.
// (The checksum, FNV-1a 64, detects accidents and edits; it is no defence against forgery.)
//
// MPFR: our Mpfr/Mpfi values carry their own precision (no process-wide default), and
// MPFR keeps its caches per thread, so items may use MPFR in any worker.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace bouncer {

struct Shard {
  long index = 0, count = 1;
  bool all() const { return count == 1; }
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
// "i/N" with 0 <= i < N, 1 <= N <= 1e6; throws InputError naming `field`.
Shard parse_shard(const std::string& field, const std::string& text);

struct GridPlan {
  long items = 0;
  long tile_items = 64;  // items per tile (the last tile may be shorter)
  long tiles() const { return items == 0 ? 0 : (items + tile_items - 1) / tile_items; }
  long begin(long tile) const { return tile * tile_items; }
  long end(long tile) const { return std::min(items, (tile + 1) * tile_items); }
  static bool in_shard(long tile, const Shard& s) { return tile % s.count == s.index; }
};

struct GridOptions {
  unsigned threads = 0;         // 0: all cores (std::thread::hardware_concurrency)
  Shard shard;                  // which tiles to compute
  std::string tile_dir;         // empty: keep tiles in memory only (no resume)
  std::string job_key;          // identifies the job; tiles with another key are refused
  bool compute = true;          // false: only load saved tiles (bouncer merge)
  bool progress = false;        // draw a progress bar on stderr
  std::string label;            // shown before the progress bar
};

struct GridResult {
  std::vector<std::string> items;  // one text per item ("" where no tile was available)
  std::vector<bool> have_tile;     // per tile: computed or loaded
  long tiles_loaded = 0, tiles_computed = 0;
  long tiles_other_build = 0, tiles_bad_checksum = 0;  // found saved but recomputed
  bool complete() const;           // every tile is available
  std::vector<long> missing() const;
};

// Runs the plan: loads saved tiles, computes the shard's missing ones in parallel with
// `item(index)` (which must depend on the index only), saves each finished tile.
// An exception thrown by `item` stops the workers and is rethrown (finished tiles stay
// saved); a worker thread that cannot be created stops them too (ResourceError, base/output.hpp).
// Threads = 1 runs in the calling thread. The tile directory must be a real directory
// (created if missing; a symbolic link is refused: InputError).
GridResult run_grid(const GridPlan& plan, const std::function<std::string(long)>& item, const GridOptions& opt);
// The same with items computed in groups: `items(begin, end, out)` fills out[0 .. end - begin)
// for the items [begin, end) of one tile, at most `group` of them at a time (fewer at a tile's
// end), for items that are cheaper computed together (orbits stepped side by side,
// ImpactMap::step_n). Each item must still depend on its index only, not on its group.
GridResult run_grid(const GridPlan& plan, long group, const std::function<void(long, long, std::string*)>& items,
                    const GridOptions& opt);

// Tile files: PREFIX.tiles/tile-NNNNNN. Exposed for merge and for tests. A tile larger than
// kMaxTileBytes, or anything but a regular file at a tile's name, is refused (InputError).
inline constexpr std::size_t kMaxTileBytes = std::size_t{256} << 20;
std::string tile_path(const std::string& dir, long tile);
// This build's identity in tiles: a fingerprint of version, commit, compiler and flags.
const std::string& tile_build();
enum class TileStatus { ok, absent, other_job, other_build, bad_checksum };
// Reads one tile into items_out when it is ok: present, of this job (key and item range),
// of `build`, and its checksum holds.
TileStatus load_tile(const std::string& dir, long tile, const GridPlan& plan, const std::string& key,
                     std::vector<std::string>& items_out, const std::string& build = tile_build());
inline bool read_tile(const std::string& dir, long tile, const GridPlan& plan, const std::string& key,
                      std::vector<std::string>& items_out) {
  return load_tile(dir, tile, plan, key, items_out) == TileStatus::ok;
}
void write_tile(const std::string& dir, long tile, const GridPlan& plan, const std::string& key,
                const std::vector<std::string>& items, const std::string& build = tile_build());
// Copies the valid tiles of `from` that `to` lacks; returns how many were copied.
long import_tiles(const std::string& from, const std::string& to, const GridPlan& plan, const std::string& key);

// A lock on a tile directory (DIR/lock, POSIX record locks: released by the kernel when
// the process ends, however it ends, so a crash leaves no stale lock). A whole run (no
// shard, a merge, rank 0 under mpirun) locks the whole file; shard I/N shares byte 0 with
// the other shards of the job and locks byte 1 + I alone, so the shards of a job array run
// together, while a second run of the same shard, or a whole run, is refused. Creates DIR.
// Throws InputError(field, ...) naming the process that holds the lock, and its command
// line when it runs on this machine.
class PrefixLock {
 public:
  PrefixLock(const std::string& field, const std::string& dir, const Shard& shard);
  ~PrefixLock();
  PrefixLock(const PrefixLock&) = delete;
  PrefixLock& operator=(const PrefixLock&) = delete;
  // Turns a shard's shared hold into a whole lock (needed to clear another job's tiles);
  // false when other processes hold parts of it.
  bool make_whole();

 private:
  int fd_ = -1;
};

// A stable 64-bit fingerprint of a job description (FNV-1a), as 16 hex digits.
std::string job_fingerprint(const std::string& text);

// The memory available to a new computation of this process, in bytes: the least of the
// machine's MemAvailable (/proc/meminfo), the address-space limit (ulimit -v) and the
// cgroup's memory.max less its current use (a container's limit); 0 when unknown.
double available_memory_bytes();

// The number of worker threads `requested` means (0: all cores; at least 1).
unsigned worker_threads(unsigned requested);

// A text progress bar on stderr, redrawn at most ~10 times a second; thread-safe.
class ProgressBar {
 public:
  ProgressBar(std::string label, long total, bool enabled);
  ~ProgressBar();
  void advance(long n);
  void finish();

 private:
  struct State;
  State* s_;
};

// True when stderr is a terminal (progress bars are drawn only then).
bool stderr_is_terminal();

}  // namespace bouncer
