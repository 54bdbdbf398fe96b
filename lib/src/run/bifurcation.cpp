// Bifurcation diagrams (run/bifurcation.hpp).
#include "bouncer/run/bifurcation.hpp"

#include <charconv>
#include <sstream>
#include <stdexcept>

#include "bouncer/model/impact_map.hpp"

namespace bouncer {

namespace {

void check_bifurcation(const BifurcationRequest& r) {
  check_varied_range(r.model, r.vary, r.lo, r.hi);
  if (r.samples < 1 || r.samples > 100000) throw InputError("samples", "must be an integer in [1, 100000]");
  if (r.transient < 0 || r.transient > 100000000) throw InputError("transient", "must be an integer in [0, 100000000]");
  if (r.record < 1 || r.record > 1000000) throw InputError("record", "must be an integer in [1, 1000000]");
  if (static_cast<double>(r.samples) * static_cast<double>(r.record) > 5e7)
    throw InputError("record", "samples x record must be at most 5e7 rows (got " + std::to_string(r.samples) + " x " +
                                   std::to_string(r.record) + ")");
  validate(with_parameter(r.model, r.vary, r.lo), r.start, "theta", "v");
  if (!r.precision.is_analysis()) throw InputError("precision", "interval precision is not supported here");
  if (r.certify) {
    require_certified_model(r.model, "bifurcation");
    if (r.carry) throw InputError("carry", "cannot be used with --certify (each column is certified from its own start)");
    if (r.precision.kind != Precision::Kind::double_)
      throw InputError("precision", "with --certify the twin run is double; got '" + r.precision.text() + "'");
  }
}

struct SweepBase {
  virtual ~SweepBase() = default;
  virtual BifurcationColumn column(long k) = 0;
};

template <class T>
struct Sweep final : SweepBase {
  using Tr = ScalarTraits<T>;
  const BifurcationRequest& r;
  Model<T> base;
  T lo, hi;
  std::optional<State<T>> carried;  // carry: the last state of the previous value

  explicit Sweep(const BifurcationRequest& req)
      : r(req), base(make_model<T>(req.model, req.precision.bits)),
        lo(Tr::from_decimal(req.lo.text(), req.precision.bits)), hi(Tr::from_decimal(req.hi.text(), req.precision.bits)) {}

  T param(long k) const { return r.samples == 1 ? lo : T(lo + (hi - lo) * k / (r.samples - 1)); }

  BifurcationColumn column(long k) override {
    const T p = param(k);
    const ImpactMap<T> map(with_parameter(base, r.vary, p));
    State<T> s = r.carry && carried ? *carried : make_state<T>(r.start, r.precision.bits);
    BifurcationColumn col;
    col.value = number_of(p);
    col.points.reserve(static_cast<size_t>(r.record));
    long n = 0;
    try {
      for (; n < r.transient; ++n) s = map.step(s).next;
      for (long m = 0; m < r.record; ++m, ++n) {
        const StepResult<T> st = map.step(s);
        s = st.next;
        col.points.push_back({n + 1, number_of(s.theta), number_of(s.v), st.kind == EventKind::sticking});
      }
      carried = s;
    } catch (const Undecided& u) {
      col.undecided_step = n + 1;
      col.undecided_reason = u.what();
      carried.reset();
    }
    if (r.certify) certify(col, p, map);
    return col;
  }

