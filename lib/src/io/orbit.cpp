#include "bouncer/io/orbit.hpp"
#include "bouncer/base/output.hpp"

#include <unistd.h>

#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>
#include <type_traits>

// GCC 12 at -O3 reports false "maybe uninitialized" warnings inside nlohmann::json.
#pragma GCC diagnostic push
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nlohmann/json.hpp>
#pragma GCC diagnostic pop

#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/shortest.hpp"

namespace bouncer {

const std::set<std::string>& orbit_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "steps", "precision", "format", "every", "out", "method"});
    return k;
  }();
  return keys;
}

OrbitRequest orbit_request(const Options& o) {
  OrbitRequest r;
  r.model = model_from(o);
  r.initial = initial_conditions_from(o, r.model);
  r.steps = integer_from(o, "steps", 0, 1000000000000000LL, 10);
  r.every = integer_from(o, "every", 1, 1000000000000000LL, 1);
  r.precision = precision_from(o);
  const std::string f = o.get_or("format", "csv");
  if (f == "csv") r.format = Format::csv;
  else if (f == "json") r.format = Format::json;
  else if (f == "table") r.format = Format::table;
  else if (f == "npy") r.format = Format::npy;
  else throw InputError("format", "unknown format '" + f + "' (allowed: csv, json, table, npy)");
  // Interval runs default to Lohner's method, as the certified commands do: the same
  // exact orbit, enclosed in sets that grow with the dynamics, not with the wrapping effect.
  r.method = r.precision.is_interval() ? EnclosureMethod::lohner : EnclosureMethod::naive;
  if (o.has("method")) {
    r.method = parse_enclosure_method("method", o.get("method"));
    if (r.method == EnclosureMethod::lohner && !r.precision.is_interval())
      throw InputError("method", "lohner needs --precision interval:BITS (got " + o.get_or("precision", "double") +
                                     "); point precisions have no enclosure method");
  }
  if (r.format == Format::npy) {
    // float64 holds a double run's numbers exactly and no other precision's: refused rather
    // than rounded (the CSV and JSON formats print every precision in full).
    if (r.precision.kind != Precision::Kind::double_)
      throw InputError("format", "npy holds float64 values: it needs --precision double (got " + r.precision.text() +
                                     "); allowed with other precisions: csv, json, table");
    if (!o.has("out"))
      throw InputError("out", "--format npy writes a binary file and its provenance beside it: give --out PATH "
                              "(writes PATH and PATH.json)");
  }
  return r;
}

namespace {

// One output column: scalar columns of interval runs become NAME_lo, NAME_hi.
struct Column {
  std::string name;
  bool scalar;
};

const std::vector<Column>& columns() {
  static const std::vector<Column> c{
      {"n", false},        {"theta", true},       {"v", true},           {"event", false},
      {"tau", true},       {"periods", false},    {"segment", false},    {"wall", false},
      {"corner", false},   {"flight", false},     {"sticking", false},   {"stuck_theta", true},
      {"stuck_v", true},   {"phase_bits", false}, {"orbit", false}};
  return c;
}

std::vector<std::string> header_names(bool interval) {
  std::vector<std::string> out;
  for (const Column& c : columns()) {
    if (c.scalar && interval) {
      out.push_back(c.name + "_lo");
      out.push_back(c.name + "_hi");
    } else {
      out.push_back(c.name);
    }
  }
  return out;
}

const char* truth_name(Truth t, const char* yes, const char* no) {
  return t == Truth::yes ? yes : t == Truth::no ? no : "undecided";
}

// A row's cells, written by start_cells and step_cells (which say once what a row holds)
// into one of two writers: StringCells collects strings (the table and JSON formats);
// CsvCells writes each cell and its ',' straight into the CSV block (CsvBlock), with no
// per-cell strings or iostream formatting.
class StringCells {
 public:
  void integer(long long x) { row.push_back(std::to_string(x)); }
  void text(const char* x) { row.emplace_back(x); }
  void empty() { row.emplace_back(); }
  template <class T>
  void scalar(const T& x) {
    using Tr = ScalarTraits<T>;
    if constexpr (Tr::is_interval) {
      row.push_back(Tr::lower_string(x));
      row.push_back(Tr::upper_string(x));
    } else {
      row.push_back(Tr::to_string(x));
    }
  }
  template <class T>
  void empty_scalar() {
    row.emplace_back();
    if constexpr (ScalarTraits<T>::is_interval) row.emplace_back();
  }
  std::vector<std::string> row;
};

// The CSV text waiting for the stream: rows are written straight into it, and it goes out in
// blocks of at least 64 KiB (one write each, no copy per row).
class CsvBlock {
 public:
  explicit CsvBlock(std::ostream& out) : out_(out), data_(std::make_unique<char[]>(kCapacity)) {}
  char* begin() { return data_.get(); }
  char* cursor() { return data_.get() + used_; }
  char* limit() { return data_.get() + kCapacity; }
  // The text up to `end` is kept (and written once a block is full).
  void commit(const char* end) {
    used_ = static_cast<size_t>(end - begin());
    if (used_ >= kBlock) flush();
  }
  void flush() {
    if (used_ == 0) return;
    out_.write(begin(), static_cast<std::streamsize>(used_));
    used_ = 0;
  }
  // Text longer than the block (a cell of a very high precision) goes to the stream at once.
  void write(const char* text, size_t n) {
    flush();
    out_.write(text, static_cast<std::streamsize>(n));
  }

