// bench_recheck: the scan's two re-check rules (analysis/classify.hpp RecheckRule) on the
// paper's scan ranges (figs. paramspace1, (a, eps) of the constant model, and paramspace2,
// (a, c) of the velocity-dependent model), start by start: every parameter point's starts are
// classified three times (ScanGrid::labels, the library call behind `bouncer scan`): with the
// rules before exact cycles and recurrence (--recheck full, every step taken:
// ClassifyOptions::exact_cycles off), with
// --recheck full (exact cycles carried: the same labels and evidence, checked here, exit 1
// if not) and with --recheck recurrence, the default; timed (thread CPU time, each first in
// turn), and the labels of the two rules compared. Issue 25's target: the scan >= 3x faster with the same labels, or
// every difference explained: each differing start is listed with both labels and evidence.
// Timings are printed, never checked (not a test).
//   bench_recheck [--grid PxQ] [--ics K] [--transient N] [--steps M] [--json FILE]
//     (defaults 20x10 points, 10 x 10 starts each, the paper's 5000 and 500: 20000 starts a
//     scan, each scan about 30 s with the full rule on this machine)
//   bench_recheck --quick        (4x2 points, 3 x 3 starts, transient 500, steps 128)
//   bench_recheck --columns      (the tables' columns as JSON, nothing run; bench_record.hpp)

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench_record.hpp"
#include "bouncer/io/options.hpp"
#include "bouncer/run/scan.hpp"

using namespace bouncer;

