// bouncer._core: the Python module's native part. Two ways in:
//
//  * Model: the library itself. A model is built once from the CLI's option texts (the same
//    parsers and validation: io/scene.cpp model_from, parse_precision), and its methods call
//    the library's functions on it: ImpactMap<T>::step, the orbit driver (run/orbit.hpp)
//    with a sink that fills numpy arrays straight from the StepResult<T> fields (no text in
//    between for double), classify, find_periodic / search_periodic, lyapunov,
//    continue_branch, certify_sticking, certify_periodic, and the grids (run/: basin, scan,
//    bifurcation, portrait, exponent curves, read by the CLI's own request readers,
//    io/requests/). The analyses return plain dicts that the Python layer
//    (python/bouncer/_model.py) turns into dataclasses.
//  * run(words): a bouncer command line run in this process (tools/run_command.hpp: the
//    same parsing, validation and code as the command-line tool), which returns what the
//    command printed. The CLI-parity path, and the way to the commands with no typed call
//    yet (trajectory, tongues, ...).
//
// No science here: the collision law, the analyses and the certificates are the library's.
// What this file does is conversion (Python values <-> option texts and scalars), the GIL and
// interrupts. The defaults and ranges of the analysis options are the CLI's: the same
// library readers (io/options.hpp, io/requests/*.hpp) read them here and in tools/cmd_*.cpp.
//
// Interrupts: long calls run on a worker thread while the calling thread waits in slices of
// 50 ms and, between them, takes the GIL to let Python run its signal handlers
// (PyErr_CheckSignals: Ctrl-C in a notebook). When a handler raises (KeyboardInterrupt), the
// worker's cancel flag is set (base/cancel.hpp), the computation unwinds at its next check
// (output files are written all or none, so none is left half written), and the exception is
// re-raised here. Model.step holds the GIL: one step is a fraction of a microsecond in double.
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <complex>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "analysis_common.hpp"
#include "bouncer/io/options.hpp"
#include "bouncer/io/curve_figures.hpp"
#include "bouncer/io/requests/exponent_curve.hpp"
#include "bouncer/io/requests/grids.hpp"
#include "bouncer/io/requests/attractors.hpp"
#include "bouncer/io/requests/certify_periodic.hpp"
#include "bouncer/io/requests/certify_sticking.hpp"
#include "bouncer/io/chaos_certificate.hpp"
#include "bouncer/io/reports/certify_chaos.hpp"
#include "bouncer/io/requests/certify_chaos.hpp"
#include "bouncer/io/requests/continue.hpp"
#include "bouncer/io/requests/guess.hpp"
#include "bouncer/io/requests/portrait.hpp"
#include "bouncer/analysis/classify.hpp"
#include "bouncer/analysis/continuation.hpp"
#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "bouncer/base/cancel.hpp"
#include "bouncer/io/orbit.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/thread_caches.hpp"
#include "bouncer/run/orbit.hpp"
#include "bouncer/verify/border_collision.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "bouncer/verify/periodic_certify.hpp"
#include "bouncer/verify/sticking.hpp"
#include "cli_common.hpp"
#include "command_line.hpp"
#include "picture_common.hpp"
#include "run_command.hpp"

namespace py = pybind11;

namespace {

using namespace bouncer;

// ---- long calls: off the GIL, on a worker thread, Ctrl-C cancelling ------------------------

template <class F>
auto interruptible(F&& f) {
  using R = std::invoke_result_t<F&>;
  std::optional<R> result;
  std::exception_ptr failure;
  std::atomic<bool> cancel{false};
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      const MpfrThreadCaches caches;  // MPFR's per-thread caches, freed at the end
      const CancelScope cancel_scope(&cancel);
      try {
        result.emplace(f());
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(m);
      done = true;
      cv.notify_all();
    });
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(m);
        if (cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) break;
      }
      if (interrupted) continue;  // cancelled: wait for the computation to unwind
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {  // a handler raised; the error stays set until we return
        interrupted = true;
        cancel.store(true);
      }
    }
    worker.join();
  }
  if (interrupted) throw py::error_already_set();
  if (failure) std::rethrow_exception(failure);
  return std::move(*result);
}

// ---- the CLI-parity path ------------------------------------------------------------------

const char* kind_name(cli::CommandOutcome::Kind k) {
  using K = cli::CommandOutcome::Kind;
  switch (k) {
    case K::ok: return "ok";
    case K::help: return "help";
    case K::input: return "input";
    case K::output: return "output";
    case K::internal: return "internal";
    case K::cancelled: return "cancelled";
  }
  return "internal";
}

py::dict run(const std::vector<std::string>& words) {
  cli::CommandCapture capture;
  const cli::CommandOutcome outcome = interruptible([&] {
    const cli::CaptureScope capture_scope(&capture);
    return cli::run_command(words, false);
  });
  py::dict r;
  r["status"] = outcome.status;
  r["kind"] = kind_name(outcome.kind);
  r["message"] = outcome.message;
  r["unknown_option"] = outcome.unknown_option;
  r["out"] = py::bytes(capture.out.str());
  r["csv"] = py::bytes(capture.csv);
  return r;
}

// ---- Python values -> option texts ----------------------------------------------------------

// The options of one call, as the CLI's Options (long option names, texts). Python passes
// each value as a list of texts (one text, or two for a pair such as guess).
using Texts = std::map<std::string, std::vector<std::string>>;

// A value with a NUL byte is refused as run_command refuses it (a C string would cut it),
// with the whole value in the message (escaped by one_line, as every message of
// run_command is): raised here, because InputError::what() would end at the NUL.
[[noreturn]] void refuse_nul(const std::string& field, const std::string& value) {
  throw py::value_error(cli::one_line(field + ": the value '" + value + "' contains a NUL byte"));
}

Options options_of(const Texts& texts) {
  Options o;
  for (const auto& [key, values] : texts) {
    for (const std::string& v : values)
      if (v.find('\0') != std::string::npos) refuse_nul(key, v);
    o.set(key, values);
  }
  return o;
}

// The exact decimal text of a Python number or decimal string (floats: the exact decimal of
// their binary value, as str(decimal.Decimal(x)) writes it; non-finite floats as repr, which
// the parser refuses with bouncer's message).
std::string text_of(py::handle x, const char* field) {
  if (py::isinstance<py::str>(x)) {
    std::string s = x.cast<std::string>();
    if (s.find('\0') != std::string::npos) refuse_nul(field, s);
    return s;
  }
  if (py::isinstance<py::bool_>(x))
    throw py::type_error(std::string(field) + ": expected a number or a decimal string, got bool");
  if (PyFloat_Check(x.ptr())) {
    const double d = PyFloat_AsDouble(x.ptr());
    if (!std::isfinite(d)) return py::repr(x).cast<std::string>();
    return py::str(py::module_::import("decimal").attr("Decimal")(d)).cast<std::string>();
  }
  if (PyIndex_Check(x.ptr())) return py::str(py::reinterpret_steal<py::object>(PyNumber_Index(x.ptr()))).cast<std::string>();
  if (py::isinstance(x, py::module_::import("decimal").attr("Decimal"))) return py::str(x).cast<std::string>();
  throw py::type_error(std::string(field) + ": expected a number or a decimal string, got " +
                       py::str(py::type::handle_of(x).attr("__name__")).cast<std::string>());
}

// ---- scalars -> Python ------------------------------------------------------------------------

// An interval's ends as exact decimal texts, rounded outward (ScalarTraits::lower_string and
// upper_string): they enclose the exact value.
struct Interval {
  std::string lo, hi;
};

double outward_double(const std::string& text, bool up) {
  const std::optional<Decimal> parsed = Decimal::parse(text);
  if (!parsed) return std::strtod(text.c_str(), nullptr);  // inf, -inf, nan
  const mpq_class& q = parsed->value();
  double d = q.get_d();  // truncated toward zero
  if (!up && mpq_class(d) > q) d = std::nextafter(d, -std::numeric_limits<double>::infinity());
  if (up && mpq_class(d) < q) d = std::nextafter(d, std::numeric_limits<double>::infinity());
  return d;
}

py::object interval_to_mpmath(const Interval& x, std::optional<long> bits) {
  const py::module_ mpmath = py::module_::import("mpmath");
  const py::object libmp = mpmath.attr("libmp");
  const long prec = bits ? *bits : std::max(53L, mpmath.attr("mp").attr("prec").cast<long>());
  const py::object lo = mpmath.attr("mpf")(libmp.attr("from_str")(x.lo, prec, libmp.attr("round_floor")));
  const py::object hi = mpmath.attr("mpf")(libmp.attr("from_str")(x.hi, prec, libmp.attr("round_ceiling")));
  return mpmath.attr("mpi")(lo, hi);
}

// double -> float; the other point types -> their round-trip decimal text (str, as the CLI
// prints them); interval types -> Interval.
template <class T>
py::object scalar(const T& x) {
  using Tr = ScalarTraits<T>;
  if constexpr (std::is_same_v<T, double>) {
    return py::float_(x);
  } else if constexpr (Tr::is_interval) {
    return py::cast(Interval{Tr::lower_string(x), Tr::upper_string(x)});
  } else {
    return py::str(Tr::to_string(x));
  }
}

py::object interval_of(const Enclosure& e) { return py::cast(Interval{e.lo, e.hi}); }

// numpy arrays that own a std::vector's buffer (no copy).
template <class X>
py::array numpy_of(std::vector<X>&& v, std::vector<py::ssize_t> shape, py::dtype dtype = py::dtype::of<X>()) {
  auto* heap = new std::vector<X>(std::move(v));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<X>*>(p); });
  return py::array(dtype, std::move(shape), heap->data(), owner);
}

