// bench_grid: throughput of the deterministic grid runner on the paper's workloads.
//   1. basin grid, double: every point of an N x N grid (a = 19, eps = 0.9, theta in [0, 1),
//      v in [4, 40]) iterated S impact-map steps (exactly S steps per point), at 1 and 2
//      threads: steps per second and the speed-up (target >= 1.9x on 2 idle cores); then the
//      same with kStepLanes points side by side (ImpactMap::step_n, the batched step), its
//      ns per orbit-step and its end states compared with the one-by-one run's;
//   2. the same grid classified as `bouncer basin` does (classify_many, kStepLanes points side
//      by side; S - 500 transient + 500 examined steps), points per second;
//   3. a bifurcation diagram at paper resolution (1000 values of a x (5000 + 500) steps);
//   4. the basin iteration in MPFR at 128 bits on a smaller grid, extrapolated to N x N;
//   5. an exponent curve (`bouncer lyapunov --vary a`): K values of a in [20, 30] of the
//      velocity-dependent model (c = 1000), each 5000 transient + 20000 tangent steps and
//      the classification where the window ended, on 2 threads;
//   6. a continuation with a located border collision (`bouncer continue`): the stable
//      period-7 branch at c = 1000 over a in [27, 29], in double and at 128 bits.
// Peak memory (max RSS) is printed after each phase: it grows with the grid (one short
// text per point), never with the number of steps. Results at 1 and 2 threads are compared
// byte for byte. Timings are printed, never checked (not a test).
//   bench_grid [--size N] [--steps S] [--mpfr-size M] [--bits B] [--samples K] [--quick] [--curve-only]
//              [--continue-only] [--json FILE]
//   bench_grid --columns    (the table's columns as JSON, nothing run; bench_record.hpp)
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>

#include "bench_record.hpp"
#include "bouncer/analysis/classify.hpp"
#include "bouncer/analysis/continuation.hpp"
#include "bouncer/run/grid.hpp"
#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/model/impact_map.hpp"

using namespace bouncer;

