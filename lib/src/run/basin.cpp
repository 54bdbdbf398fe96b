// Basins of attraction (run/basin.hpp).
#include "bouncer/run/basin.hpp"

#include <charconv>
#include <stdexcept>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/run/cells.hpp"

namespace bouncer {

namespace {

void check_basin(const BasinRequest& r, bool certified) {
  if (r.nx < 1 || r.ny < 1 || r.nx > 8192 || r.ny > 8192)
    throw InputError("grid", "must be NxM with 1 <= N, M <= 8192 (got " + std::to_string(r.nx) + "x" + std::to_string(r.ny) + ")");
  if (!(r.theta_lo < r.theta_hi)) throw InputError("theta-range", "needs LO < HI");
  if (r.theta_lo < Decimal::from_int(0) || r.theta_hi > Decimal::from_int(1))
    throw InputError("theta-range", "must lie in [0, 1] (got '" + r.theta_lo.text() + ":" + r.theta_hi.text() + "')");
  if (r.v_range) {
    if (!(r.v_range->first < r.v_range->second)) throw InputError("v-range", "needs LO < HI");
    if (r.v_range->second.approx() > 1e15 || r.v_range->first.approx() < -1e15)
      throw InputError("v-range", "must lie within +-1e15");
  }
  if (!r.precision.is_analysis())
    throw InputError("precision", "interval precision is not supported here (use " +
                                      precision_names<AnalysisScalars>(" or ") + ")");
  check_confirm(r.confirm);
  if (certified && r.confirm.on)
    throw InputError("confirm", "is not used with --certify (which compares double's class with the certified one)");
  if (certified) {
    require_certified_model(r.model, "basin");
    if (r.precision.kind != Precision::Kind::double_)
      throw InputError("precision", "with --certify the twin run is double (the artefact map compares double with the "
                                    "certified answer); got '" + r.precision.text() + "'");
  }
}

struct GridBase {
  virtual ~GridBase() = default;
  virtual bool outside(long i) const = 0;
  // Start i classified (whether or not it lies inside the phase space).
  virtual Classification classification(long i) const = 0;
  virtual AttractorCell cell(long i) const = 0;
  // cell(i) for every i of `cells`, the starts inside classified together (classify_many).
  virtual void cells(const std::vector<long>& cells, AttractorCell* out) const = 0;
  virtual CertifiedCell certified_cell(long i) const = 0;
  virtual std::vector<Number> theta() const = 0;
  virtual std::vector<Number> v() const = 0;
};

template <class T>
struct Grid final : GridBase {
  using Tr = ScalarTraits<T>;
  const BasinRequest& r;
  ImpactMap<T> map;
  T t0, t1, v0, v1;
  mutable ReleaseCache releases;  // certified: release orbits shared by every start

  T num(const Decimal& d) const { return Tr::from_decimal(d.text(), r.precision.bits); }
  explicit Grid(const BasinRequest& req)
      : r(req), map(make_model<T>(req.model, req.precision.bits)), t0(num(req.theta_lo)), t1(num(req.theta_hi)),
        v0(num(req.v_range->first)), v1(num(req.v_range->second)) {}

  T theta_at(long col) const { return cell_centre(t0, t1, col, r.nx); }
  T v_at(long row) const { return cell_centre(v0, v1, row, r.ny); }
  bool outside(const T& theta, const T& v) const {
    const auto& wall = map.model().wall;
    return v < wall.velocity_at(theta);
  }

  bool outside(long i) const override { return outside(theta_at(i % r.nx), v_at(i / r.nx)); }
  Classification classification(long i) const override {
    return classify<T>(map, State<T>{theta_at(i % r.nx), v_at(i / r.nx)}, r.classify);
  }

  // One cell: cells() of one (classify_many of one start is classify, bit for bit).
  AttractorCell cell(long i) const override {
    AttractorCell out;
    cells({i}, &out);
    return out;
  }

  void cells(const std::vector<long>& is, AttractorCell* out) const override {
    std::vector<State<T>> starts;
    std::vector<size_t> inside;
    for (size_t k = 0; k < is.size(); ++k) {
      const T theta = theta_at(is[k] % r.nx), v = v_at(is[k] / r.nx);
      out[k] = AttractorCell{};
      if (outside(theta, v)) {
        out[k].cls = OrbitClass::outside;
      } else {
        starts.push_back(State<T>{theta, v});
        inside.push_back(k);
      }
    }
    const std::vector<Classification> c = classify_many<T>(map, starts, r.classify);
    for (size_t m = 0; m < inside.size(); ++m) {
      out[inside[m]].cls = c[m].cls;
      out[inside[m]].period = c[m].period;
    }
  }

  CertifiedCell certified_cell(long i) const override {
    const T theta = theta_at(i % r.nx), v = v_at(i / r.nx);
    if (outside(theta, v)) return CertifiedCell::outside();
    // The exact start: the grid point itself (a dyadic number, printed exactly).
    const InitialCondition start{*Decimal::parse(exact_decimal(mpq_class(Tr::to_double(theta)))),
                                 *Decimal::parse(exact_decimal(mpq_class(Tr::to_double(v))))};
    return certified_with_twin(certify_point(r.model, start, r.cert, releases),
                               classify<T>(map, State<T>{theta, v}, r.classify));
  }