 private:
  static constexpr size_t kBlock = size_t{1} << 16;
  static constexpr size_t kCapacity = kBlock + 4096;
  std::ostream& out_;
  std::unique_ptr<char[]> data_;
  size_t used_ = 0;
};

class CsvCells {
 public:
  explicit CsvCells(CsvBlock& block) : block_(block), p_(block.cursor()) {}
  CsvCells(const CsvCells&) = delete;
  CsvCells& operator=(const CsvCells&) = delete;
  void integer(long long x) {
    room(24);
    p_ = std::to_chars(p_, p_ + 24, x).ptr;
    *p_++ = ',';
  }
  void text(const char* x) { text(x, std::strlen(x)); }
  void text(const char* x, size_t n) {
    if (n + 1 > kRoom) {
      block_.commit(p_);
      block_.write(x, n);
      p_ = block_.cursor();
    } else {
      room(n + 1);
      std::memcpy(p_, x, n);
      p_ += n;
    }
    *p_++ = ',';
  }
  void empty() {
    room(1);
    *p_++ = ',';
  }
  template <class T>
  void scalar(const T& x) {
    using Tr = ScalarTraits<T>;
    if constexpr (std::is_same_v<T, double>) {
      // The shortest decimal that reads back to x, as ScalarTraits<double>::to_string.
      room(kShortestChars + 1);
      p_ = shortest_chars(p_, x);
      *p_++ = ',';
    } else if constexpr (Tr::is_interval) {
      string(Tr::lower_string(x));
      string(Tr::upper_string(x));
    } else {
      string(Tr::to_string(x));
    }
  }
  template <class T>
  void empty_scalar() {
    empty();
    if constexpr (ScalarTraits<T>::is_interval) empty();
  }
  // Ends the line (its last ',' becomes '\n').
  void finish() {
    p_[-1] = '\n';
    block_.commit(p_);
  }

