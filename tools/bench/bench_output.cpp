// bench_output: what writing an orbit costs per row next to computing it (issue 25: CSV was
// 725 ns per 97-byte row against a 50 ns step). Workload: `bouncer orbit --model constant
// --a 24 --eps 0.5 --theta 0.05 --v 10.5 --steps N` in double (the default scene's chaotic
// orbit: impacts on both segments, long and short flights), through the library calls of
// `bouncer orbit` (io/orbit.hpp):
//   step  follow_orbit with a sink that keeps nothing: the floor of every output row;
//   csv   write_orbits (--format csv): the rows as text, shortest round-trip doubles;
//   npy   write_orbits_npy (--format npy): the rows as 16 float64;
//   json  write_orbits (--format json), for comparison (one string per cell, iostream).
// Each output goes to a stream that counts and drops its bytes (the file system is not
// timed: `bouncer orbit --out` adds write(2) of 64 KiB blocks). Timing: thread CPU time;
// the rows are interleaved in rounds; ns/row is the median over rounds, "x step" the median
// over rounds of (row / step in the same round); spread = (max - min) / median.
// Timings are printed, never checked (not a test).
//   bench_output [--steps N] [--rounds R] [--json FILE]   (default N = 1000000, R = 5)
//   bench_output --columns   (the table's columns as JSON, nothing run; bench_record.hpp)

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#include "bench_record.hpp"
#include "bouncer/io/orbit.hpp"

using namespace bouncer;

namespace {

// Counts and drops what is written (as /dev/null would, without the system calls).
class CountingBuf : public std::streambuf {
 public:
  long long bytes = 0;

 protected:
  std::streamsize xsputn(const char*, std::streamsize n) override {
    bytes += n;
    return n;
  }
  int_type overflow(int_type ch) override {
    if (!traits_type::eq_int_type(ch, traits_type::eof())) ++bytes;
    return traits_type::not_eof(ch);
  }
};

class NullSink final : public OrbitSink<double> {
 public:
  double keep = 0;
  void start(const State<double>& s) override { keep += s.theta; }
  void row(long long, const StepResult<double>& r) override { keep += r.next.theta; }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Run run = bench::Run::start("bench_output", argc, argv);
  bench::Table table{"output",
                     "`bouncer orbit` in double: nanoseconds per written row against the step (thread CPU time)",
                     {"output", "rows", "bytes/row", "ns/row", "x step", "spread"},
                     {-6, 9, 9, 8, 7, 7},
                     {},
                     {}};
  if (run.columns_only) return run.print_columns({&table});
  long long steps = 1000000;
  int rounds = 5;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::atoll(argv[++i]);
    else if (!std::strcmp(argv[i], "--rounds") && i + 1 < argc) rounds = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_output [--steps N] [--rounds R] [--json FILE]\n       bench_output --columns\n");
      return 2;
    }
  }
  if (steps < 1 || rounds < 1) {
    std::fprintf(stderr, "bench_output: --steps and --rounds must be >= 1\n");
    return 2;
  }
  Options o;
  o.set("model", "constant");
  o.set("a", "24");
  o.set("eps", "0.5");
  o.set("theta", std::vector<std::string>{"0.05"});
  o.set("v", std::vector<std::string>{"10.5"});
  o.set("steps", std::to_string(steps));
  OrbitRequest req = orbit_request(o);
  Provenance p;
  p.command = "orbit";
  p.precision = "double";
  p.bits = 53;
  const long long rows = planned_orbit_rows(req);

  struct Row {
    const char* name;
    std::function<long long()> body;  // returns the bytes written
    std::vector<double> ns;
  };
  const ImpactMap<double> map(make_model<double>(req.model, 53));
  const State<double> s0 = make_state<double>(map.model(), req.initial.at(0));
  double keep = 0;
  auto text = [&](Format f) {
    return [&req, &p, f] {
      OrbitRequest r = req;
      r.format = f;
      CountingBuf buf;
      std::ostream s(&buf);
      write_orbits(r, p, s);
      return buf.bytes;
    };
  };
  std::vector<Row> table_rows{
      {"step",
       [&] {
         NullSink sink;
         follow_orbit(map, s0, orbit_steps(req), sink);
         keep += sink.keep;
         return 0LL;
       },
       {}},
      {"csv", text(Format::csv), {}},
      {"npy",
       [&] {
         CountingBuf buf;
         std::ostream s(&buf);
         write_orbits_npy(req, rows, s);
         return buf.bytes;
       },
       {}},
      {"json", text(Format::json), {}},
  };
  std::vector<long long> bytes(table_rows.size());
  for (int k = 0; k < rounds; ++k)
    for (size_t i = 0; i < table_rows.size(); ++i) {
      const double t0 = bench::thread_cpu_seconds();
      bytes[i] = table_rows[i].body();
      table_rows[i].ns.push_back(1e9 * (bench::thread_cpu_seconds() - t0) / static_cast<double>(rows));
    }
  run.print_provenance();
  std::printf("# %lld rows (steps 0..%lld) of one orbit; %d rounds; output to a stream that drops its bytes\n", rows,
              steps, rounds);
  table.print_header();
  for (size_t i = 0; i < table_rows.size(); ++i) {
    const Row& r = table_rows[i];
    std::vector<double> ratio;
    for (int k = 0; k < rounds; ++k) ratio.push_back(r.ns[k] / table_rows[0].ns[k]);
    const double m = median(r.ns);
    const double spread = (*std::max_element(r.ns.begin(), r.ns.end()) - *std::min_element(r.ns.begin(), r.ns.end())) / m;
    table.add_and_print({r.name, std::to_string(rows), i == 0 ? "-" : bench::fmt("%.1f", static_cast<double>(bytes[i]) / rows),
                         bench::fmt("%.1f", m), bench::fmt("%.2f", median(ratio)), bench::fmt("%.2f", spread)});
  }
  table.notes.push_back("ns/row includes the step; x step = ns/row over the step's ns/row in the same round.");
  std::printf("%s\n", table.notes.back().c_str());
  if (keep == 12345.678) std::printf("#\n");  // keeps the step row's work observable
  return run.finish({&table}) ? 0 : 1;
}