  std::vector<Number> theta() const override { return axis(r.nx, [&](long k) { return theta_at(k); }); }
  std::vector<Number> v() const override { return axis(r.ny, [&](long k) { return v_at(k); }); }
};

}  // namespace

std::pair<Decimal, Decimal> basin_v_range(const BasinRequest& r) { return starts_v_range(r.model, r.v_range); }

namespace {
std::unique_ptr<GridBase> make_grid(const BasinRequest& r) {
  std::unique_ptr<GridBase> g;
  with_point_scalar(r.precision, [&](auto tag) { g = std::make_unique<Grid<typename decltype(tag)::type>>(r); });
  return g;
}
}  // namespace

struct BasinGrid::Impl {
  BasinRequest request;
  bool certified;
  std::unique_ptr<GridBase> grid;
  long stride = 1;  // --confirm: the sample's lattice (run/cells.hpp)
  // --confirm: the same grid at the check's two precisions (requests first: the grids refer to them).
  BasinRequest check_request[2];
  std::unique_ptr<GridBase> check[2];
};

BasinGrid::BasinGrid(const BasinRequest& r, bool certified) : impl_(new Impl{r, certified, nullptr, 1, {}, {}}) {
  check_basin(r, certified);
  impl_->request.v_range = basin_v_range(r);
  impl_->grid = make_grid(impl_->request);
  if (r.confirm.on) {
    impl_->stride = bouncer::confirm_stride(r.nx, r.ny, 1, r.confirm.sample);
    const std::pair<Precision, Precision> p = check_precisions(r.precision, r.confirm.bits);
    for (int k = 0; k < 2; ++k) {
      impl_->check_request[k] = impl_->request;
      impl_->check_request[k].precision = k == 0 ? p.first : p.second;
      impl_->check[k] = make_grid(impl_->check_request[k]);
    }
  }
}
BasinGrid::~BasinGrid() = default;

const BasinRequest& BasinGrid::request() const { return impl_->request; }

GridPlan BasinGrid::plan() const {
  const long items = impl_->request.nx * impl_->request.ny;
  return point_grid_plan(items, impl_->certified ? 16 : 256);
}

std::string BasinGrid::item(long i) const {
  return impl_->certified ? encode(impl_->grid->certified_cell(i)) : encode(cell(i));
}
long BasinGrid::group() const { return impl_->certified ? 1 : kStepLanes; }
void BasinGrid::items(long begin, long end, std::string* out) const {
  const Impl& m = *impl_;
  const BasinRequest& r = m.request;
  if (m.certified) {
    for (long i = begin; i < end; ++i) out[i - begin] = item(i);
    return;
  }
  // The --confirm sample's cells one by one (cell()); the others together.
  std::vector<long> together;
  for (long i = begin; i < end; ++i) {
    if (r.confirm.on && in_confirm_sample(i % r.nx, i / r.nx, r.nx, r.ny, m.stride))
      out[i - begin] = encode(cell(i));
    else
      together.push_back(i);
  }
  std::vector<AttractorCell> cells(together.size());
  m.grid->cells(together, cells.data());
  for (size_t k = 0; k < together.size(); ++k) out[together[k] - begin] = encode(cells[k]);
}

AttractorCell BasinGrid::cell(long i) const {
  const Impl& m = *impl_;
  const BasinRequest& r = m.request;
  if (!r.confirm.on || !in_confirm_sample(i % r.nx, i / r.nx, r.nx, r.ny, m.stride) || m.grid->outside(i))
    return m.grid->cell(i);
  // The same cell centre at the check's precisions (as classify reads its decimal start at
  // each precision); its test for "outside" is the run's.
  return confirmed_cell(check_precision(m.grid->classification(i), r.precision, r.confirm.bits, [&](const Precision& p) {
    return m.check[p.bits == m.check_request[0].precision.bits ? 0 : 1]->classification(i);
  }));
}
long BasinGrid::confirm_stride() const { return impl_->stride; }
CertifiedCell BasinGrid::certified_cell(long i) const { return impl_->grid->certified_cell(i); }

BasinResult BasinGrid::result(std::vector<AttractorCell> cells) const {
  return {impl_->request, impl_->grid->theta(), impl_->grid->v(), std::move(cells)};
}
CertifiedBasinResult BasinGrid::certified_result(std::vector<CertifiedCell> cells) const {
  return {impl_->request, impl_->grid->theta(), impl_->grid->v(), std::move(cells)};
}

BasinResult basin(const BasinRequest& r, const GridOptions& run) {
  const BasinGrid grid(r, false);
  return grid.result(decode_cells<AttractorCell>(
      run_in_memory(grid.plan(), grid.group(), [&](long b, long e, std::string* out) { grid.items(b, e, out); }, run)));
}

CertifiedBasinResult certified_basin(const BasinRequest& r, const GridOptions& run) {
  const BasinGrid grid(r, true);
  return grid.certified_result(
      decode_cells<CertifiedCell>(run_in_memory(grid.plan(), [&](long i) { return grid.item(i); }, run)));
}

}  // namespace bouncer
