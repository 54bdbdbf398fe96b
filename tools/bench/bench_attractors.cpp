// bench_attractors: `bouncer attractors` at one parameter point (run/attractors.hpp), the
// issue-23 target: 10^4 starts (100 x 100) in under 10 s on 2 cores. Workloads:
//   1. veldep c = 1000, a = 23.1 (periods 3, 8, 7, 2 coexist), double, with certificates;
//   2. constant eps = 0.5, a = 24 (eq. 5 fixed points beside a sticking cycle), double;
// each at 1 and 2 threads (the results compared start by start: they must be identical).
// Timings are printed, never checked (not a test).
//   bench_attractors [--starts N] [--json FILE] (N x N starts, default 100)
//   bench_attractors --columns   (the table's columns as JSON, nothing run; bench_record.hpp)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "bench_record.hpp"
#include "bouncer/run/attractors.hpp"

using namespace bouncer;

namespace {

ModelSpec model(Law law, const char* a, const char* eps, const char* c) {
  ModelSpec m;
  m.law = law;
  m.a = parse_decimal("a", a);
  if (law == Law::constant) m.eps = parse_decimal("eps", eps);
  m.c = parse_decimal("c", c);
  m.wall = parse_wall("wall", "triangle");
  validate(m);
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Run run = bench::Run::start("bench_attractors", argc, argv);
  bench::Table table{"attractors", "`bouncer attractors` at one point: N x N starts at 1 and 2 threads",
                     {"point", "starts", "threads", "seconds", "steps/s", "found"}, {-24, 8, 7, 9, 10, -1}, {}, {}};
  if (run.columns_only) return run.print_columns({&table});
  long n = 100;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--starts") && i + 1 < argc) n = std::atol(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_attractors [--starts N] [--json FILE]\n       bench_attractors --columns\n");
      return 2;
    }
  }
  struct Case {
    const char* what;
    ModelSpec m;
  } cases[] = {{"veldep c=1000 a=23.1", model(Law::veldep, "23.1", "1", "1000")},
               {"constant eps=0.5 a=24", model(Law::constant, "24", "0.5", "1000")}};
  if (n < 1) {
    std::fprintf(stderr, "bench_attractors: --starts must be >= 1\n");
    return 2;
  }
  run.print_provenance();
  table.print_header();
  for (const Case& c : cases) {
    AttractorsResult first;
    for (unsigned threads : {1u, 2u}) {
      AttractorsRequest r;
      r.model = c.m;
      r.nx = r.ny = n;
      GridOptions g;
      g.threads = threads;
      const auto t0 = std::chrono::steady_clock::now();
      const AttractorsResult res = find_attractors(r, g);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::string found;
      for (const FoundAttractor& a : res.attractors)
        found += std::string(found.empty() ? "" : ", ") + name(a.kind) + " " + std::to_string(a.period) +
                 (a.certificate && a.certificate->certified ? "*" : "");
      if (threads == 1) first = res;
      else found += first.label == res.label ? " (identical)" : " (DIFFERENT)";
      table.add_and_print({c.what, std::to_string(n * n), std::to_string(threads), bench::fmt("%.2f", s),
                           bench::fmt("%.3g", static_cast<double>(res.steps) / res.seconds), found});
    }
  }
  table.notes.push_back("*: certified by Krawczyk; the seconds include the certificates.");
  std::printf("%s\n", table.notes.back().c_str());
  return run.finish({&table}) ? 0 : 1;
}
