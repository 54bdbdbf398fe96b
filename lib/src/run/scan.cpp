// Parameter-space scans (run/scan.hpp).
#include "bouncer/run/scan.hpp"

#include <charconv>
#include <stdexcept>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/trapping.hpp"

namespace bouncer {

namespace {

void check_scan(const ScanRequest& r, bool certified) {
  const Parameter y = scan_parameter(r.model);
  const std::string yr = std::string(name(y)) + "-range";
  if (!(r.a_lo < r.a_hi)) throw InputError("a-range", "needs LO < HI");
  if (!(r.y_lo < r.y_hi)) throw InputError(yr, "needs LO < HI");
  for (const Decimal& a : {r.a_lo, r.a_hi})
    for (const Decimal& yv : {r.y_lo, r.y_hi}) {
      try {
        validate(with_parameter(with_parameter(r.model, Parameter::a, a), y, yv));
      } catch (const InputError& e) {
        throw InputError(e.field == "a" ? "a-range" : e.field == name(y) ? yr : e.field, e.what());
      }
    }
  if (r.p < 1 || r.q < 1 || r.p > 4096 || r.q > 4096)
    throw InputError("grid", "must be PxQ with 1 <= P, Q <= 4096 (got " + std::to_string(r.p) + "x" + std::to_string(r.q) + ")");
  if (r.k < 1 || r.k > 1000) throw InputError("ics", "must be an integer in [1, 1000] (got " + std::to_string(r.k) + ")");
  if (!(r.theta_lo < r.theta_hi)) throw InputError("theta-range", "needs LO < HI");
  if (r.theta_lo < Decimal::from_int(0) || r.theta_hi > Decimal::from_int(1)) throw InputError("theta-range", "must lie in [0, 1]");
  if (r.v_range) {
    if (!(r.v_range->first < r.v_range->second)) throw InputError("v-range", "needs LO < HI");
    if (r.v_range->second.approx() > 1e15 || r.v_range->first.approx() < -1e15)
      throw InputError("v-range", "must lie within +-1e15");
  } else if (y == Parameter::eps && r.y_hi == Decimal::from_int(1) && !certified) {
    throw InputError("v-range", "is needed when eps reaches 1 (the trapping region 4(1+3eps)/(1-eps) is unbounded)");
  }
  if (!r.precision.is_analysis())
    throw InputError("precision", "interval precision is not supported here (use " +
                                      precision_names<AnalysisScalars>(" or ") + ")");
  check_confirm(r.confirm);
  if (certified && r.confirm.on)
    throw InputError("confirm", "is not used with --certify (which compares double's class with the certified one)");
  if (certified) {
    require_certified_model(r.model, "scan");
    if (r.precision.kind != Precision::Kind::double_)
      throw InputError("precision", "with --certify the twin run is double (the artefact map compares double with the "
                                    "certified answer); got '" + r.precision.text() + "'");
    if (!r.start_at_release) validate(r.model, r.start, "theta", "v");  // the wall does not depend on (a, eps): valid at every point
  }
}

struct GridBase {
  virtual ~GridBase() = default;
  virtual bool outside(long i, long j) const = 0;
  virtual Classification classification(long i, long j) const = 0;
  virtual std::pair<Number, Number> start(long i, long j) const = 0;
  virtual ScanCell cell(long i) const = 0;
  virtual std::vector<StartLabel> labels(long i) const = 0;
  virtual CertifiedCell certified_cell(long i) const = 0;
  virtual std::vector<Number> a(bool exact) const = 0;
  virtual std::vector<Number> y(bool exact) const = 0;
};

template <class T>
struct Grid final : GridBase {
  using Tr = ScalarTraits<T>;
  const ScanRequest& r;
  Parameter py;
  Model<T> base;
  T a0, a1, y0, y1, t0, t1, v0, v1;
  T num(const Decimal& d) const { return Tr::from_decimal(d.text(), r.precision.bits); }
  explicit Grid(const ScanRequest& req)
      : r(req), py(scan_parameter(req.model)), base(make_model<T>(req.model, req.precision.bits)), a0(num(req.a_lo)),
        a1(num(req.a_hi)), y0(num(req.y_lo)), y1(num(req.y_hi)), t0(num(req.theta_lo)), t1(num(req.theta_hi)),
        v0(num(req.v_range ? req.v_range->first : req.a_lo)), v1(num(req.v_range ? req.v_range->second : req.a_hi)) {}