py::object str_array(const std::vector<std::string>& v, std::vector<py::ssize_t> shape) {
  py::list items;
  for (const std::string& s : v) items.append(py::str(s));
  return py::module_::import("numpy").attr("array")(items, py::arg("dtype") = "str").attr("reshape")(py::tuple(py::cast(shape)));
}

// One real column of an orbit: float64 in double and interval:double ((N, 2) [lo, hi] for
// the interval), decimal texts (str) for the other types, NaN or "" where a row has none.
template <class T>
struct RealColumn {
  using Tr = ScalarTraits<T>;
  static constexpr bool doubles = std::is_same_v<T, double> || std::is_same_v<T, DoubleInterval>;
  std::vector<std::conditional_t<doubles, double, std::string>> data;

  void reserve(size_t n) { data.reserve(Tr::is_interval ? 2 * n : n); }
  void push(const T& x) {
    if constexpr (std::is_same_v<T, double>) {
      data.push_back(x);
    } else if constexpr (std::is_same_v<T, DoubleInterval>) {
      data.push_back(x.lower());
      data.push_back(x.upper());
    } else if constexpr (Tr::is_interval) {
      data.push_back(Tr::lower_string(x));
      data.push_back(Tr::upper_string(x));
    } else {
      data.push_back(Tr::to_string(x));
    }
  }
  void push_none() {
    for (int i = 0; i < (Tr::is_interval ? 2 : 1); ++i) {
      if constexpr (doubles) data.push_back(std::numeric_limits<double>::quiet_NaN());
      else data.emplace_back();
    }
  }
  py::object numpy(py::ssize_t rows) && {
    std::vector<py::ssize_t> shape{rows};
    if (Tr::is_interval) shape.push_back(2);
    if constexpr (doubles) return numpy_of(std::move(data), shape);
    else return str_array(data, shape);
  }
};

// ---- Step and Orbit -----------------------------------------------------------------------------

// One step's result, the CLI's orbit row for it (io/orbit.cpp), as a struct sequence
// (C's named tuple, like os.stat_result): the tuple (theta, v), so that
// `theta, v = m.step(theta, v)` iterates the map, and the other fields as attributes. A
// struct sequence is built and read at C speed: a pybind11 class took 0.6 us to build and
// 0.26 us per attribute read, most of Model.step's time.
PyStructSequence_Field kStepFields[] = {
    {"theta", "Phase of the next impact (or release), in [0, 1)"},
    {"v", "Velocity just after it"},
    {"tau", "Time from the start state to the next one"},
    {"event", "impact | sticking | ride"},
    {"periods", "Whole wall periods begun during the step"},
    {"segment", "Wall segment of the last contact"},
    {"wall", "Direction of the wall at the impact: up | down | flat (its segment's; on the sine wall the sign of its velocity)"},
    {"corner", "The last impact was exactly at a wall corner"},
    {"indirect", "The flight rose above the wall's top (None: undecided)"},
    {"stick_segment", "Sticking only (else None): segment of the collision that stuck"},
    {"stuck_theta", "Sticking only (else None): phase where the collapse completed"},
    {"stuck_v", "Sticking only (else None): velocity there (the wall's)"},
    {"passed_upward_turn", "Sticking only: the ride passed an upward turn (the downward-sticking convention applied)"},
    {"phase_bits", "Correct bits of theta left after long flights, at best"},
    {nullptr, nullptr}};
PyStructSequence_Desc kStepDesc{
    "bouncer.Step",
    "One step of the impact map: the tuple (theta, v) of the state after it, and what happened as attributes "
    "(the CLI's orbit row). Real numbers are float in double, decimal texts (str) in long, dd, quad and "
    "mpfr:BITS, Interval in interval precisions.",
    kStepFields, 2};
PyTypeObject* step_type = nullptr;  // made at import, never freed

template <class T>
py::object step_of(const StepResult<T>& r, const Model<T>& m) {
  py::object s = py::reinterpret_steal<py::object>(PyStructSequence_New(step_type));
  if (!s) throw py::error_already_set();
  int i = 0;
  auto put = [&](py::object x) { PyStructSequence_SetItem(s.ptr(), i++, x.release().ptr()); };
  put(scalar(r.next.theta));
  put(scalar(r.next.v));
  put(scalar(r.tau));
  put(py::str(name(r.kind)));
  put(py::int_(r.periods));
  put(py::int_(r.segment));
  put(py::str(direction_name(contact_direction(m, r))));
  put(py::bool_(r.corner));
  put(r.indirect == Truth::yes ? py::object(py::bool_(true))
      : r.indirect == Truth::no ? py::object(py::bool_(false))
                                : py::object(py::none()));
  const bool stuck = r.kind == EventKind::sticking;
  put(stuck ? py::object(py::int_(r.stick_segment)) : py::object(py::none()));
  put(stuck ? scalar(r.stuck_theta) : py::object(py::none()));
  put(stuck ? scalar(r.stuck_v) : py::object(py::none()));
  put(py::bool_(stuck && r.passed_upward_turn));
  put(py::int_(ScalarTraits<T>::bits(r.next.theta) - r.phase_bits_lost));
  return s;
}

// Codes of Orbit.event (bouncer.EVENTS) and Orbit.indirect: run/orbit.hpp's, as int8.
std::int8_t event_int8(EventKind k) { return static_cast<std::int8_t>(event_code(k)); }
constexpr std::int8_t kStartEvent = kStartEventCode;

struct Orbit {
  py::object n, theta, v, event, tau, periods, segment, wall, corner, indirect, stick_segment, stuck_theta, stuck_v,
      passed_upward_turn, phase_bits;
  std::string status = "completed";  // completed | undecided
  long long steps_done = 0;
  std::string reason;                // why undecided
  py::object phase_lost_at, lohner_fallbacks;
  std::string precision;
  py::ssize_t rows = 0;
};

template <class T>
struct OrbitColumns {
  std::vector<long long> n, periods;
  RealColumn<T> theta, v, tau, stuck_theta, stuck_v;
  std::vector<std::int8_t> event, wall, indirect;
  std::vector<std::int32_t> segment, stick_segment, phase_bits;
  std::vector<std::uint8_t> corner, passed;
  OrbitOutcome outcome;

  void reserve(size_t rows) {
    for (auto* c : {&n, &periods}) c->reserve(rows);
    for (auto* c : {&theta, &v, &tau, &stuck_theta, &stuck_v}) c->reserve(rows);
    for (auto* c : {&event, &wall, &indirect}) c->reserve(rows);
    for (auto* c : {&segment, &stick_segment, &phase_bits}) c->reserve(rows);
    for (auto* c : {&corner, &passed}) c->reserve(rows);
  }
  void start(const State<T>& s) {
    n.push_back(0);
    theta.push(s.theta);
    v.push(s.v);
    event.push_back(kStartEvent);
    tau.push_none();
    periods.push_back(-1);
    segment.push_back(-1);
    wall.push_back(0);
    corner.push_back(0);
    indirect.push_back(0);
    stick_segment.push_back(-1);
    stuck_theta.push_none();
    stuck_v.push_none();
    passed.push_back(0);
    phase_bits.push_back(-1);
  }
  void row(long long k, const StepResult<T>& r, const Model<T>& m) {
    n.push_back(k);
    theta.push(r.next.theta);
    v.push(r.next.v);
    event.push_back(event_int8(r.kind));
    tau.push(r.tau);
    periods.push_back(r.periods);
    segment.push_back(r.segment);
    wall.push_back(static_cast<std::int8_t>(contact_direction(m, r)));
    corner.push_back(r.corner ? 1 : 0);
    indirect.push_back(static_cast<std::int8_t>(flight_code(r.indirect)));
    const bool stuck = r.kind == EventKind::sticking;
    stick_segment.push_back(stuck ? r.stick_segment : -1);
    if (stuck) {
      stuck_theta.push(r.stuck_theta);
      stuck_v.push(r.stuck_v);
    } else {
      stuck_theta.push_none();
      stuck_v.push_none();
    }
    passed.push_back(stuck && r.passed_upward_turn ? 1 : 0);
    phase_bits.push_back(static_cast<std::int32_t>(ScalarTraits<T>::bits(r.next.theta) - r.phase_bits_lost));
  }
  Orbit result(const Precision& p) && {
    Orbit o;
    o.rows = static_cast<py::ssize_t>(n.size());
    const std::vector<py::ssize_t> shape{o.rows};
    o.n = numpy_of(std::move(n), shape);
    o.theta = std::move(theta).numpy(o.rows);
    o.v = std::move(v).numpy(o.rows);
    o.event = numpy_of(std::move(event), shape);
    o.tau = std::move(tau).numpy(o.rows);
    o.periods = numpy_of(std::move(periods), shape);
    o.segment = numpy_of(std::move(segment), shape);
    o.wall = numpy_of(std::move(wall), shape);
    o.corner = numpy_of(std::move(corner), shape, py::dtype("bool"));
    o.indirect = numpy_of(std::move(indirect), shape);
    o.stick_segment = numpy_of(std::move(stick_segment), shape);
    o.stuck_theta = std::move(stuck_theta).numpy(o.rows);
    o.stuck_v = std::move(stuck_v).numpy(o.rows);
    o.passed_upward_turn = numpy_of(std::move(passed), shape, py::dtype("bool"));
    o.phase_bits = numpy_of(std::move(phase_bits), shape);
    o.status = outcome.undecided ? "undecided" : "completed";
    o.steps_done = outcome.steps_done;
    o.reason = outcome.reason;
    o.phase_lost_at = outcome.phase_lost_at >= 0 ? py::object(py::int_(outcome.phase_lost_at)) : py::object(py::none());
    o.lohner_fallbacks = outcome.fallbacks >= 0 ? py::object(py::int_(outcome.fallbacks)) : py::object(py::none());
    o.precision = p.text();
    return o;
  }
};

