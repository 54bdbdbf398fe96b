// Phase portraits (run/portrait.hpp).
#include "bouncer/run/portrait.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>

#include "bouncer/base/cancel.hpp"

namespace bouncer {

namespace {

std::string integer_range(long long lo, long long hi) {
  return "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

void check_portrait(const PortraitRequest& r) {
  validate(r.model);
  if (r.starts.empty()) throw InputError("theta", "needs at least one initial condition");
  if (r.starts.size() > 1000) throw InputError("theta", "at most 1000 initial conditions");
  for (const InitialCondition& ic : r.starts) validate(r.model, ic, "theta", "v");
  if (r.steps < 1 || r.steps > 10000000) throw InputError("steps", integer_range(1, 10000000));
  if (r.transient < 0 || r.transient > 100000000) throw InputError("transient", integer_range(0, 100000000));
  if (static_cast<double>(r.steps) * static_cast<double>(r.starts.size()) > 2e7)
    throw InputError("steps", "orbits x steps must be at most 2e7 points");
  if (!r.precision.is_analysis())
    throw InputError("precision", "interval precision is not supported here (use " +
                                      precision_names<AnalysisScalars>(" or ") + ")");
}

struct OrbitsBase {
  virtual ~OrbitsBase() = default;
  virtual PortraitOrbit orbit(long k) const = 0;
};

template <class T>
struct Orbits final : OrbitsBase {
  const PortraitRequest& r;
  ImpactMap<T> map;

  explicit Orbits(const PortraitRequest& req) : r(req), map(make_model<T>(req.model, req.precision.bits)) {}

  PortraitOrbit orbit(long k) const override {
    State<T> s = make_state<T>(r.starts[static_cast<size_t>(k)], r.precision.bits);
    PortraitOrbit o;
    o.points.reserve(static_cast<size_t>(r.steps) + (r.transient == 0));
    long n = 0;
    try {
      for (; n < r.transient; ++n) {
        throw_if_cancelled(n);
        s = map.step(s).next;
      }
      if (r.transient == 0) o.points.push_back({0, number_of(s.theta), number_of(s.v), std::nullopt});
      for (long m = 0; m < r.steps; ++m, ++n) {
        throw_if_cancelled(n);
        const StepResult<T> st = map.step(s);
        s = st.next;
        o.points.push_back({n + 1, number_of(s.theta), number_of(s.v), st.kind});
      }
    } catch (const Undecided& u) {
      o.undecided_step = n + 1;
      o.undecided_reason = u.what();
    }
    return o;
  }
};

[[noreturn]] void bad_orbit(std::string_view text) {
  throw std::runtime_error("a grid tile holds a portrait orbit no bouncer wrote: '" + std::string(text.substr(0, 80)) + "'");
}

Number read_number(std::string_view digits) {
  std::string d(digits);
  const double v = std::strtod(d.c_str(), nullptr);
  return {v, std::move(d)};
}

std::optional<EventKind> event_named(std::string_view text, std::string_view whole) {
  if (text == "start") return std::nullopt;
  for (EventKind k : {EventKind::impact, EventKind::sticking, EventKind::ride})
    if (text == name(k)) return k;
  bad_orbit(whole);
}

}  // namespace

std::string encode(const PortraitOrbit& o) {
  std::string s;
  for (const PortraitPoint& p : o.points)
    s += "S " + std::to_string(p.n) + ',' + p.theta.digits + ',' + p.v.digits + ',' + (p.event ? name(*p.event) : "start") + "\n";
  if (o.undecided_step) s += "U " + std::to_string(*o.undecided_step) + ' ' + o.undecided_reason + "\n";
  return s;
}

template <>
PortraitOrbit decode_cell<PortraitOrbit>(std::string_view text) {
  PortraitOrbit o;
  const std::string_view whole = text;
  while (!text.empty()) {
    const size_t nl = text.find('\n');
    if (nl == std::string_view::npos || nl < 2 || text[1] != ' ') bad_orbit(whole);
    const std::string_view line = text.substr(2, nl - 2);
    if (text[0] == 'S') {
      const size_t c1 = line.find(','), c2 = line.find(',', c1 + 1), c3 = line.find(',', c2 + 1);
      if (c1 == std::string_view::npos || c2 == std::string_view::npos || c3 == std::string_view::npos) bad_orbit(whole);
      PortraitPoint p;
      const auto r = std::from_chars(line.data(), line.data() + c1, p.n);
      if (r.ec != std::errc() || r.ptr != line.data() + c1) bad_orbit(whole);
      p.theta = read_number(line.substr(c1 + 1, c2 - c1 - 1));
      p.v = read_number(line.substr(c2 + 1, c3 - c2 - 1));
      p.event = event_named(line.substr(c3 + 1), whole);
      o.points.push_back(std::move(p));
    } else if (text[0] == 'U') {
      const size_t sp = line.find(' ');
      long step = 0;
      const auto r = std::from_chars(line.data(), line.data() + std::min(sp, line.size()), step);
      if (r.ec != std::errc()) bad_orbit(whole);
      o.undecided_step = step;
      o.undecided_reason = sp == std::string_view::npos ? "" : std::string(line.substr(sp + 1));
    } else {
      bad_orbit(whole);
    }
    text.remove_prefix(nl + 1);
  }
  return o;
}

struct PortraitGrid::Impl {
  PortraitRequest request;
  std::unique_ptr<OrbitsBase> orbits;
};

PortraitGrid::PortraitGrid(const PortraitRequest& r) : impl_(new Impl{r, nullptr}) {
  check_portrait(r);
  with_point_scalar(r.precision, [&](auto tag) {
    impl_->orbits = std::make_unique<Orbits<typename decltype(tag)::type>>(impl_->request);
  });
}
PortraitGrid::~PortraitGrid() = default;
const PortraitRequest& PortraitGrid::request() const { return impl_->request; }

GridPlan PortraitGrid::plan() const {
  GridPlan plan;
  plan.items = static_cast<long>(impl_->request.starts.size());
  plan.tile_items = 1;
  return plan;
}

double PortraitGrid::item_bytes() const { return 60.0 * static_cast<double>(impl_->request.steps) + 64; }

PortraitOrbit PortraitGrid::orbit(long k) const { return impl_->orbits->orbit(k); }
std::string PortraitGrid::item(long k) const { return encode(orbit(k)); }
PortraitResult PortraitGrid::result(std::vector<PortraitOrbit> orbits) const { return {impl_->request, std::move(orbits)}; }

PortraitResult portrait(const PortraitRequest& r, const GridOptions& run) {
  const PortraitGrid grid(r);
  return grid.result(decode_cells<PortraitOrbit>(run_in_memory(grid.plan(), [&](long k) { return grid.item(k); }, run)));
}

}  // namespace bouncer
