// The deterministic grid runner: the same bytes whatever the thread count, shard split or
// interruption. The truth each run is compared with is a plain serial loop over the items.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "bouncer/run/grid.hpp"
#include "bouncer/base/cancel.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"

using namespace bouncer;
namespace fs = std::filesystem;

namespace {

ModelSpec constant_model(const char* a, const char* eps) {
  ModelSpec m;
  m.law = Law::constant;
  m.a = *Decimal::parse(a);
  m.eps = *Decimal::parse(eps);
  m.wall = parse_wall("wall", "triangle");
  validate(m);
  return m;
}

// Item i: the state after `steps` impact-map steps from a grid point, as exact text.
template <class T>
std::string orbit_end(const ImpactMap<T>& map, long i, long steps, long bits) {
  using Tr = ScalarTraits<T>;
  const T theta = Tr::from_int(2 * (i % 16) + 1, bits) / 32;  // cell centres in [0, 1)
  const T v = Tr::from_int(5 + i / 16, bits);
  State<T> s{theta, v};
  std::string kinds;
  try {
    for (long n = 0; n < steps; ++n) {
      const StepResult<T> r = map.step(s);
      s = r.next;
      kinds += r.kind == EventKind::sticking ? 's' : 'i';
    }
  } catch (const Undecided& u) {
    return std::string("undecided ") + u.what();
  }
  return Tr::to_string(s.theta) + "," + Tr::to_string(s.v) + "," + kinds.substr(kinds.size() > 8 ? kinds.size() - 8 : 0);
}

struct TempDir {
  fs::path path;
  TempDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("bouncer-test-grid-" + std::to_string(rd()) + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string sub(const std::string& name) const { return (path / name).string(); }
};

const ImpactMap<double>& double_map() {
  static const ImpactMap<double> m(make_model<double>(constant_model("24", "0.5"), 53));
  return m;
}

std::vector<std::string> serial(long items, const std::function<std::string(long)>& f) {
  std::vector<std::string> out;
  for (long i = 0; i < items; ++i) out.push_back(f(i));
  return out;
}

}  // namespace

TEST(Grid, ShardParsing) {
  const Shard s = parse_shard("shard", "2/5");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  for (const char* bad : {"5/5", "1/0", "-1/3", "a/b", "1", "1/", "/2", "1/2/3", " 1/2"})
    EXPECT_THROW(parse_shard("shard", bad), InputError) << bad;
}

TEST(Grid, TilesCoverTheItemsOnceAndShardsPartitionThem) {
  GridPlan plan{1001, 64};
  EXPECT_EQ(plan.tiles(), 16);
  long covered = 0;
  for (long t = 0; t < plan.tiles(); ++t) {
    covered += plan.end(t) - plan.begin(t);
    int owners = 0;
    for (long i = 0; i < 3; ++i) owners += GridPlan::in_shard(t, Shard{i, 3});
    EXPECT_EQ(owners, 1);
  }
  EXPECT_EQ(covered, 1001);
}

TEST(Grid, SameResultAtOneAndTwoThreadsAsASerialLoop) {
  const auto f = [](long i) { return orbit_end(double_map(), i, 300, 53); };
  GridPlan plan{160, 7};  // tiles of uneven length on purpose
  const auto truth = serial(plan.items, f);
  for (unsigned threads : {1u, 2u, 3u}) {
    GridOptions o;
    o.threads = threads;
    const GridResult r = run_grid(plan, f, o);
    ASSERT_TRUE(r.complete());
    EXPECT_EQ(r.items, truth) << threads << " threads";
  }
}

TEST(Grid, GroupedItemsEqualTheSerialLoop) {
  // The grouped form: groups never cross a tile and cover each item once, in order, with the
  // last group of a tile shorter; the texts are the serial loop's (here the orbits go four
  // side by side through the batched step, ImpactMap::step_n, as bench_grid's basin does).
  const auto f = [](long i) { return orbit_end(double_map(), i, 300, 53); };
  GridPlan plan{160, 7};
  const auto truth = serial(plan.items, f);
  for (long group : {1L, 3L, 4L, 7L, 50L})
    for (unsigned threads : {1u, 2u}) {
      GridOptions o;
      o.threads = threads;
      std::atomic<long> calls{0};
      const GridResult r = run_grid(plan, group, [&](long b, long e, std::string* out) {
        ++calls;
        EXPECT_LE(e - b, group);
        EXPECT_EQ(plan.begin(b / plan.tile_items), plan.begin((e - 1) / plan.tile_items)) << "a group crosses a tile";
        if (e - b == 4) {
          State<double> s[4];
          StepResult<double> res[4];
          Reason why[4];
          for (int k = 0; k < 4; ++k)
            s[k] = State<double>{static_cast<double>(2 * ((b + k) % 16) + 1) / 32, static_cast<double>(5 + (b + k) / 16)};
          for (long n = 0; n < 300; ++n) {
            ASSERT_EQ(double_map().step_n<kStepLanes>(s, res, why), 0u);
            for (int k = 0; k < 4; ++k) s[k] = res[k].next;
          }
          for (int k = 0; k < 4; ++k) {
            const std::string one = f(b + k);
            EXPECT_EQ(one.substr(0, one.rfind(',')),
                      ScalarTraits<double>::to_string(s[k].theta) + "," + ScalarTraits<double>::to_string(s[k].v));
          }
        }
        for (long i = b; i < e; ++i) out[i - b] = f(i);
      }, o);
      ASSERT_TRUE(r.complete());
      EXPECT_EQ(r.items, truth) << "group " << group << ", " << threads << " threads";
      long expected = 0;
      for (long t = 0; t < plan.tiles(); ++t) expected += (plan.end(t) - plan.begin(t) + group - 1) / group;
      EXPECT_EQ(calls.load(), expected);
    }
  EXPECT_THROW(run_grid(plan, 0, [](long, long, std::string*) {}, GridOptions{}), std::invalid_argument);
}

TEST(Grid, MpfrScanOnTwoThreadsEqualsOneThread) {
  // 200 bits: precision travels with each value, no process-wide default is involved.
  const ImpactMap<Mpfr> map(make_model<Mpfr>(constant_model("19", "0.9"), 200));
  const auto f = [&map](long i) { return orbit_end(map, i, 120, 200); };
  GridPlan plan{48, 5};
  GridOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const GridResult r1 = run_grid(plan, f, one);
  const GridResult r2 = run_grid(plan, f, two);
  ASSERT_TRUE(r1.complete() && r2.complete());
  EXPECT_EQ(r1.items, r2.items);
  EXPECT_EQ(r1.items, serial(plan.items, f));
  // The text really carries 200-bit numbers (more digits than a double holds).
  EXPECT_GT(r1.items[3].find(','), 40u) << r1.items[3];
}

TEST(Grid, ShardsMergedEqualTheWholeRun) {
  TempDir tmp;
  const auto f = [](long i) { return orbit_end(double_map(), i, 200, 53); };
  GridPlan plan{150, 8};
  const auto truth = serial(plan.items, f);
  const std::string dir = tmp.sub("job.tiles");
  for (long s = 0; s < 3; ++s) {
    GridOptions o;
    o.threads = 2;
    o.shard = Shard{s, 3};
    o.tile_dir = dir;
    o.job_key = "k1";
    const GridResult r = run_grid(plan, f, o);
    // A shard computes exactly its own tiles (plus what earlier shards saved).
    for (long t = 0; t < plan.tiles(); ++t)
      EXPECT_EQ(static_cast<bool>(r.have_tile[static_cast<size_t>(t)]), t % 3 <= s) << "shard " << s << " tile " << t;
  }
  GridOptions merge;
  merge.compute = false;
  merge.tile_dir = dir;
  merge.job_key = "k1";
  const GridResult all = run_grid(plan, [](long) -> std::string { throw std::logic_error("merge must not compute"); }, merge);
  ASSERT_TRUE(all.complete());
  EXPECT_EQ(all.tiles_loaded, plan.tiles());
  EXPECT_EQ(all.items, truth);
}

TEST(Grid, ShardsInSeparateDirectoriesImportIntoOne) {
  TempDir tmp;
  const auto f = [](long i) { return "item " + std::to_string(i * i); };
  GridPlan plan{40, 3};
  for (long s = 0; s < 2; ++s) {
    GridOptions o;
    o.shard = Shard{s, 2};
    o.tile_dir = tmp.sub("part" + std::to_string(s) + ".tiles");
    o.job_key = "k";
    run_grid(plan, f, o);
  }
  const std::string out = tmp.sub("out.tiles");
  fs::create_directories(out);
  EXPECT_EQ(import_tiles(tmp.sub("part0.tiles"), out, plan, "k") + import_tiles(tmp.sub("part1.tiles"), out, plan, "k"),
            plan.tiles());
  GridOptions merge;
  merge.compute = false;
  merge.tile_dir = out;
  merge.job_key = "k";
  const GridResult r = run_grid(plan, f, merge);
  ASSERT_TRUE(r.complete());
  EXPECT_EQ(r.items, serial(plan.items, f));
}

TEST(Grid, ResumeAfterDeletingTilesRecomputesOnlyThoseAndGivesTheSameBytes) {
  TempDir tmp;
  std::atomic<long> calls{0};
  const auto f = [&calls](long i) {
    ++calls;
    return orbit_end(double_map(), i, 150, 53);
  };
  GridPlan plan{100, 9};
  GridOptions o;
  o.threads = 2;
  o.tile_dir = tmp.sub("run.tiles");
  o.job_key = "resume";
  const GridResult first = run_grid(plan, f, o);
  ASSERT_TRUE(first.complete());
  EXPECT_EQ(calls.load(), plan.items);
  // An interrupted run: some tiles never written, one left half-written.
  long deleted_items = 0;
  for (long t : {0L, 4L, plan.tiles() - 1}) {
    fs::remove(tile_path(o.tile_dir, t));
    deleted_items += plan.end(t) - plan.begin(t);
  }
  {
    const std::string p = tile_path(o.tile_dir, 6);
    std::string text;
    std::ifstream in(p, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    in.close();
    std::ofstream(p, std::ios::binary | std::ios::trunc) << text.substr(0, text.size() / 2);
    deleted_items += plan.end(6) - plan.begin(6);
  }
  calls = 0;
  const GridResult second = run_grid(plan, f, o);
  ASSERT_TRUE(second.complete());
  EXPECT_EQ(calls.load(), deleted_items);
  EXPECT_EQ(second.tiles_computed, 4);
  EXPECT_EQ(second.items, first.items);
  EXPECT_EQ(second.items, serial(plan.items, [](long i) { return orbit_end(double_map(), i, 150, 53); }));
}

TEST(Grid, TilesOfAnotherJobAreNotUsed) {
  TempDir tmp;
  GridPlan plan{20, 4};
  GridOptions o;
  o.tile_dir = tmp.sub("t");
  o.job_key = "job-a";
  run_grid(plan, [](long i) { return "a" + std::to_string(i); }, o);
  o.job_key = "job-b";
  const GridResult r = run_grid(plan, [](long i) { return "b" + std::to_string(i); }, o);
  EXPECT_EQ(r.tiles_loaded, 0);
  EXPECT_EQ(r.items[7], "b7");
  std::vector<std::string> items;
  EXPECT_TRUE(read_tile(o.tile_dir, 0, plan, "job-b", items));
  EXPECT_FALSE(read_tile(o.tile_dir, 0, GridPlan{20, 5}, "job-b", items));  // other item range
}

// A tile written by another build, or changed after it was written, is not loaded: the
// run recomputes it and counts why (the outputs carry this build's provenance).
TEST(Grid, TilesOfAnotherBuildOrWithABadChecksumAreRecomputed) {
  TempDir tmp;
  GridPlan plan{12, 4};
  GridOptions o;
  o.tile_dir = tmp.sub("t");
  o.job_key = "job";
  fs::create_directories(o.tile_dir);
  write_tile(o.tile_dir, 0, plan, "job", {"x0", "x1", "x2", "x3"}, "another-build");
  write_tile(o.tile_dir, 1, plan, "job", {"y4", "y5", "y6", "y7"});
  write_tile(o.tile_dir, 2, plan, "job", {"z8", "z9", "z10", "z11"});
  std::vector<std::string> items;
  EXPECT_EQ(load_tile(o.tile_dir, 0, plan, "job", items), TileStatus::other_build);
  EXPECT_EQ(load_tile(o.tile_dir, 0, plan, "job", items, "another-build"), TileStatus::ok);
  EXPECT_EQ(load_tile(o.tile_dir, 1, plan, "job", items), TileStatus::ok);
  EXPECT_EQ(load_tile(o.tile_dir, 1, plan, "other-job", items), TileStatus::other_job);
  EXPECT_EQ(load_tile(o.tile_dir, 3, plan, "job", items), TileStatus::absent);
  {  // one byte of tile 1 changed ("y5" -> "y6"), its checksum left as it was
    std::fstream f(tile_path(o.tile_dir, 1), std::ios::in | std::ios::out | std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const size_t at = text.find("y5");
    ASSERT_NE(at, std::string::npos);
    f.seekp(static_cast<std::streamoff>(at + 1));
    f.put('6');
  }
  EXPECT_EQ(load_tile(o.tile_dir, 1, plan, "job", items), TileStatus::bad_checksum);
  {  // a tile cut short
    std::ofstream f(tile_path(o.tile_dir, 2), std::ios::binary | std::ios::trunc);
    f << "bouncer-tile 2\nkey job\n";
  }
  EXPECT_EQ(load_tile(o.tile_dir, 2, plan, "job", items), TileStatus::bad_checksum);
  const GridResult r = run_grid(plan, [](long i) { return "n" + std::to_string(i); }, o);
  EXPECT_EQ(r.tiles_loaded, 0);
  EXPECT_EQ(r.tiles_other_build, 1);
  EXPECT_EQ(r.tiles_bad_checksum, 2);
  EXPECT_EQ(r.tiles_computed, 3);
  for (long i = 0; i < 12; ++i) EXPECT_EQ(r.items[static_cast<size_t>(i)], "n" + std::to_string(i));
}

TEST(Grid, ItemTextsWithNewlinesAndEmptyTextsRoundTripThroughTiles) {
  TempDir tmp;
  GridPlan plan{10, 3};
  const auto f = [](long i) { return i % 3 == 0 ? std::string() : "line1\nitem " + std::to_string(i) + "\nend\n"; };
  GridOptions o;
  o.tile_dir = tmp.sub("t");
  o.job_key = "nl";
  run_grid(plan, f, o);
  o.compute = false;
  const GridResult r = run_grid(plan, f, o);
  ASSERT_TRUE(r.complete());
  EXPECT_EQ(r.items, serial(plan.items, f));
}

TEST(Grid, AnItemErrorStopsTheRunAndKeepsFinishedTiles) {
  TempDir tmp;
  GridPlan plan{30, 5};
  GridOptions o;
  o.threads = 1;
  o.tile_dir = tmp.sub("t");
  o.job_key = "err";
  EXPECT_THROW(run_grid(plan, [](long i) -> std::string {
                 if (i == 17) throw std::runtime_error("boom");
                 return std::to_string(i);
               }, o),
               std::runtime_error);
  std::vector<std::string> items;
  EXPECT_TRUE(read_tile(o.tile_dir, 0, plan, "err", items));
  EXPECT_FALSE(read_tile(o.tile_dir, 3, plan, "err", items));
  EXPECT_FALSE(fs::exists(tile_path(o.tile_dir, 3) + ".partial"));
}

TEST(Grid, ACancelledRunStopsOnEveryWorkerAndWithoutTheFlagNothingChanges) {
  // The caller's flag (base/cancel.hpp) reaches the workers: set while item 40 is computed,
  // the run throws Cancelled long before the 4000 items are done, on 1 and on 2 threads.
  for (unsigned threads : {1u, 2u}) {
    std::atomic<bool> cancel{false};
    std::atomic<long> computed{0};
    const auto f = [&](long i) {
      if (i == 40) cancel.store(true);
      computed.fetch_add(1);
      return std::to_string(i);
    };
    GridPlan plan{4000, 10};
    GridOptions o;
    o.threads = threads;
    const CancelScope scope(&cancel);
    EXPECT_THROW(run_grid(plan, f, o), Cancelled) << threads << " threads";
    EXPECT_LT(computed.load(), 100) << threads << " threads";
  }
  // No scope, or a clear flag: the whole run.
  std::atomic<bool> clear{false};
  const CancelScope scope(&clear);
  GridOptions o;
  o.threads = 2;
  const GridResult r = run_grid(GridPlan{400, 10}, [](long i) { return std::to_string(i); }, o);
  EXPECT_TRUE(r.complete());
}

TEST(Grid, JobFingerprintIsStableAndSensitive) {
  EXPECT_EQ(job_fingerprint("abc"), job_fingerprint("abc"));
  EXPECT_NE(job_fingerprint("abc"), job_fingerprint("abd"));
  EXPECT_EQ(job_fingerprint("").size(), 16u);
  EXPECT_EQ(job_fingerprint(""), "cbf29ce484222325");  // FNV-1a 64 offset basis
}