 private:
  // Room for a cell of at most kRoom bytes; longer ones go through CsvBlock::write.
  static constexpr size_t kRoom = 1024;
  void string(const std::string& x) { text(x.data(), x.size()); }
  void room(size_t n) {
    if (static_cast<size_t>(block_.limit() - p_) < n) {
      block_.commit(p_);
      block_.flush();
      p_ = block_.cursor();
    }
  }
  CsvBlock& block_;
  char* p_;
};

// Streams rows in one of the three text formats.
class RowWriter {
 public:
  RowWriter(std::ostream& out, Format f, bool interval, long bits)
      : out_(out), f_(f), names_(header_names(interval)), csv_(out) {
    width_ = static_cast<int>(bits * 0.30103) + 9;
  }
  // CSV rows are written with CsvCells into csv_block(), which goes out in 64 KiB blocks.
  bool fast_csv() const { return f_ == Format::csv; }
  CsvBlock& csv_block() { return csv_; }
  void begin(const Provenance& p) {
    if (f_ == Format::json) {
      out_ << "{\"provenance\": " << p.as_json() << ",\n \"columns\": [";
      for (size_t i = 0; i < names_.size(); ++i) out_ << (i ? ", " : "") << '"' << names_[i] << '"';
      out_ << "],\n \"orbits\": [";
      return;
    }
    out_ << p.as_comment_lines();
    if (f_ == Format::csv) {
      for (size_t i = 0; i < names_.size(); ++i) out_ << (i ? "," : "") << names_[i];
      out_ << "\n";
    } else {
      table_row(names_);
    }
  }
  void begin_orbit(size_t index) {
    if (f_ == Format::json) out_ << (index ? ",\n  " : "\n  ") << "{\"orbit\": " << index << ", \"rows\": [";
    first_row_ = true;
  }
  void row(const std::vector<std::string>& cells) {
    if (f_ == Format::json) {
      out_ << (first_row_ ? "\n    [" : ",\n    [");
      for (size_t i = 0; i < cells.size(); ++i) out_ << (i ? ", " : "") << '"' << cells[i] << '"';
      out_ << "]";
    } else if (f_ == Format::csv) {
      for (size_t i = 0; i < cells.size(); ++i) out_ << (i ? "," : "") << cells[i];
      out_ << "\n";
    } else {
      table_row(cells);
    }
    first_row_ = false;
  }
  void end_orbit(size_t index, const OrbitOutcome& o, long bits) {
    flush_csv();
    std::ostringstream end;
    if (o.undecided)
      end << "undecided at step " << o.steps_done + 1 << ": " << o.reason << " (steps 1.." << o.steps_done
          << " done; rerun at more bits)";
    else
      end << "completed " << o.steps_done << " steps";
    std::string warn;
    if (o.phase_lost_at >= 0)
      warn = "theta has no correct bit from step " + std::to_string(o.phase_lost_at) +
             " on: long flights consumed all " + std::to_string(bits) + " bits of the phase";
    if (f_ == Format::json) {
      out_ << "],\n   \"end\": {\"status\": \"" << (o.undecided ? "undecided" : "completed") << "\", \"steps_done\": "
           << o.steps_done << ", \"message\": \"" << end.str() << "\", \"phase_warning\": \"" << warn << "\"";
      if (o.fallbacks >= 0) out_ << ", \"lohner_fallbacks\": " << o.fallbacks;
      out_ << "}}";
    } else {
      // The "# end:" line comes last: a file without it was cut off.
      if (!warn.empty()) out_ << "# warning: orbit " << index << " " << warn << "\n";
      if (o.fallbacks >= 0)
        out_ << "# lohner: orbit " << index << " " << o.fallbacks << " of " << o.steps_done
             << " steps fell back to the interval box image\n";
      out_ << "# end: orbit " << index << " " << end.str() << "\n";
    }
  }
  void finish() {
    flush_csv();
    if (f_ == Format::json) out_ << "\n ]\n}\n";
    out_.flush();
    check();
  }
  // A stream that failed (disk full, closed pipe) ends the run at once, not after 1e10 rows.
  void check() const {
    if (!out_) throw OutputError("writing the orbit failed (disk full, or the reader closed the pipe?)");
  }