  T a_at(long col) const { return cell_centre(a0, a1, col, r.p); }
  T y_at(long row) const { return cell_centre(y0, y1, row, r.q); }
  Model<T> model_at(long i) const { return with_parameter(with_parameter(base, Parameter::a, a_at(i % r.p)), py, y_at(i / r.p)); }
  // The exact decimal of a double centre: the parameter a certified point states.
  static Number exact(const T& x) {
    const double d = Tr::to_double(x);
    return {d, exact_decimal(mpq_class(d))};
  }

  // Start j of the starts at model m: the k x k cell centres of the theta range and of the v
  // range, by default the trapping region of this point (model/trapping.hpp), from the wall's
  // fastest upward velocity; eps = 1 needs a v range (refused by check_scan).
  State<T> start_of(const Model<T>& m, long j) const {
    const T vlo = r.v_range ? v0 : wall_up_speed(m.wall);
    const T vhi = r.v_range ? v1 : trapping_top(m).value();
    return {cell_centre(t0, t1, j % r.k, r.k), cell_centre(vlo, vhi, j / r.k, r.k)};
  }
  static bool outside_at(const Model<T>& m, const State<T>& x) { return x.v < m.wall.velocity_at(x.theta); }

  bool outside(long i, long j) const override {
    const Model<T> m = model_at(i);
    return outside_at(m, start_of(m, j));
  }
  Classification classification(long i, long j) const override {
    const Model<T> m = model_at(i);
    return classify<T>(ImpactMap<T>(m), start_of(m, j), r.classify);
  }
  std::pair<Number, Number> start(long i, long j) const override {
    const State<T> x = start_of(model_at(i), j);
    return {number_of(x.theta), number_of(x.v)};
  }

  // The point's starts inside the phase space, classified side by side (classify_many, with
  // the request's re-check rule).
  std::vector<StartLabel> labels(long i) const override {
    const Model<T> m = model_at(i);
    const ImpactMap<T> map(m);
    std::vector<State<T>> inside;
    std::vector<long> index;
    for (long j = 0; j < r.k * r.k; ++j) {
      const State<T> x = start_of(m, j);
      if (!outside_at(m, x)) {
        inside.push_back(x);
        index.push_back(j);
      }
    }
    std::vector<Classification> c = classify_many<T>(map, inside, r.classify);
    std::vector<StartLabel> out;
    for (size_t n = 0; n < c.size(); ++n) out.push_back({index[n], std::move(c[n])});
    return out;
  }

  ScanCell cell(long i) const override {
    ScanCell c;
    const std::vector<StartLabel> inside = labels(i);
    c.count[static_cast<size_t>(OrbitClass::outside)] = r.k * r.k - static_cast<long>(inside.size());
    for (const StartLabel& s : inside) ++c.count[static_cast<size_t>(s.label.cls)];
    return c;
  }

  CertifiedCell certified_cell(long i) const override {
    ModelSpec spec = r.model;
    spec.a = *Decimal::parse(exact(a_at(i % r.p)).digits);
    (py == Parameter::eps ? spec.eps : spec.c) = *Decimal::parse(exact(y_at(i / r.p)).digits);
    ReleaseCache releases;  // parameters differ from point to point: nothing to share
    const CertifiedPoint c =
        r.start_at_release ? certify_release_point(spec, r.cert, releases) : certify_point(spec, r.start, r.cert, releases);
    const Model<T> m = model_at(i);
    const ImpactMap<T> map(m);
    return certified_with_twin(c, classify<T>(map, r.start_at_release ? release_state(m) : make_state<T>(r.start, r.precision.bits),
                                              r.classify));
  }

