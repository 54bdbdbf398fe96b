#include "bouncer/io/orbit.hpp"
#include "bouncer/base/output.hpp"

#include <iomanip>
#include <ostream>
#include <sstream>

#include "bouncer/model/impact_map.hpp"

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
  else throw InputError("format", "unknown format '" + f + "' (allowed: csv, json, table)");
  // Interval runs default to Lohner's method, as the certified commands do: the same
  // exact orbit, enclosed in sets that grow with the dynamics, not with the wrapping effect.
  r.method = r.precision.is_interval() ? EnclosureMethod::lohner : EnclosureMethod::naive;
  if (o.has("method")) {
    r.method = parse_enclosure_method("method", o.get("method"));
    if (r.method == EnclosureMethod::lohner && !r.precision.is_interval())
      throw InputError("method", "lohner needs --precision interval:BITS (got " + o.get_or("precision", "double") +
                                     "); point precisions have no enclosure method");
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

template <class T>
void put_scalar(std::vector<std::string>& row, const T& x) {
  using Tr = ScalarTraits<T>;
  if constexpr (Tr::is_interval) {
    row.push_back(Tr::lower_string(x));
    row.push_back(Tr::upper_string(x));
  } else {
    row.push_back(Tr::to_string(x));
  }
}

template <class T>
void put_empty_scalar(std::vector<std::string>& row) {
  row.emplace_back();
  if constexpr (ScalarTraits<T>::is_interval) row.emplace_back();
}

const char* direction_name(int d) { return d > 0 ? "up" : d < 0 ? "down" : "flat"; }
const char* truth_name(Truth t, const char* yes, const char* no) {
  return t == Truth::yes ? yes : t == Truth::no ? no : "undecided";
}

// Streams rows in one of the three formats.
class RowWriter {
 public:
  RowWriter(std::ostream& out, Format f, bool interval, long bits) : out_(out), f_(f), names_(header_names(interval)) {
    width_ = static_cast<int>(bits * 0.30103) + 9;
  }
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
    if (f_ == Format::json) out_ << "\n ]\n}\n";
    out_.flush();
    check();
  }
  // A stream that failed (disk full, closed pipe) ends the run at once, not after 1e10 rows.
  void check() const {
    if (!out_) throw OutputError("writing the orbit failed (disk full, or the reader closed the pipe?)");
  }

 private:
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
};

template <class T>
std::vector<std::string> start_row(const State<T>& s, size_t orbit) {
  std::vector<std::string> row{"0"};
  put_scalar(row, s.theta);
  put_scalar(row, s.v);
  row.emplace_back("start");
  put_empty_scalar<T>(row);
  for (int i = 0; i < 6; ++i) row.emplace_back();
  put_empty_scalar<T>(row);
  put_empty_scalar<T>(row);
  row.emplace_back();
  row.push_back(std::to_string(orbit));
  return row;
}

template <class T>
std::vector<std::string> step_row(long long n, const StepResult<T>& r, const Model<T>& m, size_t orbit) {
  std::vector<std::string> row{std::to_string(n)};
  put_scalar(row, r.next.theta);
  put_scalar(row, r.next.v);
  row.emplace_back(name(r.kind));
  put_scalar(row, r.tau);
  row.push_back(std::to_string(r.periods));
  row.push_back(std::to_string(r.segment));
  row.emplace_back(direction_name(m.wall.direction[r.segment]));
  row.emplace_back(r.corner ? "1" : "0");
  row.emplace_back(truth_name(r.indirect, "indirect", "direct"));
  if (r.kind == EventKind::sticking) {
    std::string s = direction_name(m.wall.direction[r.stick_segment]);
    if (r.passed_upward_turn) s += std::string(":") + name(m.downward);
    row.push_back(s);
    put_scalar(row, r.stuck_theta);
    put_scalar(row, r.stuck_v);
  } else {
    row.emplace_back();
    put_empty_scalar<T>(row);
    put_empty_scalar<T>(row);
  }
  row.push_back(std::to_string(ScalarTraits<T>::bits(r.next.theta) - r.phase_bits_lost));
  row.push_back(std::to_string(orbit));
  return row;
}

// The text sink of the orbit driver (run/orbit.hpp): each row as the writer's cells.
template <class T>
class TextSink final : public OrbitSink<T> {
 public:
  TextSink(RowWriter& w, const Model<T>& m, size_t orbit) : w_(w), m_(m), orbit_(orbit) {}
  void start(const State<T>& s) override { w_.row(start_row(s, orbit_)); }
  void row(long long n, const StepResult<T>& r) override { w_.row(step_row(n, r, m_, orbit_)); }
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

}  // namespace

std::vector<OrbitOutcome> write_orbits(const OrbitRequest& r, const Provenance& p, std::ostream& out) {
  return with_scalar(r.precision, [&](auto tag) { return run<typename decltype(tag)::type>(r, p, out); });
}

}  // namespace bouncer