// The numpy sink of the orbit driver (run/orbit.hpp follow_orbit).
template <class T>
class ColumnSink final : public OrbitSink<T> {
 public:
  ColumnSink(OrbitColumns<T>& c, const Model<T>& m) : c_(c), m_(m) {}
  void start(const State<T>& s) override { c_.start(s); }
  void row(long long n, const StepResult<T>& r) override { c_.row(n, r, m_); }

 private:
  OrbitColumns<T>& c_;
  const Model<T>& m_;
};

// More rows than this is refused (as `bouncer orbit` refuses to print more than 1e8 rows
// without --force): about 8 GB of arrays.
constexpr double kMaxOrbitRows = 1e8;

// ---- the model in one scalar type -------------------------------------------------------------

class Stepper {
 public:
  virtual ~Stepper() = default;
  virtual py::object step(py::handle theta, py::handle v) const = 0;
  virtual Orbit orbit(const OrbitRequest& req) const = 0;
};

template <class T>
class TypedStepper final : public Stepper {
  using Tr = ScalarTraits<T>;

 public:
  TypedStepper(const ModelSpec& spec, const Precision& p) : spec_(spec), prec_(p), map_(make_model<T>(spec, p.bits)) {
    if constexpr (std::is_same_v<T, double>) prepare_fast_check();
  }

  py::object step(py::handle theta, py::handle v) const override {
    return step_of(map_.step(start(theta, v)), map_.model());
  }

  // The orbit driver of `bouncer orbit` (run/orbit.hpp follow_orbit), into arrays: the same
  // start (make_state with the knot), the same steps, Lohner's method for interval runs
  // unless naive is asked for, and an undecided step ends the run (status "undecided").
  Orbit orbit(const OrbitRequest& req) const override {
    const State<T> s0 = make_state<T>(map_.model(), req.initial.at(0));
    OrbitColumns<T> cols = interruptible([&] {
      OrbitColumns<T> c;
      c.reserve(static_cast<size_t>(req.steps / req.every) + 2);
      ColumnSink<T> sink(c, map_.model());
      c.outcome = follow_orbit(map_, s0, orbit_steps(req), sink);
      return c;
    });
    return std::move(cols).result(prec_);
  }

 private:
  // A start from Python values, validated as the CLI validates --theta and --v
  // (model/spec.hpp validate: theta in [0, 1), v at least the wall's velocity at theta,
  // v <= 1e15), converted as `bouncer orbit` converts them (make_state, knots recognised).
  State<T> start(py::handle theta, py::handle v) const {
    if constexpr (std::is_same_v<T, double>) {
      double th = 0, vv = 0;
      if (as_double(theta, th) && as_double(v, vv) && certainly_valid(th, vv)) {
        State<double> s{th, vv};
        for (size_t k = 0; k < knot_.size(); ++k)
          if (knot_exact_[k] && th == knot_[k]) s.knot = static_cast<int>(k);
        return s;
      }
    }
    InitialCondition ic{parse_decimal("theta", text_of(theta, "theta")), parse_decimal("v", text_of(v, "v"))};
    validate(spec_, ic, "theta", "v");
    return make_state<T>(map_.model(), ic);
  }

  // Fast path of Model.step in double: a Python float is a double, and its exact decimal
  // rounds to itself, so the state is (theta, v) as given. The exact validation (above) is
  // skipped only when these double comparisons prove that it passes: 0 <= theta < 1,
  // v <= 1e15, and theta strictly inside a segment j (between doubles that bound its exact
  // knots) with v at least the exact wall velocity u_j rounded up. Anything else (a knot,
  // a start near the wall's velocity, NaN) takes the exact path and its messages.
  static bool as_double(py::handle x, double& out) {
    if (PyFloat_Check(x.ptr())) {
      out = PyFloat_AS_DOUBLE(x.ptr());
      return true;
    }
    if (PyLong_CheckExact(x.ptr())) {
      int overflow = 0;
      const long long n = PyLong_AsLongLongAndOverflow(x.ptr(), &overflow);
      if (overflow || n > (1LL << 53) || n < -(1LL << 53)) return false;
      out = static_cast<double>(n);
      return true;
    }
    return false;
  }
  void prepare_fast_check() {
    const auto& knots = spec_.wall.knots;
    for (size_t j = 0; j < knots.size(); ++j) {
      const mpq_class& q = knots[j].value();
      knot_.push_back(q.get_d());
      knot_exact_.push_back(mpq_class(knot_.back()) == q);
      knot_below_.push_back(outward_double(knots[j].text(), false));
      knot_above_.push_back(outward_double(knots[j].text(), true));
      const mpq_class u = wall_velocity_exact(spec_.wall, q);
      double up = u.get_d();
      if (mpq_class(up) < u) up = std::nextafter(up, std::numeric_limits<double>::infinity());
      velocity_up_.push_back(up);
    }
  }
  bool certainly_valid(double theta, double v) const {
    if (knot_below_.empty()) return false;  // the sine wall: no knots, the exact path decides
    if (!(theta >= 0 && theta < 1 && v <= 1e15)) return false;  // also NaN
    size_t j = 0;
    for (size_t k = 1; k < knot_below_.size(); ++k)
      if (knot_below_[k] <= theta) j = k;
    const bool after_start = theta >= knot_above_[j];
    const bool before_end = j + 1 < knot_below_.size() ? theta < knot_below_[j + 1] : true;
    return after_start && before_end && v >= velocity_up_[j];
  }

  ModelSpec spec_;
  Precision prec_;
  ImpactMap<T> map_;
  std::vector<double> knot_, knot_below_, knot_above_, velocity_up_;
  std::vector<bool> knot_exact_;
};

std::unique_ptr<Stepper> make_stepper(const ModelSpec& spec, const Precision& p) {
  return with_scalar(p, [&](auto tag) -> std::unique_ptr<Stepper> {
    return std::make_unique<TypedStepper<typename decltype(tag)::type>>(spec, p);
  });
}

// ---- the analyses: the CLI's option handling, the library's functions --------------------------

py::list attempts_of(const std::vector<Attempt>& attempts) {
  py::list out;
  for (const Attempt& t : attempts) {
    py::dict a;
    a["scalar"] = t.scalar;
    a["bits"] = t.bits;
    a["decided"] = t.decided;
    a["steps"] = t.steps;
    a["reason"] = t.reason;
    a["seconds"] = t.seconds;
    out.append(a);
  }
  return out;
}

template <class T>
py::tuple pair_of(const T& x, const T& y) {
  return py::make_tuple(scalar(x), scalar(y));
}

// ---- grids (run/): typed results -> numpy -------------------------------------------------

// threads (default: all cores) for the library's grid calls; no progress bar from Python.
GridOptions grid_run_options(const Options& o) {
  GridOptions g;
  g.threads = static_cast<unsigned>(integer_from(o, "threads", 1, 4096, 0));
  return g;
}

// The axes of a grid: float64 arrays (the nearest doubles) and the numbers' own digits.
void put_axes(py::dict& d, const std::string& x, const std::vector<Number>& xs, const std::string& y,
              const std::vector<Number>& ys) {
  for (const auto& [key, axis] : {std::pair{x, &xs}, std::pair{y, &ys}}) {
    py::array_t<double> values(static_cast<py::ssize_t>(axis->size()));
    py::list digits;
    for (size_t i = 0; i < axis->size(); ++i) {
      values.mutable_at(static_cast<py::ssize_t>(i)) = (*axis)[i].value;
      digits.append((*axis)[i].digits);
    }
    d[py::str(key)] = values;
    d[py::str(key + "_text")] = digits;
  }
  d["shape"] = py::make_tuple(ys.size(), xs.size());
}

// Class names as int8 codes into `names` (reshaped to the grid by the Python layer).
template <class Cells, class Name>
py::array_t<std::int8_t> codes_of(const Cells& cells, Name&& name_of, std::vector<std::string>& names) {
  py::array_t<std::int8_t> codes(static_cast<py::ssize_t>(cells.size()));
  for (size_t i = 0; i < cells.size(); ++i) {
    const std::string n = name_of(cells[i]);
    auto it = std::find(names.begin(), names.end(), n);
    if (it == names.end()) it = names.insert(names.end(), n);
    codes.mutable_at(static_cast<py::ssize_t>(i)) = static_cast<std::int8_t>(it - names.begin());
  }
  return codes;
}

template <class Cells, class F>
py::array_t<std::int64_t> ints_of(const Cells& cells, F&& f) {
  py::array_t<std::int64_t> a(static_cast<py::ssize_t>(cells.size()));
  for (size_t i = 0; i < cells.size(); ++i) a.mutable_at(static_cast<py::ssize_t>(i)) = f(cells[i]);
  return a;
}

void put_attractors(py::dict& d, const std::vector<AttractorCell>& cells) {
  std::vector<std::string> names;
  d["class_"] = codes_of(cells, [](const AttractorCell& c) { return name(c.cls); }, names);
  d["period"] = ints_of(cells, [](const AttractorCell& c) { return c.period; });
  d["class_names"] = names;
}

// --confirm (run/cells.hpp GridConfirm): each start's verdict ("unchecked" outside the
// sample), the class and period at the check's first precision, and what differs.
void put_confirm(py::dict& d, const std::vector<AttractorCell>& cells, const GridConfirm& g) {
  std::vector<std::string> verdicts, names = py::cast<std::vector<std::string>>(d["class_names"]);
  d["confirm"] = codes_of(cells, [](const AttractorCell& c) { return c.confirm ? std::string(name(*c.confirm)) : std::string("unchecked"); }, verdicts);
  d["confirm_names"] = verdicts;
  d["check_class"] = codes_of(cells, [](const AttractorCell& c) { return name(c.check_cls); }, names);
  d["check_period"] = ints_of(cells, [](const AttractorCell& c) { return c.check_period; });
  d["class_names"] = names;
  // What differs where run and check disagree ("accelerator period 33 vs 11"), "" elsewhere.
  std::vector<std::string> differs;
  differs.reserve(cells.size());
  for (const AttractorCell& c : cells) differs.push_back(c.differs_in);
  d["differs_in"] = differs;
  d["confirm_bits"] = g.bits;
}