 private:
  void flush_csv() { csv_.flush(); }
  void table_row(const std::vector<std::string>& cells) {
    for (size_t i = 0; i < cells.size(); ++i) {
      const bool wide = names_[i].rfind("theta", 0) == 0 || names_[i].rfind("v", 0) == 0 ||
                        names_[i].rfind("tau", 0) == 0 || names_[i].rfind("stuck", 0) == 0;
      out_ << std::left << std::setw(wide ? width_ : 9) << cells[i] << (i + 1 < cells.size() ? " " : "");
    }
    out_ << "\n";
  }
  std::ostream& out_;
  Format f_;
  std::vector<std::string> names_;
  int width_ = 24;
  bool first_row_ = true;
  CsvBlock csv_;
};

template <class Cells, class T>
void start_cells(Cells& c, const State<T>& s, size_t orbit) {
  c.integer(0);
  c.scalar(s.theta);
  c.scalar(s.v);
  c.text("start");
  c.template empty_scalar<T>();
  for (int i = 0; i < 6; ++i) c.empty();
  c.template empty_scalar<T>();
  c.template empty_scalar<T>();
  c.empty();
  c.integer(static_cast<long long>(orbit));
}

template <class Cells, class T>
void step_cells(Cells& c, long long n, const StepResult<T>& r, const Model<T>& m, size_t orbit) {
  c.integer(n);
  c.scalar(r.next.theta);
  c.scalar(r.next.v);
  c.text(name(r.kind));
  c.scalar(r.tau);
  c.integer(r.periods);
  c.integer(r.segment);
  c.text(direction_name(contact_direction(m, r, false)));
  c.text(r.corner ? "1" : "0");
  c.text(truth_name(r.indirect, "indirect", "direct"));
  if (r.kind == EventKind::sticking) {
    std::string wall = direction_name(contact_direction(m, r, true));
    if (r.passed_upward_turn) wall += std::string(":") + name(m.downward);
    c.text(wall.c_str());
    c.scalar(r.stuck_theta);
    c.scalar(r.stuck_v);
  } else {
    c.empty();
    c.template empty_scalar<T>();
    c.template empty_scalar<T>();
  }
  c.integer(ScalarTraits<T>::bits(r.next.theta) - r.phase_bits_lost);
  c.integer(static_cast<long long>(orbit));
}

// The text sink of the orbit driver (run/orbit.hpp): each row as the writer's cells (CSV:
// appended to the writer's buffer).
template <class T>
class TextSink final : public OrbitSink<T> {
 public:
  TextSink(RowWriter& w, const Model<T>& m, size_t orbit) : w_(w), m_(m), orbit_(orbit) {}
  void start(const State<T>& s) override {
    if (w_.fast_csv()) {
      CsvCells c(w_.csv_block());
      start_cells(c, s, orbit_);
      c.finish();
    } else {
      StringCells c;
      start_cells(c, s, orbit_);
      w_.row(c.row);
    }
  }
  void row(long long n, const StepResult<T>& r) override {
    if (w_.fast_csv()) {
      CsvCells c(w_.csv_block());
      step_cells(c, n, r, m_, orbit_);
      c.finish();
    } else {
      StringCells c;
      step_cells(c, n, r, m_, orbit_);
      w_.row(c.row);
    }
  }
  void check() override { w_.check(); }

 private:
  RowWriter& w_;
  const Model<T>& m_;
  size_t orbit_;
};

template <class T>
std::vector<OrbitOutcome> run(const OrbitRequest& req, const Provenance& p, std::ostream& out) {
  const long bits = req.precision.bits;
  const ImpactMap<T> map(make_model<T>(req.model, bits));
  // Every start is converted before anything is written (a theta that rounds to 1 is bad
  // input, and bad input leaves no partial output).
  std::vector<State<T>> starts;
  for (const InitialCondition& ic : req.initial) starts.push_back(make_state<T>(map.model(), ic));
  RowWriter w(out, req.format, ScalarTraits<T>::is_interval, bits);
  w.begin(p);
  std::vector<OrbitOutcome> outcomes;
  for (size_t i = 0; i < req.initial.size(); ++i) {
    w.begin_orbit(i);
    TextSink<T> sink(w, map.model(), i);
    const OrbitOutcome o = follow_orbit(map, starts[i], orbit_steps(req), sink);
    w.end_orbit(i, o, bits);
    outcomes.push_back(o);
  }
  w.finish();
  return outcomes;
}

// ---- --format npy ----------------------------------------------------------------------

// Codes of the text columns: event as bouncer.Model.orbit's Orbit.event (python/module.cpp,
// bouncer.EVENTS: the start row, then EventKind in order), wall directions as Wall::direction.
constexpr double kEmpty = std::numeric_limits<double>::quiet_NaN();

// Rows of float64 appended to one buffer written in 64 KiB blocks.
class NpyWriter {
 public:
  explicit NpyWriter(std::ostream& out) : out_(out) { buf_.reserve(kBlock); }
  void put(double x) {
    buf_.push_back(x);
    if (buf_.size() == kBlock) flush();
  }
  void flush() {
    static_assert(std::endian::native == std::endian::little, "the .npy data are written as little-endian float64");
    if (buf_.empty()) return;
    out_.write(reinterpret_cast<const char*>(buf_.data()), static_cast<std::streamsize>(buf_.size() * sizeof(double)));
    buf_.clear();
  }
  void check() const {
    if (!out_) throw OutputError("writing the orbit failed (disk full, or the reader closed the pipe?)");
  }