namespace {

ModelSpec basin_model() {
  ModelSpec m;
  m.law = Law::constant;
  m.a = *Decimal::parse("19");
  m.eps = *Decimal::parse("0.9");
  m.wall = parse_wall("wall", "triangle");
  validate(m);
  return m;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

long peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;
}

template <class T>
State<T> grid_point(long i, long n, long bits) {
  using Tr = ScalarTraits<T>;
  const T theta = Tr::from_int(2 * (i % n) + 1, bits) / (2 * n);
  const T v = Tr::from_int(4, bits) + Tr::from_int(36 * (2 * (i / n) + 1), bits) / (2 * n);
  return {theta, v};
}

// Exactly `steps` steps from grid point i; the end state as text.
template <class T>
std::string iterate(const ImpactMap<T>& map, long i, long n, long steps, long bits) {
  using Tr = ScalarTraits<T>;
  State<T> s = grid_point<T>(i, n, bits);
  try {
    for (long k = 0; k < steps; ++k) s = map.step(s).next;
  } catch (const Undecided& u) {
    return u.what();
  }
  return Tr::to_string(s.theta) + "," + Tr::to_string(s.v);
}

// The same for the grid points [begin, end), kStepLanes of them side by side in one call
// of the batched step (ImpactMap::step_n); a point whose step is undecided goes on alone.
void iterate_side_by_side(const ImpactMap<double>& map, long begin, long end, long n, long steps, std::string* out) {
  using Tr = ScalarTraits<double>;
  constexpr int K = kStepLanes;
  if (end - begin < K) {
    for (long i = begin; i < end; ++i) out[i - begin] = iterate(map, i, n, steps, 53);
    return;
  }
  State<double> s[K];
  StepResult<double> r[K];
  Reason why[K];
  for (int k = 0; k < K; ++k) s[k] = grid_point<double>(begin + k, n, 53);
  unsigned failed = 0;
  long done = 0;
  for (; done < steps && !failed; ++done) {
    failed = map.step_n<K>(s, r, why);
    for (int k = 0; k < K; ++k)
      if (!(failed >> k & 1u)) s[k] = r[k].next;
  }
  for (int k = 0; k < K; ++k) {
    std::string& o = out[k];
    if (failed >> k & 1u) {
      o = Undecided(why[k]).what();
      continue;
    }
    try {
      for (long j = done; j < steps; ++j) s[k] = map.step(s[k]).next;
      o = Tr::to_string(s[k].theta) + "," + Tr::to_string(s[k].v);
    } catch (const Undecided& u) {
      o = u.what();
    }
  }
  for (long i = begin + K; i < end; i += K)
    iterate_side_by_side(map, i, std::min(end, i + K), n, steps, out + (i - begin));
}

struct Row {
  std::string what;
  long threads;
  double seconds, rate;
  std::string unit, note;
};

// The table: its columns (and text widths) in one place, for the text and the JSON.
bench::Table grid_table() {
  return {"grid", "grid workloads: wall-clock seconds and throughput",
          {"workload", "threads", "seconds", "rate", "note"}, {-52, 7, 10, 18, -1}, {}, {}};
}

void fill(bench::Table& table, const std::vector<Row>& rows) {
  for (const Row& r : rows)
    table.add({r.what, std::to_string(r.threads), bench::fmt("%.2f", r.seconds), bench::fmt("%.3g", r.rate) + " " + r.unit,
               r.note});
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Run run = bench::Run::start("bench_grid", argc, argv);
  bench::Table table = grid_table();
  if (run.columns_only) return run.print_columns({&table});
  long n = 512, steps = 5000, mn = 48, bits = 128, samples = 1000;
  bool curve_only = false;     // only workload 5 (the others take minutes)
  bool continue_only = false;  // only workload 6
  for (int i = 1; i < argc; ++i) {
    auto next = [&]() { return i + 1 < argc ? std::atol(argv[++i]) : 0L; };
    if (!std::strcmp(argv[i], "--size")) n = next();
    else if (!std::strcmp(argv[i], "--steps")) steps = next();
    else if (!std::strcmp(argv[i], "--mpfr-size")) mn = next();
    else if (!std::strcmp(argv[i], "--bits")) bits = next();
    else if (!std::strcmp(argv[i], "--samples")) samples = next();
    else if (!std::strcmp(argv[i], "--quick")) { n = 64; steps = 1000; mn = 12; samples = 50; }
    else if (!std::strcmp(argv[i], "--curve-only")) curve_only = true;
    else if (!std::strcmp(argv[i], "--continue-only")) continue_only = true;
    else {
      std::fprintf(stderr, "usage: bench_grid [--size N] [--steps S] [--mpfr-size M] [--bits B] [--samples K] [--quick] [--curve-only] [--continue-only] [--json FILE]\n       bench_grid --columns\n");
      return 2;
    }
  }
  if (n < 1 || steps < 501 || mn < 1 || bits < 16 || samples < 2) {
    std::fprintf(stderr, "bench_grid: need size >= 1, steps > 500, mpfr-size >= 1, bits >= 16, samples >= 2\n");
    return 2;
  }
  run.print_provenance();
  std::printf("bench_grid: %u hardware threads; basin %ld x %ld, %ld steps per point\n", std::thread::hardware_concurrency(),
              n, n, steps);
  std::vector<Row> rows;
  const ModelSpec spec = basin_model();
  const ImpactMap<double> map(make_model<double>(spec, 53));
  GridPlan plan{n * n, 256};
  const double total_steps = static_cast<double>(n) * n * steps;

  if (!curve_only && !continue_only) {
    // 1. Exactly `steps` steps per point, 1 and 2 threads.
    std::vector<std::string> ref;
    double t1 = 0;
    for (unsigned threads : {1u, 2u}) {
      GridOptions o;
      o.threads = threads;
      const auto t0 = std::chrono::steady_clock::now();
      GridResult r = run_grid(plan, [&](long i) { return iterate(map, i, n, steps, 53); }, o);
      const double t = seconds_since(t0);
      std::string note = "peak RSS " + std::to_string(peak_rss_mb()) + " MB";
      if (threads == 1) {
        t1 = t;
        ref = std::move(r.items);
      } else {
        char sp[64];
        std::snprintf(sp, sizeof sp, "; speed-up %.2fx; %s", t1 / t, r.items == ref ? "identical" : "DIFFERENT");
        note += sp;
      }
      rows.push_back({"basin " + std::to_string(n) + "^2 x " + std::to_string(steps) + " steps, double", threads, t,
                      total_steps / t, "steps/s", note});
      std::fflush(stdout);
    }

    // 1b. The same, kStepLanes points side by side (ImpactMap::step_n), compared with 1.
    for (unsigned threads : {1u, 2u}) {
      GridOptions o;
      o.threads = threads;
      const auto t0 = std::chrono::steady_clock::now();
      GridResult r = run_grid(plan, kStepLanes, [&](long b, long e, std::string* out) {
        iterate_side_by_side(map, b, e, n, steps, out);
      }, o);
      const double t = seconds_since(t0);
      char note[128];
      if (threads == 1)
        std::snprintf(note, sizeof note, "%.1f ns per orbit-step; %.2fx one by one; %s", 1e9 * t / total_steps,
                      rows[0].seconds / t, r.items == ref ? "identical" : "DIFFERENT");
      else
        std::snprintf(note, sizeof note, "%.2fx one by one at 2 threads; %s", rows[1].seconds / t,
                      r.items == ref ? "identical" : "DIFFERENT");
      rows.push_back({"basin " + std::to_string(n) + "^2 x " + std::to_string(steps) + " steps, double, " +
                          std::to_string(kStepLanes) + " side by side",
                      threads, t, total_steps / t, "steps/s", note});
      std::fflush(stdout);
    }

    // 2. The real basin: classify every point (transient steps - 500, then 500 examined), as
    //    `bouncer basin` does: kStepLanes points at a time (classify_many, BasinGrid::items).
    {
      ClassifyOptions co;
      co.transient = steps - 500;
      co.steps = 500;
      co.max_period = 64;
      std::vector<std::string> first;
      double c1 = 0;
      for (unsigned threads : {1u, 2u}) {
        GridOptions o;
        o.threads = threads;
        const auto t0 = std::chrono::steady_clock::now();
        GridResult r = run_grid(plan, kStepLanes, [&](long b, long e, std::string* out) {
          std::vector<State<double>> starts;
          for (long i = b; i < e; ++i) starts.push_back(grid_point<double>(i, n, 53));
          const std::vector<Classification> cs = classify_many<double>(map, starts, co);
          for (long i = b; i < e; ++i)
            out[i - b] = std::string(name(cs[i - b].cls)) + "," + std::to_string(cs[i - b].period);
        }, o);
        const double t = seconds_since(t0);
        std::string note = "peak RSS " + std::to_string(peak_rss_mb()) + " MB";
        if (threads == 1) {
          c1 = t;
          first = std::move(r.items);
        } else {
          char sp[64];
          std::snprintf(sp, sizeof sp, "; speed-up %.2fx; %s", c1 / t, r.items == first ? "identical" : "DIFFERENT");
          note += sp;
        }
        rows.push_back({"basin " + std::to_string(n) + "^2 classified (bouncer basin), double", threads, t,
                        static_cast<double>(n) * n / t, "points/s", note});
        std::fflush(stdout);
      }
    }

    // 3. Bifurcation diagram at paper resolution: K values of a in [28, 30], eps = 0.96.
    {
      ModelSpec b = spec;
      b.eps = *Decimal::parse("0.96");
      const Model<double> base = make_model<double>(b, 53);
      GridPlan bp{samples, 8};
      GridOptions o;
      o.threads = 2;
      const auto t0 = std::chrono::steady_clock::now();
      GridResult r = run_grid(bp, [&](long k) {
        const Model<double> m = with_parameter(base, Parameter::a, 28 + 2.0 * k / (samples - 1));
        const ImpactMap<double> mp(m);
        State<double> s{0.5, 4};
        std::string out;
        for (long i = 0; i < 5000; ++i) s = mp.step(s).next;
        for (long i = 0; i < 500; ++i) {
          s = mp.step(s).next;
          out += ScalarTraits<double>::to_string(s.theta) + "," + ScalarTraits<double>::to_string(s.v) + "\n";
        }
        return out;
      }, o);
      const double t = seconds_since(t0);
      rows.push_back({"bifurcation " + std::to_string(samples) + " values x (5000 + 500), double", 2, t,
                      samples * 5500.0 / t, "steps/s", "peak RSS " + std::to_string(peak_rss_mb()) + " MB"});
    }

    // 4. MPFR: the basin iteration on an mn x mn grid, extrapolated to n x n.
    {
      const ImpactMap<Mpfr> mmap(make_model<Mpfr>(spec, bits));
      GridPlan mp{mn * mn, 8};
      std::vector<std::string> first;
      double m1 = 0;
      for (unsigned threads : {1u, 2u}) {
        GridOptions o;
        o.threads = threads;
        const auto t0 = std::chrono::steady_clock::now();
        GridResult r = run_grid(mp, [&](long i) { return iterate(mmap, i, mn, steps, bits); }, o);
        const double t = seconds_since(t0);
        const double rate = static_cast<double>(mn) * mn * steps / t;
        char note[160];
        std::snprintf(note, sizeof note, "%s%s%ld^2 would take ~%.0f s", threads == 1 ? "" : "speed-up ",
                      threads == 1 ? "" : (std::to_string(m1 / t).substr(0, 4) + "x, " + (r.items == first ? "identical; " : "DIFFERENT; ")).c_str(),
                      n, total_steps / rate);
        if (threads == 1) {
          m1 = t;
          first = std::move(r.items);
        }
        rows.push_back({"basin " + std::to_string(mn) + "^2 x " + std::to_string(steps) + " steps, MPFR " + std::to_string(bits) + " bits",
                        threads, t, rate, "steps/s", note});
      }
    }
  }  // !curve_only

  // 5. Exponent curve: what `bouncer lyapunov --vary a --samples K --transient 5000 --steps
  //    20000` computes per value (lyapunov, then classify from the window's end).
  if (!continue_only) {
    ModelSpec v = spec;
    v.law = Law::veldep;
    v.c = *Decimal::parse("1000");
    const Model<double> base = make_model<double>(v, 53);
    LyapunovOptions lo;
    lo.transient = 5000;
    lo.steps = 20000;
    ClassifyOptions co;
    co.transient = 0;
    GridPlan cp{samples, 16};
    GridOptions o;
    o.threads = 2;
    const auto t0 = std::chrono::steady_clock::now();
    GridResult r = run_grid(cp, [&](long k) {
      const Model<double> m = with_parameter(base, Parameter::a, 20 + 10.0 * k / (samples - 1));
      State<double> s{0.1, 6};
      const LyapunovResult lr = lyapunov(m, s, lo, &s);
      const Classification c = classify<double>(ImpactMap<double>(m), s, co);
      return ScalarTraits<double>::to_string(lr.lambda) + "," + name(c.cls);
    }, o);
    const double t = seconds_since(t0);
    long chaotic = 0;
    for (const std::string& it : r.items) chaotic += it.find("chaotic") != std::string::npos;
    rows.push_back({"lyapunov curve " + std::to_string(samples) + " values x (5000 + 20000), double", 2, t,
                    samples * 25000.0 / t, "steps/s",
                    std::to_string(chaotic) + " chaotic/transient-chaos values; peak RSS " + std::to_string(peak_rss_mb()) + " MB"});
  }
  // 6. Continuation with a located border collision: the stable period-7 branch of the
  //    velocity-dependent model at c = 1000 (data/scenes/continue-veldep-period7.toml) over
  //    a in [27, 29], in double and at 128 bits; both ends are border collisions.
  if (!curve_only) {
    ModelSpec v = spec;
    v.law = Law::veldep;
    v.c = *Decimal::parse("1000");
    v.a = *Decimal::parse("28");
    const InitialCondition guess{*Decimal::parse("0.19204436106841707"), *Decimal::parse("26.916257785320354")};
    std::string a_double;
    // With the look beyond each end (what `bouncer continue` does: a classification of the
    // orbit at a* + 1e-6 |a*|, 5000 + 500 steps and a re-check of a chaotic verdict, all in
    // the working type) and without it (the continuation alone).
    double seconds[2][2] = {};
    auto run = [&](auto tag, long b, const char* label, bool beyond) {
      using T = decltype(tag);
      const Model<T> m = make_model<T>(v, b);
      ContinuationOptions o;
      o.classify_beyond = beyond;
      // Repeated until 0.5 s have passed (a double run takes milliseconds): the mean per run,
      // in thread CPU time (one thread: the ratio to double is what matters, and the
      // machine's other load moves the wall clock more).
      const double t0 = bench::thread_cpu_seconds();
      Branch<T> br;
      long reps = 0;
      do {
        br = continue_branch(m, Parameter::a, 7, make_state<T>(guess, b), ScalarTraits<T>::from_int(27, b),
                             ScalarTraits<T>::from_int(29, b), o);
        ++reps;
      } while (bench::thread_cpu_seconds() - t0 < 0.5);
      const double t = (bench::thread_cpu_seconds() - t0) / static_cast<double>(reps);
      const bool is_double = std::is_same_v<T, double>;
      seconds[is_double ? 0 : 1][beyond ? 0 : 1] = t;
      const std::string lo = ScalarTraits<T>::to_string(br.low.param);
      if (a_double.empty()) a_double = lo;
      char each[96];
      std::snprintf(each, sizeof each, t < 0.1 ? "%.2g ms per run (%ld run%s); " : "%.0f ms per run (%ld run%s); ", t * 1e3,
                    reps, reps == 1 ? "" : "s");
      std::string note = each + std::to_string(br.points.size()) + " points, " + std::to_string(br.corrector_runs) +
                         " Newton runs; low end " + name(br.low.reason) + " at a* = " + lo.substr(0, 22);
      if (!is_double && seconds[0][beyond ? 0 : 1] > 0) {
        char ratio[64];
        std::snprintf(ratio, sizeof ratio, "; %.0fx double", t / seconds[0][beyond ? 0 : 1]);
        note += ratio;
      }
      rows.push_back({std::string("continue period 7 (veldep c 1000), a in [27, 29], ") + label +
                          (beyond ? "" : ", without the look beyond"),
                      1, t, static_cast<double>(br.corrector_runs) / t, "Newton runs/s", note});
    };
    run(0.0, 53, "double", true);
    run(Mpfr(128), 128, "mpfr:128", true);
    run(0.0, 53, "double", false);
    run(Mpfr(128), 128, "mpfr:128", false);
  }
  fill(table, rows);
  table.notes.push_back("Peak RSS at the end: " + std::to_string(peak_rss_mb()) + " MB (grid of " + std::to_string(n * n) +
                        " points).");
  std::printf("\n");
  table.print_all();
  return run.finish({&table}) ? 0 : 1;
}