void put_certified(py::dict& d, const std::vector<CertifiedCell>& cells) {
  std::vector<std::string> names;
  d["class_"] = codes_of(cells, [](const CertifiedCell& c) { return name(c.cls); }, names);
  d["double_class"] = codes_of(cells, [](const CertifiedCell& c) { return name(c.double_class); }, names);
  d["agreement"] = codes_of(cells, [](const CertifiedCell& c) { return name(c.agreement); }, names);
  d["period"] = ints_of(cells, [](const CertifiedCell& c) { return c.period; });
  d["certified_steps"] = ints_of(cells, [](const CertifiedCell& c) { return c.certified_steps; });
  d["double_period"] = ints_of(cells, [](const CertifiedCell& c) { return c.double_period; });
  py::list scalars;
  for (const CertifiedCell& c : cells) scalars.append(c.scalar);
  d["scalar"] = scalars;
  d["class_names"] = names;
}

py::dict certified_dict(const std::string& exact_value, const CertifiedCell& c) {
  py::dict d;
  d["value"] = exact_value;
  d["class_"] = name(c.cls);
  d["period"] = c.period;
  d["certified_steps"] = c.certified_steps;
  d["scalar"] = c.scalar;
  d["double_class"] = name(c.double_class);
  d["double_period"] = c.double_period;
  d["agreement"] = name(c.agreement);
  return d;
}

class ModelCore {
 public:
  explicit ModelCore(const Texts& texts) : options_(options_of(texts)) {
    for (const auto& [k, v] : options_.values)
      if (!model_keys().count(k) && k != "precision") throw InputError(k, "is not an option of a model");
    spec_ = model_from(options_);
    precision_ = precision_from(options_);
    stepper_ = make_stepper(spec_, precision_);
  }

  py::object step(py::handle theta, py::handle v) const { return stepper_->step(theta, v); }

  // `bouncer orbit`'s request (io/orbit.cpp orbit_request: the same ranges, defaults and
  // messages) for this model and one start.
  Orbit orbit(const Texts& texts) const {
    Options o = with_model(texts);
    const OrbitRequest req = orbit_request(o);
    const double rows = static_cast<double>(req.steps / req.every) + 2;
    if (rows > kMaxOrbitRows)
      throw InputError("steps", "would return " + std::to_string(static_cast<long long>(rows)) +
                                    " rows (more than 1e8, about 8 GB of arrays): raise every");
    return stepper_->orbit(req);
  }

  // bouncer classify (tools/cmd_classify.cpp).
  py::dict classify(const Texts& texts) const {
    const Options o = with_model(texts);
    const InitialCondition ic = start_from(o, spec_);
    const ClassifyOptions co = classify_options_from(o);
    const Precision prec = analysis_precision(o, "classify");
    return with_point_scalar(prec, [&](auto tag) {
      using T = typename decltype(tag)::type;
      const Classification c = interruptible([&] {
        const ImpactMap<T> map(make_model<T>(spec_, prec.bits));
        return bouncer::classify<T>(map, make_state<T>(ic, prec.bits), co);
      });
      py::dict d;
      d["class_"] = name(c.cls);
      d["period"] = c.period;
      d["lambda_"] = c.lambda;
      d["evidence"] = c.evidence;
      const bool unbounded = c.cls == OrbitClass::unbounded;
      d["growth_alpha"] = unbounded ? py::object(py::float_(c.alpha)) : py::object(py::none());
      d["growth_per_step"] = unbounded ? py::object(py::float_(c.growth_rate)) : py::object(py::none());
      d["phase_branches"] = unbounded ? py::object(py::int_(c.branches)) : py::object(py::none());
      d["accelerator_period"] = unbounded ? py::object(py::int_(c.accel_period)) : py::object(py::none());
      d["accelerator_gain"] = unbounded ? py::object(py::float_(c.accel_gain)) : py::object(py::none());
      d["growth_kind"] = unbounded ? py::object(py::str(c.growth_kind)) : py::object(py::none());
      const bool transient = c.cls == OrbitClass::transient_chaos;
      d["settled_class"] = transient ? py::object(py::str(name(c.settled_class))) : py::object(py::none());
      d["settled_at"] = transient ? py::object(py::int_(c.settled_at)) : py::object(py::none());
      d["transient"] = co.transient;
      d["steps"] = co.steps;
      d["max_period"] = co.max_period;
      d["recheck_factor"] = co.recheck_factor;
      return d;
    });
  }

  // bouncer lyapunov without --vary (tools/cmd_lyapunov.cpp: its ranges and defaults).
  py::dict lyapunov(const Texts& texts) const {
    const Options o = with_model(texts);
    const InitialCondition ic = start_from(o, spec_);
    const LyapunovOptions lo = lyapunov_options_from(o);
    const Precision prec = analysis_precision(o, "lyapunov");
    return with_point_scalar(prec, [&](auto tag) {
      using T = typename decltype(tag)::type;
      const LyapunovResult r = interruptible([&] {
        return bouncer::lyapunov(make_model<T>(spec_, prec.bits), make_state<T>(ic, prec.bits), lo);
      });
      py::dict d;
      d["lambda_"] = r.lambda;
      d["stderr"] = r.stderr_;
      d["steps"] = r.steps;
      d["transient"] = lo.transient;
      d["blocks"] = r.blocks;
      d["contracted"] = r.contracted;
      d["unbounded"] = r.unbounded;
      d["growth_alpha"] = r.alpha;
      d["v_max"] = r.v_max;
      d["undecided"] = r.undecided;
      d["note"] = r.note;
      return d;
    });
  }

  // bouncer periodic (tools/cmd_periodic.cpp: its ranges and defaults).
  py::dict periodic(const Texts& texts) const {
    const Options o = with_model(texts);
    const long q = periodic_period_from(o);
    const NewtonOptions no = periodic_newton_from(o);
    const std::optional<InitialCondition> guess = guess_from(o, spec_);
    const Precision prec = analysis_precision(o, "periodic");
    return with_point_scalar(prec, [&](auto tag) {
      using T = typename decltype(tag)::type;
      const PeriodicOrbit<T> p = interruptible([&] {
        const Model<T> m = make_model<T>(spec_, prec.bits);
        return guess ? find_periodic(m, q, make_state<T>(*guess, prec.bits), no) : search_periodic(m, q, no);
      });
      return periodic_dict(p, q);
    });
  }

  // bouncer continue without --out (its request: io/requests/continue.hpp); with certify,
  // the same proofs as `continue --certify` (verify/border_collision.hpp).
  py::dict continue_branch(const Texts& texts) const {
    const ContinueRequest r = continue_request(with_model(texts));
    return with_point_scalar(r.precision, [&](auto tag) {
      using T = typename decltype(tag)::type;
      using Tr = ScalarTraits<T>;
      const long bits = r.precision.bits;
      const Model<T> m = make_model<T>(spec_, bits);
      const Branch<T> b = interruptible([&] {
        const T tlo = Tr::from_decimal(r.lo.text(), bits), thi = Tr::from_decimal(r.hi.text(), bits);
        Branch<T> br = bouncer::continue_branch(m, r.vary, r.period, make_state<T>(r.guess, bits), tlo, thi, r.opt);
        // The digits of each end that an error estimate backs, as `continue` (analysis/end_estimate.hpp).
        if (br.started) estimate_end_accuracy(spec_, br, r.opt);
        return br;
      });
      if (!b.started) throw InputError("guess", b.note);
      py::dict d = branch_dict(b, m, name(r.vary));
      if (r.certify) {
        const CertifiedBranchEnds cert = interruptible([&] {
          CertifiedBranchEnds x = certify_branch_ends(r.model, r.vary, r.period, b, bits);
          certify_smooth_events(r.model, r.vary, r.period, b, bits, x);
          return x;
        });
        for (const bool high : {false, true}) {
          py::dict end = d[high ? "high" : "low"];
          const auto& border = high ? cert.high : cert.low;
          const auto& fold = high ? cert.high_smooth : cert.low_smooth;
          end["certified"] = border ? border_dict(*border) : fold ? smooth_dict(*fold) : py::object(py::none());
        }
        py::list bif = d["bifurcations"];
        for (size_t i = 0; i < cert.bifurcations.size() && i < bif.size(); ++i)
          bif[i].cast<py::dict>()["certified"] = smooth_dict(cert.bifurcations[i]);
      }
      return d;
    });
  }

  // A border end's proofs (continue --certify): the two-sided enclosure of a* and the
  // one-sided bound from the branch side, as the CLI's JSON `certified` (io/reports/continue.cpp).
  static py::dict border_dict(const CertifiedBranchEnd& c) {
    const BorderCollisionCertificate& t = c.two_sided;
    py::dict d;
    d["kind"] = "border";
    d["certified"] = t.certified;
    d["bits"] = t.bits;
    d["enclosure"] = t.certified ? interval_of(t.parameter) : py::object(py::none());
    d["width"] = t.certified ? py::object(py::float_(t.width)) : py::object(py::none());
    d["margin"] = name(t.margin);
    d["margin_text"] = t.margin_text;
    d["events"] = t.events;
    d["formulation"] = t.certified ? py::object(py::str(t.shooting ? "shooting" : "composed")) : py::object(py::none());
    d["bracket_contains"] = c.bracket_contains;
    d["statement"] = t.statement;
    d["reason"] = t.reason;
    d["one_sided_certified"] = c.certificate.certified;
    d["one_sided_bound"] = c.certificate.certified ? py::object(py::str(exact_decimal(c.certificate.bound))) : py::object(py::none());
    return d;
  }

