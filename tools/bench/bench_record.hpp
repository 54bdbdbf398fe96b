// bench_record.hpp: what the C++ benchmark tools share to record their tables (issue 24).
//
// A tool's tables are data: named columns and rows of already formatted cells. The tool
// prints them as aligned text on stdout (print_header / print_row, from the same cells), and
// with `--json FILE` writes them, with the run's provenance (command, bouncer version and
// commit, date, machine), as one JSON document that tools/bench/record_tables.py turns into
// Markdown blocks of docs/guide/benchmarks.md: Markdown is formatted there and nowhere else.
// `--columns` prints the tables' names and columns as JSON without running anything (the
// test bench.tables_in_sync compares them with the page's header rows).
// The Python benchmarks (bench_audit.py, bench_python.py) write the same document through
// tools/bench/bench_record.py.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bouncer/base/build_info.hpp"

namespace bench {

// The calling thread's CPU time in seconds: the benchmarks time work in thread CPU time, so
// that other processes on the shared machine do not count (they still slow the caches).
inline double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Table {
  std::string name;                       // the block bench:TOOL/NAME of the page
  std::string title;                      // one line: what the table measures
  std::vector<std::string> columns;       // the header row
  std::vector<int> widths;                // text output only: column widths (negative: left-aligned)
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> notes;         // lines printed under the table

  void add(std::vector<std::string> cells) {
    if (cells.size() != columns.size())
      throw std::logic_error("bench table " + name + ": a row of " + std::to_string(cells.size()) + " cells for " +
                             std::to_string(columns.size()) + " columns");
    rows.push_back(std::move(cells));
  }
  // Aligned text on stdout, from the same cells the JSON holds.
  void print_line(const std::vector<std::string>& cells) const {
    std::string line;
    for (size_t i = 0; i < cells.size(); ++i) {
      const int w = i < widths.size() ? widths[i] : 0;
      const size_t n = static_cast<size_t>(w < 0 ? -w : w);
      const std::string pad = cells[i].size() < n ? std::string(n - cells[i].size(), ' ') : "";
      if (i) line += ' ';
      line += w < 0 ? cells[i] + pad : pad + cells[i];
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  }
  void print_header() const { print_line(columns); }
  void print_row() const { print_line(rows.back()); }  // the row just added
  void add_and_print(std::vector<std::string> cells) {
    add(std::move(cells));
    print_row();
  }
  void print_all() const {
    print_header();
    for (const auto& r : rows) print_line(r);
    for (const auto& n : notes) std::printf("%s\n", n.c_str());
  }
};

inline std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

inline std::string read_first_line(const char* path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  return line;
}

inline std::string read_cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) {
      const auto p = line.find(':');
      return p == std::string::npos ? line : line.substr(p + 2);
    }
  return "unknown";
}

inline std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&t));
  return buf;
}

// The run: provenance taken at start, and the options every tool shares. start() removes
// `--json FILE` and `--columns` from argv, so that the tool parses the rest as before.
struct Run {
  std::string tool, command, date, cpu_model, load_at_start, json_path;
  long cpus = 0;
  bool columns_only = false;

  static Run start(const char* tool, int& argc, char** argv) {
    Run r;
    r.tool = tool;
    int out = 1;
    std::string cmd = tool;  // the tool's name, not the path it was run by
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--json" && i + 1 < argc) {
        r.json_path = argv[++i];
        continue;
      }
      if (a == "--columns") {
        r.columns_only = true;
        continue;
      }
      cmd += " " + a;
      argv[out++] = argv[i];
    }
    argc = out;
    argv[argc] = nullptr;
    r.command = cmd;
    r.date = utc_now();
    r.cpus = sysconf(_SC_NPROCESSORS_ONLN);
    r.cpu_model = read_cpu_model();
    r.load_at_start = read_first_line("/proc/loadavg");
    return r;
  }

  // The text header every tool prints first (bench_step's, shared).
  void print_provenance() const {
    const bouncer::BuildInfo& b = bouncer::build_info();
    std::printf("# command: %s\n# date: %s\n", command.c_str(), date.c_str());
    std::printf("# machine: %ld cpus online, %s; load average at start: %s\n", cpus, cpu_model.c_str(),
                load_at_start.c_str());
    std::printf("# bouncer %s (commit %s), compiler %s %s, flags: %s\n", b.version.c_str(), b.commit.c_str(),
                b.compiler.c_str(), b.build_type.c_str(), b.flags.c_str());
  }

  static nlohmann::json table_json(const Table& t, bool with_rows) {
    nlohmann::json j = {{"name", t.name}, {"title", t.title}, {"columns", t.columns}};
    if (with_rows) {
      j["rows"] = t.rows;
      j["notes"] = t.notes;
    }
    return j;
  }

  // --columns: the tables' names and columns, no provenance, nothing run.
  int print_columns(const std::vector<const Table*>& tables) const {
    nlohmann::json j = {{"tool", tool}, {"tables", nlohmann::json::array()}};
    for (const Table* t : tables) j["tables"].push_back(table_json(*t, false));
    std::printf("%s\n", j.dump(1).c_str());
    return 0;
  }

  // --json FILE: the record of this run. Returns false (after a message) if it cannot be written.
  bool finish(const std::vector<const Table*>& tables) const {
    if (json_path.empty()) return true;
    const bouncer::BuildInfo& b = bouncer::build_info();
    nlohmann::json j = {
        {"tool", tool},
        {"command", command},
        {"version", b.version},
        {"commit", b.commit},
        {"build", b.compiler + " " + b.build_type},
        {"date", date},
        {"machine", {{"cpus", cpus}, {"cpu", cpu_model}, {"load_at_start", load_at_start}}},
        {"tables", nlohmann::json::array()},
    };
    for (const Table* t : tables) j["tables"].push_back(table_json(*t, true));
    std::ofstream f(json_path);
    f << j.dump(1) << "\n";
    if (!f) {
      std::fprintf(stderr, "%s: --json %s: cannot write the file\n", tool.c_str(), json_path.c_str());
      return false;
    }
    return true;
  }
};

}  // namespace bench