  // The exact orbit at the exact value of p (a double: a dyadic number, a finite decimal).
  void certify(BifurcationColumn& col, const T& p, const ImpactMap<T>& map) const {
    if constexpr (std::is_same_v<T, double>) {
      CertifyPointOptions opt = r.cert;
      const std::string exact = exact_decimal(mpq_class(p));
      ModelSpec spec = with_parameter(r.model, r.vary, *Decimal::parse(exact));
      opt.max_attractor_period = std::min<long>(64, std::max<long>(1, r.record / 2));
      ReleaseCache releases;
      const CertifiedPoint c = certify_point(spec, r.start, opt, releases);
      ClassifyOptions co;
      co.transient = r.transient;
      co.steps = std::max<long>(8, r.record);
      co.max_period = opt.max_attractor_period;
      co.recheck_factor = 0;
      col.exact_value = exact;
      col.certified = certified_with_twin(c, classify<T>(map, make_state<T>(r.start, 53), co));
    } else {
      (void)col, (void)p, (void)map;  // refused by check_bifurcation
    }
  }
};

[[noreturn]] void bad_column(std::string_view text) {
  throw std::runtime_error("a grid tile holds a bifurcation column no bouncer wrote: '" + std::string(text.substr(0, 80)) + "'");
}

Number read_number(std::string_view digits) {
  std::string d(digits);
  const double v = std::strtod(d.c_str(), nullptr);
  return {v, std::move(d)};
}

}  // namespace

// The tile text of a column, one record a line: "P digits", "S n,theta,v,sticking" per
// point, "U step reason" when undecided, "C exact,<certified cell>" when certified.
std::string encode(const BifurcationColumn& c) {
  std::string s = "P " + c.value.digits + "\n";
  for (const BifurcationPoint& p : c.points)
    s += "S " + std::to_string(p.n) + ',' + p.theta.digits + ',' + p.v.digits + ',' + (p.sticking ? "1" : "0") + "\n";
  if (c.undecided_step) s += "U " + std::to_string(*c.undecided_step) + ' ' + c.undecided_reason + "\n";
  if (c.certified) s += "C " + c.exact_value.value_or("") + ',' + encode(*c.certified) + "\n";
  return s;
}

template <>
BifurcationColumn decode_cell<BifurcationColumn>(std::string_view text) {
  BifurcationColumn c;
  bool have_value = false;
  while (!text.empty()) {
    const size_t nl = text.find('\n');
    if (nl == std::string_view::npos || nl < 2 || text[1] != ' ') bad_column(text);
    const std::string_view line = text.substr(2, nl - 2);
    switch (text[0]) {
      case 'P':
        c.value = read_number(line);
        have_value = true;
        break;
      case 'S': {
        BifurcationPoint p;
        const size_t c1 = line.find(','), c2 = line.find(',', c1 + 1), c3 = line.find(',', c2 + 1);
        if (c3 == std::string_view::npos) bad_column(text);
        const auto r = std::from_chars(line.data(), line.data() + c1, p.n);
        if (r.ec != std::errc() || r.ptr != line.data() + c1) bad_column(text);
        p.theta = read_number(line.substr(c1 + 1, c2 - c1 - 1));
        p.v = read_number(line.substr(c2 + 1, c3 - c2 - 1));
        p.sticking = line.substr(c3 + 1) == "1";
        c.points.push_back(std::move(p));
        break;
      }
      case 'U': {
        const size_t sp = line.find(' ');
        long step = 0;
        const auto r = std::from_chars(line.data(), line.data() + std::min(sp, line.size()), step);
        if (r.ec != std::errc()) bad_column(text);
        c.undecided_step = step;
        c.undecided_reason = sp == std::string_view::npos ? "" : std::string(line.substr(sp + 1));
        break;
      }
      case 'C': {
        const size_t comma = line.find(',');
        if (comma == std::string_view::npos) bad_column(text);
        c.exact_value = std::string(line.substr(0, comma));
        c.certified = decode_cell<CertifiedCell>(line.substr(comma + 1));
        break;
      }
      default: bad_column(text);
    }
    text.remove_prefix(nl + 1);
  }
  if (!have_value) bad_column(text);
  return c;
}

struct BifurcationGrid::Impl {
  BifurcationRequest request;
  std::unique_ptr<SweepBase> sweep;
};

BifurcationGrid::BifurcationGrid(const BifurcationRequest& r) : impl_(new Impl{r, nullptr}) {
  check_bifurcation(r);
  with_point_scalar(r.precision, [&](auto tag) {
    impl_->sweep = std::make_unique<Sweep<typename decltype(tag)::type>>(impl_->request);
  });
}
BifurcationGrid::~BifurcationGrid() = default;
const BifurcationRequest& BifurcationGrid::request() const { return impl_->request; }

GridPlan BifurcationGrid::plan() const {
  const BifurcationRequest& r = impl_->request;
  GridPlan plan;
  plan.items = r.samples;
  // carry chains the values: one tile, computed in order by one worker.
  plan.tile_items = r.carry ? r.samples : std::max<long>(1, std::min<long>(16, r.samples / 64 + 1));
  return plan;
}

double BifurcationGrid::item_bytes() const { return 40.0 * static_cast<double>(impl_->request.record) + 64; }

BifurcationColumn BifurcationGrid::column(long k) { return impl_->sweep->column(k); }
std::string BifurcationGrid::item(long k) { return encode(column(k)); }

BifurcationResult bifurcation(const BifurcationRequest& r, const GridOptions& run) {
  BifurcationGrid grid(r);
  return {grid.request(),
          decode_cells<BifurcationColumn>(run_in_memory(grid.plan(), [&](long k) { return grid.item(k); }, run))};
}

}  // namespace bouncer