  // A period doubling's or fold's certificate (certify_period_doubling, certify_fold).
  static py::dict smooth_dict(const PeriodDoublingCertificate& c) {
    py::dict d;
    d["kind"] = "smooth";
    d["certified"] = c.certified;
    d["bits"] = c.bits;
    d["enclosure"] = c.certified ? interval_of(c.parameter) : py::object(py::none());
    d["width"] = c.certified ? py::object(py::float_(c.width)) : py::object(py::none());
    d["other_multiplier"] = c.certified ? interval_of(c.other) : py::object(py::none());
    d["events"] = c.events;
    d["statement"] = c.statement;
    d["reason"] = c.reason;
    return d;
  }

  // bouncer certify-chaos (its request: io/requests/certify_chaos.hpp): the horseshoe proved
  // with MPFI and, when proved, its certificate replayed in Arb.
  py::dict certify_chaos(const Texts& texts) const {
    const CertifyChaosRequest req = certify_chaos_request(with_model(texts));
    const ChaosSearchResult r = interruptible([&] { return bouncer::certify_chaos(req.model, req.search); });
    std::optional<ReplayResult> replay;
    if (r.proved) replay = replay_certificate(r.certificate, req.replay_bits);
    py::dict d;
    d["certified"] = r.proved && replay && replay->valid;
    d["statement"] = chaos_statement(r, replay);
    d["bound"] = r.proved ? py::object(py::str(r.entropy.bound)) : py::object(py::none());
    d["bound_double"] = r.proved ? py::object(py::float_(r.entropy.bound_double)) : py::object(py::none());
    d["quotient"] = r.proved ? py::object(py::str(r.entropy.quotient.get_str())) : py::object(py::none());
    d["k"] = r.certificate.k;
    d["hsets"] = r.certificate.sets.size();
    if (r.orbit.period) {
      py::dict saddle;
      saddle["period"] = r.orbit.period;
      saddle["theta"] = r.orbit.theta;
      saddle["v"] = r.orbit.v;
      saddle["lambda_u"] = r.orbit.lambda_u;
      saddle["lambda_s"] = r.orbit.lambda_s;
      d["saddle"] = saddle;
    } else {
      d["saddle"] = py::none();
    }
    d["replay_valid"] = replay ? py::object(py::bool_(replay->valid)) : py::object(py::none());
    d["certificate"] = r.proved ? py::object(py::str(certificate_json(r.certificate))) : py::object(py::none());
    d["seconds"] = r.search_seconds + r.check_seconds;
    return d;
  }

  // bouncer certify-sticking without --a-range (its request: io/requests/certify_sticking.hpp).
  py::dict certify_sticking(const Texts& texts) const {
    const StickingQuestion q = certify_sticking_request(with_model(texts)).question;
    const auto [c, plain] = interruptible([&] {
      StickingCertificate cert = bouncer::certify_sticking(q);
      PlainSticking d = plain_sticking_period<double>(q.model, q.start, 53, q.max_steps, q.from_release);
      return std::make_pair(std::move(cert), d);
    });
    py::dict d;
    d["certified"] = c.certified;
    d["outcome"] = name(c.outcome);
    d["period"] = c.period ? py::object(py::int_(*c.period)) : py::object(py::none());
    d["scalar"] = c.scalar.empty() ? py::object(py::none()) : py::object(py::str(c.scalar));
    d["bits"] = c.bits;
    d["steps_checked"] = c.steps_checked;
    d["statement"] = describe(c, q.max_steps);
    d["reason"] = c.reason;
    d["double_period"] = plain.period ? py::object(py::int_(*plain.period)) : py::object(py::none());
    if (c.attractor) {
      py::dict a;
      a["period"] = c.attractor->period;
      a["iterate"] = c.attractor->iterate;
      a["entered_at"] = c.attractor->entered_at;
      a["box"] = c.attractor->box;
      d["attractor"] = a;
    } else {
      d["attractor"] = py::none();
    }
    d["release_theta"] = c.release_theta.empty() ? py::object(py::none()) : py::object(py::str(c.release_theta));
    d["release_v"] = c.release_v.empty() ? py::object(py::none()) : py::object(py::str(c.release_v));
    d["lohner_fallbacks"] = c.fallbacks;
    d["max_steps"] = q.max_steps;
    d["schedule"] = q.schedule.text();
    d["attempts"] = attempts_of(c.attempts);
    d["seconds"] = c.seconds;
    return d;
  }

  // bouncer certify-periodic at the model's parameter values, no range, no --lift (its
  // request: io/requests/certify_periodic.hpp).
  py::dict certify_periodic(const Texts& texts) const {
    const PeriodicQuestion q = certify_periodic_request(with_model(texts)).question;
    const PeriodicCertificate c = interruptible([&] { return bouncer::certify_periodic(q); });
    py::dict d;
    d["certified"] = c.certified;
    d["outcome"] = name(c.outcome);
    d["statement"] = c.statement;
    d["reason"] = c.reason;
    d["bits"] = c.bits;
    d["period"] = c.period;
    d["minimal_period"] = c.minimal_period_certified ? py::object(py::int_(c.minimal_period)) : py::object(py::none());
    d["stability"] = c.stability;
    py::list pts;
    for (const EnclosedOrbitPoint& p : c.points) pts.append(py::make_tuple(interval_of(p.theta), interval_of(p.v)));
    d["points"] = pts;
    d["events"] = c.events;
    d["wall_periods"] = c.wall_periods;
    py::dict mu;
    mu["kind"] = c.multipliers.kind;
    if (c.certified) {
      mu["trace"] = interval_of(c.multipliers.trace);
      mu["det"] = interval_of(c.multipliers.det);
      if (c.multipliers.kind == "real") {
        mu["mu1"] = interval_of(c.multipliers.mu[0]);
        mu["mu2"] = interval_of(c.multipliers.mu[1]);
      } else if (c.multipliers.kind == "complex") {
        mu["re"] = interval_of(c.multipliers.mu[0]);
        mu["im"] = interval_of(c.multipliers.mu[1]);
        mu["modulus"] = interval_of(c.multipliers.modulus);
      }
    }
    d["multipliers"] = mu;
    if (c.certified && c.outcome != PeriodicOutcome::through_release) {
      py::dict k;
      k["unknowns"] = c.unknowns;
      k["box"] = py::make_tuple(interval_of(c.box[0]), interval_of(c.box[1]));
      k["image"] = py::make_tuple(interval_of(c.image[0]), interval_of(c.image[1]));
      k["free"] = c.free_name;
      k["free_range"] = interval_of(c.free_range);
      k["inflations"] = c.inflations;
      d["krawczyk"] = k;
    } else {
      d["krawczyk"] = py::none();
    }
    if (c.certified && c.family_parameter) {
      py::dict f;
      f["parameter_at_theta"] = interval_of(*c.family_parameter);
      f["given_parameter"] = c.given_parameter;
      f["strip_theta"] = c.strip_theta ? interval_of(*c.strip_theta) : py::object(py::none());
      f["strip_v"] = c.strip_v ? interval_of(*c.strip_v) : py::object(py::none());
      f["strip_parameter"] = c.strip_parameter ? interval_of(*c.strip_parameter) : py::object(py::none());
      d["family"] = f;
    } else {
      d["family"] = py::none();
    }
    d["double_newton"] = c.double_theta.empty() ? py::object(py::none()) : py::object(py::make_tuple(c.double_theta, c.double_v));
    d["double_distance"] = c.double_distance ? py::object(py::float_(*c.double_distance)) : py::object(py::none());
    d["schedule"] = q.schedule.text();
    d["attempts"] = attempts_of(c.attempts);
    d["seconds"] = c.seconds;
    return d;
  }

  // bouncer basin (run/basin.hpp): the same reader (io/requests/grids.hpp) and library call.
  py::dict basin(const Texts& texts) const {
    const Options o = with_model(texts);
    const BasinOptions b = basin_options(o);
    const GridOptions run = grid_run_options(o);
    py::dict d;
    if (b.certify) {
      const CertifiedBasinResult r = interruptible([&] { return certified_basin(b.request, run); });
      put_axes(d, "theta", r.theta, "v", r.v);
      put_certified(d, r.cells);
      d["v_range"] = py::make_tuple(r.request.v_range->first.text(), r.request.v_range->second.text());
    } else {
      const BasinResult r = interruptible([&] { return bouncer::basin(b.request, run); });
      put_axes(d, "theta", r.theta, "v", r.v);
      put_attractors(d, r.cells);
      if (r.request.confirm.on) put_confirm(d, r.cells, r.request.confirm);
      d["v_range"] = py::make_tuple(r.request.v_range->first.text(), r.request.v_range->second.text());
    }
    d["certified"] = b.certify;
    return d;
  }

  // bouncer scan (run/scan.hpp): this model's law, wall and sticking rule; a and eps (or c)
  // are the scanned axes, so the model's own values of them are not used.
  py::dict scan(const Texts& texts) const {
    Options o = with_model(texts);
    for (const char* k : {"a", "eps", "c"}) o.values.erase(k);
    const ScanOptions so = scan_options(o);
    const GridOptions run = grid_run_options(o);
    py::dict d;
    const std::string y = name(scan_parameter(so.request.model));
    if (so.certify) {
      const CertifiedScanResult r = interruptible([&] { return certified_scan(so.request, run); });
      put_axes(d, "a", r.a, y, r.y_values);
      put_certified(d, r.cells);
    } else {
      const ScanResult r = interruptible([&] { return bouncer::scan(so.request, run); });
      put_axes(d, "a", r.a, y, r.y_values);
      const auto nx = static_cast<py::ssize_t>(so.request.p), ny = static_cast<py::ssize_t>(so.request.q);
      py::array_t<std::int64_t> counts({ny, nx, static_cast<py::ssize_t>(scan_classes().size())});
      auto c = counts.mutable_unchecked<3>();
      for (size_t i = 0; i < r.cells.size(); ++i)
        for (size_t k = 0; k < scan_classes().size(); ++k)
          c(static_cast<py::ssize_t>(i) / nx, static_cast<py::ssize_t>(i) % nx, static_cast<py::ssize_t>(k)) =
              r.cells[i][scan_classes()[k]];
      py::list names;
      for (OrbitClass k : scan_classes()) names.append(name(k));
      d["counts"] = counts;
      d["count_classes"] = names;
    }
    d["y"] = y;
    d["certified"] = so.certify;
    return d;
  }