namespace {

ScanRequest request(Law law, const char* a, const char* y, long p, long q, long k, long transient, long steps) {
  ScanRequest r;
  r.model.law = law;
  r.model.wall = parse_wall("wall", "triangle");
  r.model.a = parse_decimal("a", "20");
  r.model.eps = parse_decimal("eps", "0.5");
  r.model.c = parse_decimal("c", "1000");
  std::tie(r.a_lo, r.a_hi) = parse_range("a-range", a);
  std::tie(r.y_lo, r.y_hi) = parse_range(law == Law::constant ? "eps-range" : "c-range", y);
  r.p = p;
  r.q = q;
  r.k = k;
  r.classify.transient = transient;
  r.classify.steps = steps;
  r.classify.max_period = std::min(64L, steps / 2);
  return r;
}

// A label in a few words: "chaotic", "periodic 3", "transient_chaos -> periodic 3 from step 41234".
std::string words(const Classification& c) {
  std::string s = name(c.cls);
  if (c.period) s += " " + std::to_string(c.period);
  if (c.cls == OrbitClass::transient_chaos) {
    s += std::string(" -> ") + name(c.settled_class);
    if (c.settled_at) s += " from step " + std::to_string(c.settled_at);
  }
  return s;
}

// The join step of a recurrence label, or "".
std::string joined_after(const Classification& c) {
  return c.recheck_joined_at > 0 ? std::to_string(c.recheck_joined_at) : "";
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Run run = bench::Run::start("bench_recheck", argc, argv);
  bench::Table table{"recheck",
                     "the scan's re-check rules on the paper's ranges, start by start (thread CPU seconds of the classification)",
                     {"scan", "points", "starts", "joined", "differ", "stepped s", "full s", "recurrence s", "speed-up"},
                     {-34, 7, 7, 7, 7, 10, 8, 13, 9},
                     {},
                     {}};
  bench::Table diffs{"differences", "every start whose label differs between the rules",
                     {"scan", "a", "y", "start", "full", "lambda", "recurrence", "lambda", "joined after"},
                     {-12, 6, 6, 6, -36, 8, -36, 8, 12},
                     {},
                     {}};
  if (run.columns_only) return run.print_columns({&table, &diffs});
  long p = 20, q = 10, k = 10, transient = 5000, steps = 500;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      p = 4, q = 2, k = 3, transient = 500, steps = 128;
    } else if (a == "--grid" && i + 1 < argc) {
      if (std::sscanf(argv[++i], "%ldx%ld", &p, &q) != 2) p = 0;
    } else if (a == "--ics" && i + 1 < argc) {
      k = std::atol(argv[++i]);
    } else if (a == "--transient" && i + 1 < argc) {
      transient = std::atol(argv[++i]);
    } else if (a == "--steps" && i + 1 < argc) {
      steps = std::atol(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: bench_recheck [--quick] [--grid PxQ] [--ics K] [--transient N] [--steps M] [--json FILE]\n"
                   "       bench_recheck --columns\n");
      return 2;
    }
  }
  if (p < 1 || q < 1 || k < 1 || transient < 0 || steps < 8 || p * q > 100000) {
    std::fprintf(stderr, "bench_recheck: --grid needs 1 <= P, Q and P*Q <= 100000, --ics >= 1, --steps >= 8\n");
    return 2;
  }
  struct Case {
    const char* what;
    const char* tag;
    Law law;
    const char* a;
    const char* y;
  } cases[] = {{"paramspace1: constant, a 10:30, eps 0.05:0.95", "paramspace1", Law::constant, "10:30", "0.05:0.95"},
               {"paramspace2: veldep, a 20:30, c 500:1500", "paramspace2", Law::veldep, "20:30", "500:1500"}};
  run.print_provenance();
  table.print_header();
  for (const Case& c : cases) {
    ScanRequest full = request(c.law, c.a, c.y, p, q, k, transient, steps);
    full.classify.recheck = RecheckRule::full;
    ScanRequest rec = full, stepped = full;
    rec.classify.recheck = RecheckRule::recurrence;
    stepped.classify.exact_cycles = false;
    const ScanGrid gs(stepped, false), gf(full, false), gr(rec, false);
    const ScanResult axes = gf.result(std::vector<ScanCell>(static_cast<size_t>(p * q)));
    double ts = 0, tf = 0, tr = 0;
    long starts = 0, joined = 0, differ = 0, stepped_differ = 0;
    for (long i = 0; i < p * q; ++i) {
      std::vector<StartLabel> out[3];
      const ScanGrid* grids[3] = {&gs, &gf, &gr};
      double* times[3] = {&ts, &tf, &tr};
      for (int pass = 0; pass < 3; ++pass) {
        const int m = static_cast<int>((pass + i) % 3);  // each rule first in turn
        const double t0 = bench::thread_cpu_seconds();
        out[m] = grids[m]->labels(i);
        *times[m] += bench::thread_cpu_seconds() - t0;
      }
      const std::vector<StartLabel>&ls = out[0], &lf = out[1], &lr = out[2];
      for (size_t n = 0; n < ls.size() && n < lf.size(); ++n)
        stepped_differ += ls[n].label.evidence != lf[n].label.evidence || ls[n].label.settled_at != lf[n].label.settled_at;
      starts += static_cast<long>(lf.size());
      for (size_t n = 0; n < lf.size() && n < lr.size(); ++n) {
        const std::string after = joined_after(lr[n].label);
        if (!after.empty()) ++joined;
        if (same_behaviour(lf[n].label, lr[n].label)) continue;
        ++differ;
        diffs.add({c.tag, axes.a[static_cast<size_t>(i % p)].digits, axes.y_values[static_cast<size_t>(i / p)].digits,
                   std::to_string(lf[n].j), words(lf[n].label), bench::fmt("%.4f", lf[n].label.lambda),
                   words(lr[n].label), bench::fmt("%.4f", lr[n].label.lambda), after.empty() ? "-" : after});
      }
    }
    table.add_and_print({c.what, std::to_string(p * q), std::to_string(starts), std::to_string(joined),
                         std::to_string(differ), bench::fmt("%.2f", ts), bench::fmt("%.2f", tf), bench::fmt("%.2f", tr),
                         bench::fmt("%.2fx", tr > 0 ? ts / tr : 0.0)});
    if (stepped_differ) {
      std::fprintf(stderr, "bench_recheck: %ld starts differ between stepped and carried exact cycles (a defect)\n", stepped_differ);
      return 1;
    }
  }
  table.notes.push_back("grid " + std::to_string(p) + "x" + std::to_string(q) + ", " + std::to_string(k) + " x " +
                        std::to_string(k) + " starts per point, transient " + std::to_string(transient) + ", steps " +
                        std::to_string(steps) + ", recheck-factor 20. stepped: --recheck full, every step taken (the rules before exact cycles and "
                        "recurrence); full: --recheck full, exact cycles carried (the same labels and evidence, checked); recurrence: the default; "
                        "speed-up: stepped / recurrence; joined: starts whose re-check ended early by recurrence.");
  std::printf("%s\n\n", table.notes.back().c_str());
  diffs.print_header();
  for (const auto& row : diffs.rows) diffs.print_line(row);
  if (diffs.rows.empty()) diffs.notes.push_back("no start differs");
  return run.finish({&table, &diffs}) ? 0 : 1;
}