 private:
  static constexpr size_t kBlock = 8192;
  std::ostream& out_;
  std::vector<double> buf_;
};

class NpySink final : public OrbitSink<double> {
 public:
  NpySink(NpyWriter& w, const Model<double>& m, size_t orbit) : w_(w), m_(m), orbit_(static_cast<double>(orbit)) {}
  void start(const State<double>& s) override {
    const double row[] = {0,      s.theta, s.v,    kStartEventCode, kEmpty, kEmpty, kEmpty, kEmpty,
                          kEmpty, kEmpty,  kEmpty, kEmpty,          kEmpty, kEmpty, kEmpty, orbit_};
    put(row);
  }
  void row(long long n, const StepResult<double>& r) override {
    const bool stuck = r.kind == EventKind::sticking;
    const double row[] = {static_cast<double>(n),
                          r.next.theta,
                          r.next.v,
                          static_cast<double>(event_code(r.kind)),
                          r.tau,
                          static_cast<double>(r.periods),
                          static_cast<double>(r.segment),
                          static_cast<double>(contact_direction(m_, r, false)),
                          r.corner ? 1.0 : 0.0,
                          static_cast<double>(flight_code(r.indirect)),
                          stuck ? static_cast<double>(contact_direction(m_, r, true)) : kEmpty,
                          stuck ? (r.passed_upward_turn ? 1.0 : 0.0) : kEmpty,
                          stuck ? r.stuck_theta : kEmpty,
                          stuck ? r.stuck_v : kEmpty,
                          static_cast<double>(ScalarTraits<double>::bits(r.next.theta) - r.phase_bits_lost),
                          orbit_};
    put(row);
  }
  void check() override { w_.check(); }
  long long rows() const { return rows_; }

 private:
  void put(const double (&row)[16]) {
    for (double x : row) w_.put(x);
    ++rows_;
  }
  NpyWriter& w_;
  const Model<double>& m_;
  double orbit_;
  long long rows_ = 0;
};

}  // namespace

const std::vector<std::string>& npy_orbit_columns() {
  static const std::vector<std::string> c{"n",       "theta",     "v",         "event",        "tau",
                                          "periods", "segment",   "wall",      "corner",       "indirect",
                                          "stick_wall", "passed_upward_turn", "stuck_theta", "stuck_v",
                                          "phase_bits", "orbit"};
  return c;
}

long long planned_orbit_rows(const OrbitRequest& r) {
  // follow_orbit keeps the steps n with n % every == 0 and the last one.
  const long long kept = r.steps / r.every + (r.steps % r.every != 0 ? 1 : 0);
  return static_cast<long long>(r.initial.size()) * (1 + kept);
}

std::string npy_header(long long rows, size_t cols) {
  // Format 1.0: magic, version, header length (uint16 little-endian), then the dict padded
  // with spaces and ended by '\n' so that the data start at a multiple of 64 bytes (here 128).
  constexpr size_t kTotal = 128;
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                     std::to_string(cols) + "), }";
  std::string h("\x93NUMPY\x01\x00", 8);
  const size_t len = kTotal - 10;
  h += static_cast<char>(len & 0xff);
  h += static_cast<char>(len >> 8);
  h += dict;
  h.append(kTotal - 1 - h.size(), ' ');
  h += '\n';
  return h;
}