  // bouncer attractors without --vary (run/attractors.hpp find_attractors; its request:
  // io/requests/attractors.hpp): every attractor with its points, multipliers, certificate
  // summary and basin share, and each start's label.
  py::dict attractors(const Texts& texts) const {
    const Options o = with_model(texts);
    const AttractorsRequest req = attractors_request(o);
    const GridOptions run = grid_run_options(o);
    const AttractorsResult r = interruptible([&] { return find_attractors(req, run); });
    py::list list;
    for (const FoundAttractor& a : r.attractors) {
      py::dict d;
      d["id"] = a.id;
      d["kind"] = name(a.kind);
      d["period"] = a.period;
      py::array_t<double> th(static_cast<py::ssize_t>(a.points.size())), v(static_cast<py::ssize_t>(a.points.size()));
      py::list th_text, v_text;
      for (size_t k = 0; k < a.points.size(); ++k) {
        th.mutable_at(static_cast<py::ssize_t>(k)) = a.points[k].theta.value;
        v.mutable_at(static_cast<py::ssize_t>(k)) = a.points[k].v.value;
        th_text.append(a.points[k].theta.digits);
        v_text.append(a.points[k].v.digits);
      }
      d["theta"] = th;
      d["v"] = v;
      d["theta_text"] = th_text;
      d["v_text"] = v_text;
      py::list mu;
      for (const auto& m : a.multipliers) mu.append(std::complex<double>(m.first.value, m.second.value));
      d["multipliers"] = mu;
      d["multiplier_moduli"] = a.multiplier_moduli;
      d["stable"] = a.stable;
      if (a.certificate) {
        const PeriodicCertificate& c = *a.certificate;
        py::dict k;
        k["certified"] = c.certified;
        k["outcome"] = name(c.outcome);
        k["bits"] = c.bits;
        k["minimal_period"] = c.minimal_period_certified ? py::object(py::int_(c.minimal_period)) : py::object(py::none());
        k["stability"] = c.stability;
        k["reason"] = c.reason;
        py::dict m;
        m["kind"] = c.multipliers.kind;
        if (c.certified && c.multipliers.kind == "real") {
          m["mu1"] = interval_of(c.multipliers.mu[0]);
          m["mu2"] = interval_of(c.multipliers.mu[1]);
        } else if (c.certified && c.multipliers.kind == "complex") {
          m["re"] = interval_of(c.multipliers.mu[0]);
          m["im"] = interval_of(c.multipliers.mu[1]);
          m["modulus"] = interval_of(c.multipliers.modulus);
        }
        k["multipliers"] = m;
        d["certificate"] = k;
      } else {
        d["certificate"] = py::none();
      }
      const bool aperiodic = a.kind == AttractorKind::chaotic || a.kind == AttractorKind::quasiperiodic;
      d["lambda_"] = aperiodic ? py::object(py::float_(a.lambda)) : py::object(py::none());
      d["lambda_stderr"] = aperiodic ? py::object(py::float_(a.lambda_stderr)) : py::object(py::none());
      d["accelerator_gain"] =
          a.kind == AttractorKind::accelerator ? py::object(py::float_(a.accel_gain)) : py::object(py::none());
      if (a.kind == AttractorKind::family) {
        py::dict f;
        f["members_found"] = a.family_members;
        f["theta_min"] = a.family_theta_min;
        f["theta_max"] = a.family_theta_max;
        d["family"] = f;
      } else {
        d["family"] = py::none();
      }
      d["starts"] = a.starts;
      d["fraction"] = a.fraction;
      d["fraction_stderr"] = a.fraction_stderr;
      d["cells"] = a.cells;
      d["evidence"] = a.evidence;
      list.append(d);
    }
    py::dict d;
    d["attractors"] = list;
    const auto n = static_cast<py::ssize_t>(r.label.size());
    py::array_t<std::int32_t> label(n);
    py::array_t<double> theta(n), v(n);
    for (py::ssize_t i = 0; i < n; ++i) {
      label.mutable_at(i) = r.label[static_cast<size_t>(i)];
      theta.mutable_at(i) = r.theta[static_cast<size_t>(i)].value;
      v.mutable_at(i) = r.v[static_cast<size_t>(i)].value;
    }
    d["label"] = label;
    d["theta"] = theta;
    d["v"] = v;
    d["shape"] = req.sampling == StartSampling::grid ? py::object(py::make_tuple(req.ny, req.nx)) : py::object(py::none());
    d["sampling"] = name(req.sampling);
    d["v_range"] = py::make_tuple(r.request.v_range->first.text(), r.request.v_range->second.text());
    d["inside"] = r.inside;
    d["outside"] = r.outside;
    d["undecided"] = r.undecided;
    d["undecided_fraction"] = r.undecided_fraction;
    d["undecided_stderr"] = r.undecided_stderr;
    d["steps"] = r.steps;
    d["seconds"] = r.seconds;
    d["certify_seconds"] = r.certify_seconds;
    return d;
  }

  // bouncer bifurcation (run/bifurcation.hpp): one row per recorded point, as the CSV.
  py::dict bifurcation(const Texts& texts) const {
    const Options o = with_model(texts);
    const BifurcationOptions b = bifurcation_options(o);
    const GridOptions run = grid_run_options(o);
    const BifurcationResult r = interruptible([&] { return bouncer::bifurcation(b.request, run); });
    size_t rows = 0;
    for (const BifurcationColumn& c : r.columns) rows += c.points.size();
    py::array_t<double> value(static_cast<py::ssize_t>(rows)), theta(static_cast<py::ssize_t>(rows)),
        v(static_cast<py::ssize_t>(rows));
    py::array_t<std::int64_t> n(static_cast<py::ssize_t>(rows)), column(static_cast<py::ssize_t>(rows));
    py::array_t<bool> sticking(static_cast<py::ssize_t>(rows));
    py::list value_text, theta_text, v_text, undecided, certified;
    const bool texts_too = b.request.precision.kind != Precision::Kind::double_;
    size_t at = 0;
    for (size_t k = 0; k < r.columns.size(); ++k) {
      const BifurcationColumn& c = r.columns[k];
      for (const BifurcationPoint& p : c.points) {
        value.mutable_at(at) = c.value.value;
        theta.mutable_at(at) = p.theta.value;
        v.mutable_at(at) = p.v.value;
        n.mutable_at(at) = p.n;
        column.mutable_at(at) = static_cast<std::int64_t>(k);
        sticking.mutable_at(at) = p.sticking;
        if (texts_too) {
          theta_text.append(p.theta.digits);
          v_text.append(p.v.digits);
        }
        ++at;
      }
      value_text.append(c.value.digits);
      if (c.undecided_step) undecided.append(py::make_tuple(k, *c.undecided_step, c.undecided_reason));
      if (c.certified) certified.append(certified_dict(*c.exact_value, *c.certified));
    }
    py::dict d;
    d["vary"] = name(b.request.vary);
    d["value"] = value;
    d["column"] = column;
    d["n"] = n;
    d["theta"] = theta;
    d["v"] = v;
    d["sticking"] = sticking;
    d["values"] = value_text;
    d["theta_text"] = texts_too ? py::object(theta_text) : py::object(py::none());
    d["v_text"] = texts_too ? py::object(v_text) : py::object(py::none());
    d["undecided"] = undecided;
    d["certified"] = b.request.certify ? py::object(certified) : py::object(py::none());
    return d;
  }

  // bouncer portrait (run/portrait.hpp): one row per point, as the CSV (orbit, n, theta, v,
  // event); the picture's options (--polar, windows) change no point and are not taken.
  py::dict portrait(const Texts& texts) const {
    const Options o = with_model(texts);
    const PortraitOptions p = portrait_options(o);
    const GridOptions run = grid_run_options(o);
    const PortraitResult r = interruptible([&] { return bouncer::portrait(p.request, run); });
    size_t rows = 0;
    for (const PortraitOrbit& q : r.orbits) rows += q.points.size();
    const auto n_rows = static_cast<py::ssize_t>(rows);
    py::array_t<std::int64_t> orbit(n_rows), n(n_rows);
    py::array_t<double> theta(n_rows), v(n_rows);
    py::array_t<std::int8_t> event(n_rows);
    py::list theta_text, v_text, undecided, starts;
    const bool texts_too = p.request.precision.kind != Precision::Kind::double_;
    py::ssize_t at = 0;
    for (size_t k = 0; k < r.orbits.size(); ++k) {
      const PortraitOrbit& q = r.orbits[k];
      for (const PortraitPoint& pt : q.points) {
        orbit.mutable_at(at) = static_cast<std::int64_t>(k);
        n.mutable_at(at) = pt.n;
        theta.mutable_at(at) = pt.theta.value;
        v.mutable_at(at) = pt.v.value;
        event.mutable_at(at) = pt.event ? event_int8(*pt.event) : kStartEvent;
        if (texts_too) {
          theta_text.append(pt.theta.digits);
          v_text.append(pt.v.digits);
        }
        ++at;
      }
      if (q.undecided_step) undecided.append(py::make_tuple(k, *q.undecided_step, q.undecided_reason));
    }
    for (const InitialCondition& ic : r.request.starts) starts.append(py::make_tuple(ic.theta.text(), ic.v.text()));
    py::dict d;
    d["orbit"] = orbit;
    d["n"] = n;
    d["theta"] = theta;
    d["v"] = v;
    d["event"] = event;
    d["theta_text"] = texts_too ? py::object(theta_text) : py::object(py::none());
    d["v_text"] = texts_too ? py::object(v_text) : py::object(py::none());
    d["starts"] = starts;
    d["undecided"] = undecided;
    d["steps"] = r.request.steps;
    d["transient"] = r.request.transient;
    return d;
  }