  std::vector<Number> a(bool ex) const override {
    return ex ? axis_of(r.p, [&](long k) { return exact(a_at(k)); }) : axis(r.p, [&](long k) { return a_at(k); });
  }
  std::vector<Number> y(bool ex) const override {
    return ex ? axis_of(r.q, [&](long k) { return exact(y_at(k)); }) : axis(r.q, [&](long k) { return y_at(k); });
  }
  template <class F>
  static std::vector<Number> axis_of(long n, F&& at) {
    std::vector<Number> out;
    for (long k = 0; k < n; ++k) out.push_back(at(k));
    return out;
  }
};

}  // namespace

Parameter scan_parameter(const ModelSpec& m) {
  if (m.law == Law::elastic) throw InputError("model", "scan needs an inelastic model (constant: a x eps; veldep: a x c)");
  return m.law == Law::constant ? Parameter::eps : Parameter::c;
}

const std::vector<OrbitClass>& scan_classes() {
  static const std::vector<OrbitClass> c{OrbitClass::fixed,         OrbitClass::periodic,  OrbitClass::sticking,
                                         OrbitClass::quasiperiodic, OrbitClass::chaotic,   OrbitClass::unbounded,
                                         OrbitClass::effective_sticking, OrbitClass::transient_chaos,
                                         OrbitClass::undecided,     OrbitClass::outside};
  return c;
}

long ScanCell::total() const {
  long n = 0;
  for (long c : count) n += c;
  return n;
}

std::string encode(const ScanCell& c) {
  // Appended piece by piece: GCC 12 reports a false -Wrestrict on `"," + std::to_string(...)`.
  std::string s;
  for (OrbitClass k : scan_classes()) {
    if (!s.empty()) s += ',';
    s += std::to_string(c[k]);
  }
  if (c.confirmed) {
    // "|agrees,artefact,precision_dependent|j j ..."
    for (int i = 0; i < 3; ++i) {
      s += i ? ',' : '|';
      s += std::to_string(c.verdicts[i]);
    }
    s += '|';
    for (size_t n = 0; n < c.artefacts.size(); ++n) {
      if (n) s += ' ';
      s += std::to_string(c.artefacts[n]);
    }
  }
  return s;
}

namespace {
// The numbers of a text "n<sep>n<sep>...", all >= 0; false if it is anything else.
bool read_counts(std::string_view text, char sep, std::vector<long>& out) {
  out.clear();
  if (text.empty()) return true;
  const char* at = text.data();
  const char* const end = text.data() + text.size();
  while (true) {
    long n = -1;
    const auto r = std::from_chars(at, end, n);
    if (r.ec != std::errc() || n < 0) return false;
    out.push_back(n);
    if (r.ptr == end) return true;
    if (*r.ptr != sep) return false;
    at = r.ptr + 1;
  }
}
}  // namespace

template <>
ScanCell decode_cell<ScanCell>(std::string_view full) {
  ScanCell c;
  std::string_view text = full;
  if (const size_t bar = full.find('|'); bar != std::string_view::npos) {
    text = full.substr(0, bar);
    const std::string_view rest = full.substr(bar + 1);
    const size_t bar2 = rest.find('|');
    std::vector<long> v, j;
    if (bar2 == std::string_view::npos || !read_counts(rest.substr(0, bar2), ',', v) || v.size() != 3 ||
        !read_counts(rest.substr(bar2 + 1), ' ', j) || static_cast<long>(j.size()) != v[1])
      throw std::runtime_error("a grid tile holds a scan cell no bouncer wrote: '" + std::string(full.substr(0, 80)) + "'");
    c.confirmed = true;
    for (size_t k = 0; k < 3; ++k) c.verdicts[k] = v[k];
    c.artefacts = j;
  }
  const char* at = text.data();
  const char* const end = text.data() + text.size();
  for (OrbitClass k : scan_classes()) {
    const bool last = k == scan_classes().back();
    long n = -1;
    const auto r = std::from_chars(at, end, n);
    if (r.ec != std::errc() || n < 0 || (last ? r.ptr != end : (r.ptr == end || *r.ptr != ',')))
      throw std::runtime_error("a grid tile holds a scan cell no bouncer wrote: '" + std::string(text.substr(0, 80)) + "'");
    c.count[static_cast<size_t>(k)] = n;
    at = r.ptr + (last ? 0 : 1);
  }
  return c;
}

namespace {
std::unique_ptr<GridBase> make_grid(const ScanRequest& r) {
  std::unique_ptr<GridBase> g;
  with_point_scalar(r.precision, [&](auto tag) { g = std::make_unique<Grid<typename decltype(tag)::type>>(r); });
  return g;
}
}  // namespace

struct ScanGrid::Impl {
  ScanRequest request;
  bool certified;
  Parameter y;
  std::unique_ptr<GridBase> grid;
  long stride = 1;  // --confirm: the sample's lattice over the parameter points (run/cells.hpp)
  // --confirm: the same grid at the check's two precisions (requests first: the grids refer to them).
  ScanRequest check_request[2];
  std::unique_ptr<GridBase> check[2];
};

ScanGrid::ScanGrid(const ScanRequest& r, bool certified) : impl_(new Impl{r, certified, scan_parameter(r.model), nullptr, 1, {}, {}}) {
  check_scan(r, certified);
  impl_->grid = make_grid(impl_->request);
  if (r.confirm.on) {
    impl_->stride = bouncer::confirm_stride(r.p, r.q, r.k * r.k, r.confirm.sample);
    const std::pair<Precision, Precision> p = check_precisions(r.precision, r.confirm.bits);
    for (int k = 0; k < 2; ++k) {
      impl_->check_request[k] = impl_->request;
      impl_->check_request[k].precision = k == 0 ? p.first : p.second;
      impl_->check[k] = make_grid(impl_->check_request[k]);
    }
  }
}
ScanGrid::~ScanGrid() = default;
const ScanRequest& ScanGrid::request() const { return impl_->request; }
Parameter ScanGrid::y() const { return impl_->y; }
GridPlan ScanGrid::plan() const { return point_grid_plan(impl_->request.p * impl_->request.q, impl_->certified ? 4 : 16); }
std::string ScanGrid::item(long i) const {
  return impl_->certified ? encode(impl_->grid->certified_cell(i)) : encode(cell(i));
}
ScanCell ScanGrid::cell(long i) const {
  const Impl& m = *impl_;
  const ScanRequest& r = m.request;
  ScanCell c = m.grid->cell(i);
  if (!r.confirm.on || !in_confirm_sample(i % r.p, i / r.p, r.p, r.q, m.stride)) return c;
  // Every start of the point inside the phase space, again at the check's precisions (the
  // parameters and starts are the same cell centres, computed at each precision).
  c.confirmed = true;
  for (long j = 0; j < r.k * r.k; ++j) {
    if (m.grid->outside(i, j)) continue;
    const CheckedClassification k =
        check_precision(m.grid->classification(i, j), r.precision, r.confirm.bits, [&](const Precision& p) {
          return m.check[p.bits == m.check_request[0].precision.bits ? 0 : 1]->classification(i, j);
        });
    ++c.verdicts[static_cast<size_t>(k.verdict)];
    if (k.verdict == PrecisionVerdict::artefact) c.artefacts.push_back(j);
  }
  return c;
}
long ScanGrid::confirm_stride() const { return impl_->stride; }
std::pair<Number, Number> ScanGrid::start(long i, long j) const { return impl_->grid->start(i, j); }
std::vector<StartLabel> ScanGrid::labels(long i) const { return impl_->grid->labels(i); }
CertifiedCell ScanGrid::certified_cell(long i) const { return impl_->grid->certified_cell(i); }
ScanResult ScanGrid::result(std::vector<ScanCell> cells) const {
  return {impl_->request, impl_->y, impl_->grid->a(false), impl_->grid->y(false), std::move(cells)};
}
CertifiedScanResult ScanGrid::certified_result(std::vector<CertifiedCell> cells) const {
  return {impl_->request, impl_->y, impl_->grid->a(true), impl_->grid->y(true), std::move(cells)};
}

ScanResult scan(const ScanRequest& r, const GridOptions& run) {
  const ScanGrid grid(r, false);
  return grid.result(decode_cells<ScanCell>(run_in_memory(grid.plan(), [&](long i) { return grid.item(i); }, run)));
}

CertifiedScanResult certified_scan(const ScanRequest& r, const GridOptions& run) {
  const ScanGrid grid(r, true);
  return grid.certified_result(
      decode_cells<CertifiedCell>(run_in_memory(grid.plan(), [&](long i) { return grid.item(i); }, run)));
}

}  // namespace bouncer