NpyOrbits write_orbits_npy(const OrbitRequest& req, long long header_rows, std::ostream& out) {
  if (req.precision.kind != Precision::Kind::double_) throw std::logic_error("write_orbits_npy: double runs only");
  const ImpactMap<double> map(make_model<double>(req.model, req.precision.bits));
  std::vector<State<double>> starts;
  for (const InitialCondition& ic : req.initial) starts.push_back(make_state<double>(map.model(), ic));
  const std::string h = npy_header(header_rows, npy_orbit_columns().size());
  out.write(h.data(), static_cast<std::streamsize>(h.size()));
  NpyWriter w(out);
  NpyOrbits result;
  for (size_t i = 0; i < starts.size(); ++i) {
    NpySink sink(w, map.model(), i);
    result.outcomes.push_back(follow_orbit(map, starts[i], orbit_steps(req), sink));
    result.rows.push_back(sink.rows());
    result.total_rows += sink.rows();
  }
  w.flush();
  out.flush();
  w.check();
  return result;
}

void rewrite_npy_header(int fd, const std::string& name, long long rows, size_t cols) {
  const std::string h = npy_header(rows, cols);
  size_t done = 0;
  while (done < h.size()) {
    const ssize_t w = ::pwrite(fd, h.data() + done, h.size() - done, static_cast<off_t>(done));
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw OutputError("rewriting the header of '" + name + "' failed: " + std::strerror(w < 0 ? errno : EIO));
    done += static_cast<size_t>(w);
  }
}

std::string orbit_npy_sidecar(const OrbitRequest& r, const Provenance& p, const NpyOrbits& o, const std::string& npy_name) {
  using nlohmann::json;
  json doc;
  doc["provenance"] = json::parse(p.as_json());
  doc["npy"] = npy_name;
  doc["dtype"] = "<f8";
  doc["shape"] = {o.total_rows, npy_orbit_columns().size()};
  doc["columns"] = npy_orbit_columns();
  doc["empty"] = "NaN: a cell the CSV leaves empty (tau, periods, segment, wall, corner, indirect of the start row "
                 "n = 0; stick_wall, passed_upward_turn, stuck_theta, stuck_v of rows without sticking; phase_bits "
                 "of the start row)";
  const auto code = [](int c) { return std::to_string(c); };
  doc["codes"] = {{"event", {{code(kStartEventCode), "start"}, {code(event_code(EventKind::impact)), name(EventKind::impact)},
                             {code(event_code(EventKind::sticking)), name(EventKind::sticking)},
                             {code(event_code(EventKind::ride)), name(EventKind::ride)}}},
                  {"wall", {{"1", "up"}, {"-1", "down"}, {"0", "flat"}}},
                  {"stick_wall", {{"1", "up"}, {"-1", "down"}, {"0", "flat"}}},
                  {"indirect", {{code(flight_code(Truth::yes)), "indirect"}, {code(flight_code(Truth::no)), "direct"},
                                {code(flight_code(Truth::unknown)), "undecided"}}},
                  {"passed_upward_turn", {{"1", std::string("the ride passed an upward turn (CSV sticking ':") +
                                                    name(r.model.downward) + "')"},
                                          {"0", "it did not"}}}};
  json orbits = json::array();
  long long first = 0;
  for (size_t i = 0; i < o.outcomes.size(); ++i) {
    const OrbitOutcome& oc = o.outcomes[i];
    json e{{"orbit", i},
           {"first_row", first},
           {"rows", o.rows[i]},
           {"status", oc.undecided ? "undecided" : "completed"},
           {"steps_done", oc.steps_done}};
    if (oc.undecided) e["reason"] = oc.reason;
    if (oc.phase_lost_at >= 0) e["phase_lost_at"] = oc.phase_lost_at;
    orbits.push_back(e);
    first += o.rows[i];
  }
  doc["orbits"] = orbits;
  return doc.dump(1) + "\n";
}

std::vector<OrbitOutcome> write_orbits(const OrbitRequest& r, const Provenance& p, std::ostream& out) {
  return with_scalar(r.precision, [&](auto tag) { return run<typename decltype(tag)::type>(r, p, out); });
}

}  // namespace bouncer