  // bouncer lyapunov --vary (run/exponent_curve.hpp): (values, starts) arrays.
  py::dict lyapunov_curve(const Texts& texts) const {
    const Options o = with_model(texts);
    if (!o.has("vary")) throw InputError("vary", "is needed: a, eps or c");
    const ExponentCurveRequest req = exponent_curve_request(o);
    const GridOptions run = grid_run_options(o);
    const ExponentCurveResult r = interruptible([&] { return bouncer::exponent_curve(req, run); });
    const auto K = static_cast<py::ssize_t>(r.columns.size()), N = static_cast<py::ssize_t>(r.starts.size());
    py::array_t<double> value(K), max_lambda(K), mean_lambda(K), lambda({K, N}), stderr_({K, N});
    py::array_t<std::int64_t> period({K, N});
    std::vector<const ExponentRow*> cells;
    py::list values, starts;
    auto l = lambda.mutable_unchecked<2>();
    auto e = stderr_.mutable_unchecked<2>();
    auto q = period.mutable_unchecked<2>();
    for (py::ssize_t k = 0; k < K; ++k) {
      const ExponentColumn& c = r.columns[static_cast<size_t>(k)];
      value.mutable_at(k) = c.value.value;
      values.append(c.value.digits);
      max_lambda.mutable_at(k) = c.max_lambda();
      mean_lambda.mutable_at(k) = c.mean_lambda();
      for (py::ssize_t j = 0; j < N; ++j) {
        const ExponentRow& row = c.rows[static_cast<size_t>(j)];
        l(k, j) = row.lambda;
        e(k, j) = row.stderr_;
        q(k, j) = row.period;
        cells.push_back(&row);
      }
    }
    std::vector<std::string> names;
    for (const InitialCondition& ic : r.starts) starts.append(py::make_tuple(ic.theta.text(), ic.v.text()));
    py::dict d;
    d["vary"] = name(req.vary);
    d["value"] = value;
    d["values"] = values;
    d["starts"] = starts;
    d["lambda_"] = lambda;
    d["stderr"] = stderr_;
    d["class_"] = codes_of(cells, [](const ExponentRow* row) { return std::string(name(row->cls)); }, names);
    d["class_names"] = names;
    d["period"] = period;
    d["max_lambda"] = max_lambda;
    d["mean_lambda"] = mean_lambda;
    d["shape"] = py::make_tuple(K, N);
    return d;
  }

  // What the model was built from, for repr and provenance: the option texts.
  py::dict options() const {
    py::dict d;
    for (const auto& [k, v] : options_.values) d[py::str(k)] = v.size() == 1 ? py::object(py::str(v[0])) : py::object(py::cast(v));
    return d;
  }
  std::string precision_text() const { return precision_.text(); }
  long bits() const { return precision_.bits; }
  std::string law() const { return name(spec_.law); }
  std::string a() const { return spec_.a.text(); }
  py::object eps() const { return spec_.law == Law::constant ? py::object(py::str(spec_.eps.text())) : py::object(py::none()); }
  py::object c() const { return spec_.law == Law::veldep ? py::object(py::str(spec_.c.text())) : py::object(py::none()); }
  std::string wall() const { return spec_.wall.text; }

 private:
  // The model's options with the call's on top. A call may not redefine the model.
  Options with_model(const Texts& texts) const {
    Options o = options_;
    for (const auto& [k, v] : options_of(texts).values) {
      if (o.has(k)) throw InputError(k, "belongs to the model: build another Model to change it");
      o.set(k, v);
    }
    if (!o.has("precision")) o.set("precision", precision_.text());
    return o;
  }

  template <class T>
  static py::dict periodic_dict(const PeriodicOrbit<T>& p, long q) {
    py::dict d;
    d["converged"] = p.converged;
    d["period"] = q;
    d["minimal_period"] = p.minimal_period;
    py::list pts;
    for (const State<T>& s : p.points) pts.append(pair_of(s.theta, s.v));
    d["points"] = pts;
    // As `bouncer periodic`: multipliers and events belong to an orbit, None and empty
    // where Newton found none.
    py::list mu;
    for (int i = 0; i < 2; ++i) mu.append(pair_of(p.multipliers.re[i], p.multipliers.im[i]));
    d["multipliers"] = p.converged ? py::object(mu) : py::object(py::none());
    d["multiplier_moduli"] = p.converged ? py::object(py::make_tuple(p.multipliers.modulus(0), p.multipliers.modulus(1)))
                                         : py::object(py::none());
    d["complex_pair"] = p.converged ? py::object(py::bool_(p.multipliers.complex)) : py::object(py::none());
    d["marginal"] = p.converged ? py::object(py::bool_(p.marginal)) : py::object(py::none());
    d["stability"] = stability_of(p);
    py::list kinds;
    if (p.converged)
      for (EventKind k : p.kinds) kinds.append(name(k));
    d["events"] = kinds;
    d["wall_periods"] = p.converged ? p.wall_periods : std::vector<long long>{};
    d["residual"] = p.residual;
    d["tolerance"] = p.tolerance;
    d["iterations"] = p.iterations;
    d["note"] = p.note;
    return d;
  }

  template <class T>
  static py::dict end_dict(const BranchEnd<T>& e, const Model<T>& m) {
    py::dict d;
    d["reason"] = name(e.reason);
    d["param"] = scalar(e.param);
    d["bracket"] = pair_of(e.bracket_lo, e.bracket_hi);
    d["margin"] = e.margin >= 0 ? py::object(py::str(name(static_cast<Margin>(e.margin)))) : py::object(py::none());
    d["impact"] = e.impact >= 0 ? py::object(py::int_(e.impact + 1)) : py::object(py::none());  // 1-based, as the CLI
    d["knot"] = e.knot >= 0 ? py::object(py::str(m.wall.knot_exact[e.knot].get_str())) : py::object(py::none());
    d["detail"] = e.detail;
    d["last_point"] = pair_of(e.last_point.theta, e.last_point.v);
    if (e.beyond_done) {
      py::dict by;
      by["param"] = scalar(e.beyond_param);
      by["class_"] = name(e.beyond.cls);
      by["period"] = e.beyond.period;
      by["lambda_"] = e.beyond.lambda;
      by["evidence"] = e.beyond.evidence;
      by["newton_orbit_events"] = e.beyond_orbit;
      by["newton_orbit_minimal_period"] = e.beyond_orbit_period;
      by["newton_orbit_relation"] = name(e.beyond_relation);  // as continue's JSON
      d["beyond"] = by;
    } else {
      d["beyond"] = py::none();
    }
    d["beyond_note"] = e.beyond_note;
    d["accuracy"] = accuracy_dict(e.estimate);
    return d;
  }

  // The error estimate of a located end or bifurcation, with the fields of `continue`'s JSON
  // (io/reports/continue.cpp): kind, and for an estimate the backed digits and the widened bracket.
  static py::dict accuracy_dict(const EndEstimate& est) {
    py::dict d;
    d["kind"] = name(est.kind);
    if (est.kind == EndEstimate::Kind::estimate) {
      const BackedDigits b = backed_digits(est.center, est.radius);
      d["a_star_backed"] = b.value;
      d["a_star_plus_minus"] = b.plus_minus;
      d["a_star_digits"] = b.digits;
      d["bracket_estimate"] = py::make_tuple(b.lo, b.hi);
      d["error_estimate"] = est.error;
      d["refined_param"] = est.refined;
      d["refined_bits"] = est.bits;
    } else {
      d["note"] = est.note;
    }
    return d;
  }

  template <class T>
  static py::dict branch_dict(const Branch<T>& b, const Model<T>& m, const std::string& vary) {
    const py::ssize_t k = static_cast<py::ssize_t>(b.points.size());
    RealColumn<T> param, theta, v;
    std::vector<double> moduli, residual;
    std::vector<std::array<double, kMargins>> margins;
    py::list stability, events;
    for (const BranchPoint<T>& p : b.points) {
      param.push(p.param);
      for (const State<T>& s : p.orbit.points) {
        theta.push(s.theta);
        v.push(s.v);
      }
      moduli.push_back(p.orbit.multipliers.modulus(0));
      moduli.push_back(p.orbit.multipliers.modulus(1));
      residual.push_back(p.orbit.residual);
      margins.push_back(p.min_margin);
      stability.append(p.stability);
      events.append(event_text(p.events));
    }
    py::dict d;
    d["vary"] = vary;
    d["period"] = b.period;
    d["param"] = std::move(param).numpy(k);
    d["theta"] = std::move(theta).numpy(k * b.period).attr("reshape")(k, b.period);
    d["v"] = std::move(v).numpy(k * b.period).attr("reshape")(k, b.period);
    d["multiplier_moduli"] = numpy_of(std::move(moduli), {k, 2});
    d["residual"] = numpy_of(std::move(residual), {k});
    py::dict mins;
    for (int j = 0; j < kMargins; ++j) {
      std::vector<double> col;
      for (const auto& row : margins) col.push_back(row[j]);
      mins[py::str(name(static_cast<Margin>(j)))] = numpy_of(std::move(col), {k});
    }
    d["min_margin"] = mins;
    d["stability"] = stability;
    d["events"] = events;
    d["start"] = b.start;
    d["low"] = end_dict(b.low, m);
    d["high"] = end_dict(b.high, m);
    py::list bif;
    for (const Bifurcation<T>& x : b.bifurcations) {
      py::dict e;
      e["kind"] = name(x.kind);
      e["param"] = scalar(x.param);
      e["bracket"] = pair_of(x.bracket_lo, x.bracket_hi);
      e["accuracy"] = accuracy_dict(x.estimate);
      bif.append(e);
    }
    d["bifurcations"] = bif;
    d["corrector_runs"] = b.corrector_runs;
    return d;
  }

