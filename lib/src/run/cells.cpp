// Grid cells and their tile texts (run/cells.hpp).
#include "bouncer/run/cells.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>

#include "bouncer/model/trapping.hpp"

namespace bouncer {

namespace {

// The comma-separated fields of a tile text.
std::vector<std::string_view> fields(std::string_view text) {
  std::vector<std::string_view> out;
  size_t from = 0;
  while (true) {
    const size_t comma = text.find(',', from);
    out.push_back(text.substr(from, comma == std::string_view::npos ? std::string_view::npos : comma - from));
    if (comma == std::string_view::npos) return out;
    from = comma + 1;
  }
}

[[noreturn]] void bad_cell(std::string_view text) {
  throw std::runtime_error("a grid tile holds a cell no bouncer wrote: '" + std::string(text.substr(0, 80)) + "'");
}

template <class I>
I whole(std::string_view s, std::string_view text) {
  I v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) bad_cell(text);
  return v;
}

template <class E>
E named(std::optional<E> e, std::string_view text) {
  if (!e) bad_cell(text);
  return *e;
}

}  // namespace

std::string encode(const AttractorCell& c) {
  std::string s = std::string(name(c.cls)) + ',' + std::to_string(c.period);
  if (c.confirm)
    s += std::string(",") + name(*c.confirm) + ',' + name(c.check_cls) + ',' + std::to_string(c.check_period) + ',' +
         c.differs_in;
  return s;
}

template <>
AttractorCell decode_cell<AttractorCell>(std::string_view text) {
  const auto f = fields(text);
  if (f.size() != 2 && f.size() != 6) bad_cell(text);
  AttractorCell c = attractor_cell(named(orbit_class_named(f[0]), text), whole<long>(f[1], text));
  if (f.size() == 6) {
    for (PrecisionVerdict v : {PrecisionVerdict::agrees, PrecisionVerdict::artefact, PrecisionVerdict::precision_dependent})
      if (f[2] == name(v)) c.confirm = v;
    if (!c.confirm) bad_cell(text);
    c.check_cls = named(orbit_class_named(f[3]), text);
    c.check_period = whole<long>(f[4], text);
    // behaviour_difference's words: lower-case letters, digits, '_' and spaces, short.
    if (f[5].size() > 80 || !std::all_of(f[5].begin(), f[5].end(), [](char ch) {
          return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == ' ' || ch == '_';
        }))
      bad_cell(text);
    c.differs_in = std::string(f[5]);
  }
  return c;
}

namespace {
// The lattice along one axis of n units: offset (min(s, n) - 1) / 2 of every block of s.
long lattice_offset(long n, long s) { return (std::min(s, n) - 1) / 2; }
long lattice_count(long n, long s) { return (n - 1 - lattice_offset(n, s)) / s + 1; }
}  // namespace

void check_confirm(const GridConfirm& c) {
  if (!c.on) return;
  if (c.bits < 64 || c.bits > kMaxBits)
    throw InputError("confirm", "must be a number of bits in [64, " + std::to_string(kMaxBits) + "] (got " +
                                    std::to_string(c.bits) + ")");
  if (c.sample < 0) throw InputError("confirm-sample", "must be a number of starts >= 1 or all");
}

long confirm_stride(long ux, long uy, long per_unit, long sample) {
  if (sample <= 0) return 1;
  long s = 1;
  while (s < std::max(ux, uy) && confirm_sample_units(ux, uy, s) * per_unit > sample) ++s;
  return s;
}

bool in_confirm_sample(long x, long y, long ux, long uy, long stride) {
  return x % stride == lattice_offset(ux, stride) && y % stride == lattice_offset(uy, stride);
}

long confirm_sample_units(long ux, long uy, long stride) { return lattice_count(ux, stride) * lattice_count(uy, stride); }

AttractorCell confirmed_cell(const CheckedClassification& check) {
  AttractorCell c = attractor_cell(check.result.cls, check.result.period);
  c.confirm = check.verdict;
  c.check_cls = check.checks.at(0).result.cls;
  c.check_period = check.checks.at(0).result.period;
  c.differs_in = behaviour_difference(check.result, check.checks.at(0).result);
  return c;
}

std::string encode(const CertifiedCell& c) {
  std::string s = name(c.cls);
  s += ',' + std::to_string(c.period) + ',' + std::to_string(c.certified_steps) + ',' + c.scalar + ',' +
       name(c.double_class) + ',' + std::to_string(c.double_period) + ',' + name(c.agreement);
  return s;
}

template <>
CertifiedCell decode_cell<CertifiedCell>(std::string_view text) {
  const auto f = fields(text);
  if (f.size() != 7) bad_cell(text);
  CertifiedCell c;
  c.cls = named(certified_class_named(f[0]), text);
  c.period = whole<long>(f[1], text);
  c.certified_steps = whole<long long>(f[2], text);
  c.scalar = std::string(f[3]);
  c.double_class = named(orbit_class_named(f[4]), text);
  c.double_period = whole<long>(f[5], text);
  c.agreement = named(agreement_named(f[6]), text);
  return c;
}

CertifiedCell certified_with_twin(const CertifiedPoint& c, const Classification& twin) {
  return {c.cls, c.period, c.certified_steps, c.scalar, twin.cls, twin.period, compare_with_certified(c, twin.cls, twin.period)};
}

std::pair<Decimal, Decimal> starts_v_range(const ModelSpec& m, const std::optional<std::pair<Decimal, Decimal>>& given) {
  if (given) return *given;
  const auto range = trapping_v_range(m);
  if (!range && m.law == Law::constant)
    throw InputError("v-range", "is needed when eps = 1 (the trapping region 4(1+3eps)/(1-eps) is unbounded)");
  if (!range) throw InputError("v-range", "is needed for --model elastic (no trapping region: velocities grow without bound)");
  return *range;
}

void check_varied_range(const ModelSpec& m, Parameter vary, const Decimal& lo, const Decimal& hi) {
  if (vary == Parameter::eps && m.law != Law::constant) throw InputError("vary", "eps can only vary with --model constant");
  if (vary == Parameter::c && m.law != Law::veldep) throw InputError("vary", "c can only vary with --model veldep");
  if (!(lo < hi)) throw InputError("range", "needs LO < HI");
  for (const Decimal& end : {lo, hi}) {
    try {
      validate(with_parameter(m, vary, end));
    } catch (const InputError& e) {
      throw InputError("range", "end " + end.text() + " is outside the model's range (" + e.what() + ")");
    }
  }
}

GridPlan point_grid_plan(long items, long max_tile) {
  GridPlan plan;
  plan.items = items;
  plan.tile_items = std::max<long>(1, std::min<long>(max_tile, items / 64 + 1));
  return plan;
}

std::vector<std::string> run_in_memory(const GridPlan& plan, const std::function<std::string(long)>& item,
                                       const GridOptions& run) {
  return run_in_memory(plan, 1, [&item](long i, long, std::string* out) { *out = item(i); }, run);
}

std::vector<std::string> run_in_memory(const GridPlan& plan, long group,
                                       const std::function<void(long, long, std::string*)>& items, const GridOptions& run) {
  GridOptions g = run;
  g.tile_dir.clear();
  g.shard = Shard{};
  g.compute = true;
  GridResult r = run_grid(plan, group, items, g);
  if (!r.complete()) throw std::runtime_error("grid: tiles missing after an in-memory run");
  return std::move(r.items);
}

}  // namespace bouncer