  Options options_;
  ModelSpec spec_;
  Precision precision_;
  std::unique_ptr<Stepper> stepper_;
};

}  // namespace

PYBIND11_MODULE(_core, mod) {
  // The docstrings give their own signatures, in Python's terms (pybind11's would say "handle").
  py::options options;
  options.disable_function_signatures();
  mod.doc() = "bouncer's native core: the library's model, map and analyses (Model), and run(), which runs a bouncer "
              "command line in this process (see the bouncer package)";

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {  // one printable line, as run_command gives the CLI-parity layer
      PyErr_SetString(PyExc_ValueError, cli::one_line(e.what()).c_str());
    }
  });
  py::register_exception<Undecided>(mod, "Undecided", PyExc_ArithmeticError);

  // bouncer check-certificate on a certificate's text (io/chaos_certificate.hpp: read as
  // hostile; InputError -> ValueError), replayed in Arb at `bits`.
  mod.def(
      "_check_certificate",
      [](const std::string& text, long bits) {
        if (bits < 32 || bits > 65536) throw InputError("bits", "must be an integer in [32, 65536] (got " + std::to_string(bits) + ")");
        const ChaosCertificate c = parse_certificate(text);
        const ReplayResult r = interruptible([&] { return replay_certificate(c, bits); });
        py::dict d;
        d["valid"] = r.valid;
        d["disjoint"] = r.disjoint;
        py::list coverings;
        for (const ReplayedCovering& v : r.coverings) coverings.append(py::make_tuple(v.proved, v.message));
        d["coverings"] = coverings;
        d["bound"] = c.entropy_bound;
        d["recomputed_bound"] = r.recomputed_bound;
        d["problems"] = r.problems;
        d["bits"] = r.bits;
        return d;
      },
      py::arg("text"), py::arg("bits"));
  mod.def("run", &run, py::arg("words"),
          "run(words: list[str]) -> dict\n\nRun a bouncer command line (words[0] is the program name) in this process, with the GIL released; "
          "returns {status, kind, message, unknown_option, out, csv}. Ctrl-C cancels it (KeyboardInterrupt).");
  mod.attr("version") = build_info().version;
  mod.attr("commit") = build_info().commit;

  py::class_<Interval>(mod, "Interval",
                       "An interval [lo, hi] that encloses an exact value: lo and hi are exact decimal texts, rounded "
                       "outward at the run's precision (float(lo) is exact for interval:double).")
      .def(py::init<std::string, std::string>(), py::arg("lo"), py::arg("hi"), "Interval(lo: str, hi: str)")
      .def_readonly("lo", &Interval::lo, "The lower end, an exact decimal text (rounded down)")
      .def_readonly("hi", &Interval::hi, "The upper end, an exact decimal text (rounded up)")
      .def("to_floats", [](const Interval& x) { return py::make_tuple(outward_double(x.lo, false), outward_double(x.hi, true)); },
           "to_floats() -> tuple[float, float]\n\n(lo, hi) as floats rounded outward: the float interval still encloses "
           "the value")
      .def("to_mpmath", &interval_to_mpmath, py::arg("bits") = py::none(),
           "to_mpmath(bits: int | None = None) -> mpmath.mpi\n\nmpmath.mpi(lo, hi) with the ends rounded outward at "
           "`bits` bits (default: max(53, mpmath.mp.prec))")
      .def("__eq__", [](const Interval& x, const Interval& y) { return x.lo == y.lo && x.hi == y.hi; })
      .def("__repr__", [](const Interval& x) { return "Interval('" + x.lo + "', '" + x.hi + "')"; });

  step_type = PyStructSequence_NewType(&kStepDesc);
  if (!step_type) throw py::error_already_set();
  mod.add_object("Step", py::handle(reinterpret_cast<PyObject*>(step_type)));

  py::class_<Orbit>(mod, "Orbit",
                    "An orbit as numpy arrays, one entry per row (row 0: the start; then every `every`-th step and "
                    "the last). Real columns are float64 in double, (N, 2) float64 [lo, hi] in interval:double, "
                    "str arrays of decimal texts in the other precisions ((N, 2) for intervals); NaN or '' where a "
                    "row has none. Integer columns hold -1 in the start row.")
      .def_readonly("n", &Orbit::n, "int64: step number")
      .def_readonly("theta", &Orbit::theta, "phase")
      .def_readonly("v", &Orbit::v, "velocity after the impact")
      .def_readonly("event", &Orbit::event, "int8 codes into bouncer.EVENTS: start, impact, sticking, ride")
      .def_readonly("tau", &Orbit::tau, "time of the step (NaN in the start row)")
      .def_readonly("periods", &Orbit::periods, "int64: wall periods begun during the step")
      .def_readonly("segment", &Orbit::segment, "int32: wall segment of the last contact")
      .def_readonly("wall", &Orbit::wall, "int8: direction of the wall at the impact, +1 up, -1 down, 0 flat (its segment's; on the sine wall the sign of its velocity; 0 at the start)")
      .def_readonly("corner", &Orbit::corner, "bool: the impact was exactly at a wall corner")
      .def_readonly("indirect", &Orbit::indirect, "int8: 1 the flight rose above the wall's top, 0 not, -1 undecided")
      .def_readonly("stick_segment", &Orbit::stick_segment, "int32: segment of the collision that stuck (-1: none)")
      .def_readonly("stuck_theta", &Orbit::stuck_theta, "phase where a collapse completed (NaN: none)")
      .def_readonly("stuck_v", &Orbit::stuck_v, "velocity there (NaN: none)")
      .def_readonly("passed_upward_turn", &Orbit::passed_upward_turn, "bool: the ride passed an upward turn")
      .def_readonly("phase_bits", &Orbit::phase_bits, "int32: correct bits of theta left, at best")
      .def_readonly("status", &Orbit::status, "completed | undecided (an interval step could not be decided)")
      .def_readonly("steps_done", &Orbit::steps_done, "steps completed")
      .def_readonly("reason", &Orbit::reason, "why the run stopped, when undecided")
      .def_readonly("phase_lost_at", &Orbit::phase_lost_at, "first step after which theta had no correct bit, or None")
      .def_readonly("lohner_fallbacks", &Orbit::lohner_fallbacks,
                    "interval runs with Lohner's method: steps that fell back to the box image (else None)")
      .def_readonly("precision", &Orbit::precision, "the precision of the run")
      .def("__len__", [](const Orbit& o) { return o.rows; })
      .def("__repr__", [](const Orbit& o) {
        return "Orbit(" + std::to_string(o.rows) + " rows, " + o.status + " " + std::to_string(o.steps_done) +
               " steps, precision='" + o.precision + "')";
      });

  py::class_<ModelCore>(mod, "Model", "The model core (see bouncer.Model)")
      .def(py::init<const Texts&>(), py::arg("options"))
      .def("step", &ModelCore::step, py::arg("theta"), py::arg("v"),
           "step(theta, v) -> Step\n\n"
           "One step of the impact map from the state (theta, v): theta, the phase of an impact, in [0, 1); v, the "
           "velocity just after it, at least the wall's velocity at theta and at most 1e15. Floats are taken as "
           "their exact binary value; str and decimal.Decimal as exact decimals. Raises ValueError (bouncer's "
           "message) for a state outside those ranges, bouncer.Undecided when an interval step cannot be decided.")
      .def("_orbit", &ModelCore::orbit, py::arg("options"))
      .def("_classify", &ModelCore::classify, py::arg("options"))
      .def("_lyapunov", &ModelCore::lyapunov, py::arg("options"))
      .def("_periodic", &ModelCore::periodic, py::arg("options"))
      .def("_continue_branch", &ModelCore::continue_branch, py::arg("options"))
      .def("_certify_sticking", &ModelCore::certify_sticking, py::arg("options"))
      .def("_certify_periodic", &ModelCore::certify_periodic, py::arg("options"))
      .def("_certify_chaos", &ModelCore::certify_chaos, py::arg("options"))
      .def("_basin", &ModelCore::basin, py::arg("options"))
      .def("_scan", &ModelCore::scan, py::arg("options"))
      .def("_bifurcation", &ModelCore::bifurcation, py::arg("options"))
      .def("_portrait", &ModelCore::portrait, py::arg("options"))
      .def("_lyapunov_curve", &ModelCore::lyapunov_curve, py::arg("options"))
      .def("_attractors", &ModelCore::attractors, py::arg("options"))
      .def_property_readonly("options", &ModelCore::options, "The option texts the model was built from")
      .def_property_readonly("precision", &ModelCore::precision_text, "The precision: double, long, dd, quad, mpfr:BITS, "
                                                                      "interval:BITS or interval:double")
      .def_property_readonly("bits", &ModelCore::bits, "Significand bits of the precision")
      .def_property_readonly("model", &ModelCore::law, "The collision law: elastic, constant or veldep")
      .def_property_readonly("a", &ModelCore::a, "a = g T^2 / A as an exact decimal text")
      .def_property_readonly("eps", &ModelCore::eps, "The restitution coefficient (constant law), else None")
      .def_property_readonly("c", &ModelCore::c, "The scale of eps(v) (veldep law), else None")
      .def_property_readonly("wall", &ModelCore::wall, "The wall profile as given (triangle, sawtooth, ...)");
}
