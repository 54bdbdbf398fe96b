// The grid calls of the library (run/basin.hpp, run/scan.hpp, run/bifurcation.hpp) and their
// cells' tile texts (run/cells.hpp), against truth that does not come from the grid code:
//   * the eq. 5 fixed point (eps = 1/2, a = 24: theta = 1/4, v = 12, flight time one period)
//     is a fixed point of every grid that has it as a cell centre, and a bifurcation column
//     started on it stays on it;
//   * the release state (1/2, 4) sticks with period 1 for 8((1+eps)/(1-eps))^2 <= a < 32 (the
//     closed form in tests/README.md, "Continuation"; at eps = 1/4 that is 200/9 <= a < 32):
//     the certified basin's cell there says so, and double agrees;
//   * a start below the wall's velocity is "outside": on the triangle the wall moves at +4 on
//     one half of the period and -4 on the other, so v in (-4, 4) is outside on exactly one;
//   * a scan point's counts are those of a basin over the same k x k starts (two calls, one
//     answer), and sum to k x k;
//   * the results do not depend on the number of threads; a cancelled run throws Cancelled;
//   * a cell's tile text reads back to the same cell, and text no encoder wrote is refused.
#include <gtest/gtest.h>

#include <atomic>
#include <map>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/base/cancel.hpp"
#include "bouncer/run/basin.hpp"
#include "bouncer/run/bifurcation.hpp"
#include "bouncer/run/cells.hpp"
#include "bouncer/run/scan.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using test_support::spec;

Decimal dec(const char* s) { return *Decimal::parse(s); }

BasinRequest small_basin(const char* theta_range_lo, const char* theta_range_hi, const char* v_lo, const char* v_hi,
                         long nx, long ny) {
  BasinRequest r;
  r.model = spec(Law::constant, "24", "0.5");
  r.nx = nx;
  r.ny = ny;
  r.theta_lo = dec(theta_range_lo);
  r.theta_hi = dec(theta_range_hi);
  r.v_range = std::pair{dec(v_lo), dec(v_hi)};
  r.classify.transient = 200;
  r.classify.steps = 100;
  r.classify.max_period = 20;
  return r;
}

TEST(Grids, BasinCellAtTheEq5FixedPointIsFixed) {
  // One cell: its centre is (0.25, 12) exactly (the window's midpoint, dyadic).
  const BasinResult b = basin(small_basin("0.2", "0.3", "11", "13", 1, 1));
  ASSERT_EQ(b.cells.size(), 1u);
  EXPECT_EQ(b.theta[0].digits, "0.25");
  EXPECT_EQ(b.v[0].digits, "12");
  EXPECT_EQ(b.cells[0], attractor_cell(OrbitClass::fixed, 1));
}

TEST(Grids, BasinMarksStartsBelowTheWallOutside) {
  // theta = 1/4 and 3/4, v = -3.5: below the wall on its rising half only.
  const BasinResult b = basin(small_basin("0", "1", "-4", "-3", 2, 1));
  ASSERT_EQ(b.cells.size(), 2u);
  const int outside = (b.cells[0].cls == OrbitClass::outside) + (b.cells[1].cls == OrbitClass::outside);
  EXPECT_EQ(outside, 1);
  for (const AttractorCell& c : b.cells)
    if (c.cls == OrbitClass::outside) {
      EXPECT_EQ(c.period, 0);
    }
}

TEST(Grids, BasinDoesNotDependOnThreads) {
  const BasinRequest r = small_basin("0", "1", "4", "20", 9, 7);
  GridOptions one, two;
  one.threads = 1;
  two.threads = 2;
  EXPECT_EQ(basin(r, one).cells, basin(r, two).cells);
}

TEST(Grids, BasinCellsAreClassifyOfEachCentreAlone) {
  // basin classifies its cells four at a time (BasinGrid::items, classify_many, the batched
  // double step); each cell must be what classify() says of its centre alone, in double and
  // in a type without the batched step, on grids whose rows are not multiples of four and
  // with starts below the wall. Chaotic and sticking cells included (eps 0.9 at a = 19; eps
  // 0.5 at a = 24).
  for (const char* prec : {"double", "dd"})
    for (const auto& point : {std::pair{"19", "0.9"}, std::pair{"24", "0.5"}}) {
      const char* a = point.first;  // a variable, not a binding: the lambda below names it (clang 14)
      const char* eps = point.second;
      BasinRequest r = small_basin("0", "1", "-3", "30", 7, 5);
      r.model = spec(Law::constant, a, eps);
      r.precision = parse_precision("precision", prec);
      const BasinResult b = basin(r);
      ASSERT_EQ(b.cells.size(), 35u);
      std::map<OrbitClass, int> seen;
      with_point_scalar(r.precision, [&](auto tag) {
        using T = typename decltype(tag)::type;
        using Tr = ScalarTraits<T>;
        const ImpactMap<T> map(make_model<T>(r.model, r.precision.bits));
        for (long i = 0; i < 35; ++i) {
          auto num = [&](const Decimal& d) { return Tr::from_decimal(d.text(), r.precision.bits); };
          const T theta = cell_centre(num(r.theta_lo), num(r.theta_hi), i % 7, 7);
          const T v = cell_centre(num(r.v_range->first), num(r.v_range->second), i / 7, 5);
          const auto& wall = map.model().wall;
          AttractorCell want;
          if (v < wall.velocity[wall.segment_of(theta)]) {
            want.cls = OrbitClass::outside;
          } else {
            const Classification c = classify<T>(map, State<T>{theta, v}, r.classify);
            want.cls = c.cls;
            want.period = c.period;
          }
          EXPECT_EQ(b.cells[static_cast<size_t>(i)], want) << prec << " a " << a << " cell " << i;
          ++seen[want.cls];
        }
      });
      EXPECT_GT(seen[OrbitClass::outside], 0) << prec << " a " << a;
      EXPECT_GT(static_cast<int>(seen.size()), 1) << prec << " a " << a;
    }
}

TEST(Grids, BasinDefaultVelocitiesAreTheTrappingRegion) {
  BasinRequest r = small_basin("0", "1", "4", "5", 2, 2);
  r.v_range.reset();
  // constant eps < 1 on the triangle: [4, 4(1+3eps)/(1-eps)] = [4, 20] at eps = 1/2.
  const auto [lo, hi] = basin_v_range(r);
  EXPECT_EQ(lo.value(), 4);
  EXPECT_EQ(hi.value(), 20);
  r.model = spec(Law::elastic, "18");
  try {
    basin(r);
    ADD_FAILURE() << "the elastic model has no trapping region";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, "v-range");
  }
}

TEST(Grids, CertifiedBasinProvesTheReleaseStateSticks) {
  // One cell centred on (1/2, 4); at eps = 1/4, a = 24 lies in [200/9, 32): sticking period 1.
  BasinRequest r = small_basin("0", "1", "3", "5", 1, 1);
  r.model = spec(Law::constant, "24", "0.25");
  r.cert.max_steps = 300;
  r.cert.max_bits = 128;
  const CertifiedBasinResult c = certified_basin(r);
  ASSERT_EQ(c.cells.size(), 1u);
  EXPECT_EQ(c.theta[0].digits, "0.5");
  EXPECT_EQ(c.v[0].digits, "4");
  EXPECT_EQ(c.cells[0].cls, CertifiedClass::sticking) << name(c.cells[0].cls);
  EXPECT_EQ(c.cells[0].period, 1);
  EXPECT_EQ(c.cells[0].double_class, OrbitClass::sticking);
  EXPECT_EQ(c.cells[0].agreement, Agreement::agrees);
}

TEST(Grids, CertifiedBasinRefusesAPointTwinOtherThanDouble) {
  BasinRequest r = small_basin("0", "1", "3", "5", 1, 1);
  r.precision = parse_precision("precision", "mpfr:100");
  try {
    certified_basin(r);
    ADD_FAILURE() << "a certified basin's twin run is double";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, "precision");
  }
}

TEST(Grids, ScanPointCountsTheStartsABasinClassifies) {
  // A 1 x 1 scan centred on (a, eps) = (24, 0.5) and a 3 x 3 basin there: the same starts
  // (cell centres of [0, 1] x [5, 17]), the same classes counted.
  ScanRequest s;
  s.model = spec(Law::constant, "23", "0.25");
  s.a_lo = dec("23");
  s.a_hi = dec("25");
  s.y_lo = dec("0.25");
  s.y_hi = dec("0.75");
  s.p = s.q = 1;
  s.k = 3;
  s.v_range = std::pair{dec("5"), dec("17")};
  s.classify.transient = 200;
  s.classify.steps = 100;
  s.classify.max_period = 20;
  const ScanResult scanned = scan(s);
  ASSERT_EQ(scanned.cells.size(), 1u);
  EXPECT_EQ(scanned.y, Parameter::eps);
  EXPECT_EQ(scanned.a[0].digits, "24");
  EXPECT_EQ(scanned.y_values[0].digits, "0.5");
  EXPECT_EQ(scanned.cells[0].total(), 9);
  const BasinResult b = basin(small_basin("0", "1", "5", "17", 3, 3));
  std::map<OrbitClass, long> counted;
  for (const AttractorCell& c : b.cells) ++counted[c.cls];
  for (OrbitClass k : scan_classes()) EXPECT_EQ(scanned.cells[0][k], counted[k]) << name(k);
}

TEST(Grids, ScanNeedsAnInelasticModel) {
  ScanRequest s;
  s.model = spec(Law::elastic, "18");
  s.a_lo = dec("18");
  s.a_hi = dec("19");
  s.y_lo = dec("0");
  s.y_hi = dec("1");
  try {
    scan(s);
    ADD_FAILURE() << "the elastic model has no scanned parameter";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, "model");
  }
}

TEST(Grids, BifurcationColumnOnTheFixedPointStaysThere) {
  BifurcationRequest r;
  r.model = spec(Law::constant, "24", "0.5");
  r.vary = Parameter::a;
  r.lo = dec("24");
  r.hi = dec("25");
  r.samples = 2;
  r.transient = 10;
  r.record = 20;
  r.start = {dec("0.25"), dec("12")};
  const BifurcationResult b = bifurcation(r);
  ASSERT_EQ(b.columns.size(), 2u);
  EXPECT_EQ(b.columns[0].value.digits, "24");
  EXPECT_EQ(b.columns[1].value.digits, "25");
  const BifurcationColumn& c = b.columns[0];
  ASSERT_EQ(c.points.size(), 20u);
  for (size_t j = 0; j < c.points.size(); ++j) {
    EXPECT_EQ(c.points[j].n, static_cast<long>(11 + j));  // steps after the transient, 1-based
    EXPECT_NEAR(c.points[j].theta.value, 0.25, 1e-12);
    EXPECT_NEAR(c.points[j].v.value, 12, 1e-9);
    EXPECT_FALSE(c.points[j].sticking);
  }
  EXPECT_FALSE(c.undecided_step);
}

TEST(Grids, BifurcationRefusesEpsOutsideTheConstantModel) {
  BifurcationRequest r;
  r.model = spec(Law::veldep, "24");
  r.vary = Parameter::eps;
  r.lo = dec("0.1");
  r.hi = dec("0.2");
  r.start = {dec("0.25"), dec("12")};
  try {
    bifurcation(r);
    ADD_FAILURE() << "eps is no parameter of the velocity-dependent model";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, "vary");
  }
}

TEST(Grids, CancelledRunThrows) {
  const std::atomic<bool> stop{true};
  const CancelScope scope(&stop);
  EXPECT_THROW(basin(small_basin("0", "1", "4", "20", 8, 8)), Cancelled);
}

TEST(GridCells, TileTextsReadBack) {
  for (int k = 0; k < kOrbitClassCount; ++k) {
    const AttractorCell c = attractor_cell(static_cast<OrbitClass>(k), 3 * k);
    EXPECT_EQ(decode_cell<AttractorCell>(encode(c)), c);
    EXPECT_EQ(orbit_class_named(name(c.cls)), c.cls);
  }
  const CertifiedCell cc{CertifiedClass::no_sticking, 0, 5500, "mpfi:128", OrbitClass::sticking, 3773, Agreement::differs};
  EXPECT_EQ(decode_cell<CertifiedCell>(encode(cc)), cc);
  EXPECT_EQ(decode_cell<CertifiedCell>(encode(CertifiedCell::outside())), CertifiedCell::outside());
  ScanCell sc;
  for (int k = 0; k < kOrbitClassCount; ++k) sc.count[static_cast<size_t>(k)] = 7 * k + 1;
  EXPECT_EQ(decode_cell<ScanCell>(encode(sc)), sc);
  BifurcationColumn col;
  col.value = {24.5, "24.5"};
  col.points.push_back({11, {0.25, "0.25"}, {12, "12"}, false});
  col.points.push_back({12, {0.5, "0.5"}, {4, "4"}, true});
  col.undecided_step = 13;
  col.undecided_reason = "the sign of the gap at the knot is not decided";
  col.exact_value = "24.5";
  col.certified = cc;
  const BifurcationColumn back = decode_cell<BifurcationColumn>(encode(col));
  EXPECT_EQ(back.value.digits, "24.5");
  ASSERT_EQ(back.points.size(), 2u);
  EXPECT_EQ(back.points[1].n, 12);
  EXPECT_EQ(back.points[1].v.value, 4);
  EXPECT_TRUE(back.points[1].sticking);
  EXPECT_EQ(back.undecided_step, 13);
  EXPECT_EQ(back.undecided_reason, col.undecided_reason);
  EXPECT_EQ(back.exact_value, "24.5");
  EXPECT_EQ(back.certified, cc);
}

TEST(GridCells, ConfirmedCellsReadBack) {
  AttractorCell c = attractor_cell(OrbitClass::quasiperiodic, 0);
  c.confirm = PrecisionVerdict::artefact;
  c.check_cls = OrbitClass::unbounded;
  c.check_period = 0;
  c.differs_in = "class";
  EXPECT_EQ(encode(c), "quasiperiodic,0,artefact,unbounded,0,class");
  EXPECT_EQ(decode_cell<AttractorCell>(encode(c)), c);
  c.cls = OrbitClass::unbounded;
  c.differs_in = "accelerator period 33 vs 11";
  EXPECT_EQ(decode_cell<AttractorCell>(encode(c)), c);
  AttractorCell agrees = attractor_cell(OrbitClass::fixed, 1);
  agrees.confirm = PrecisionVerdict::agrees;
  agrees.check_cls = OrbitClass::fixed;
  agrees.check_period = 1;
  EXPECT_EQ(encode(agrees), "fixed,1,agrees,fixed,1,");
  EXPECT_EQ(decode_cell<AttractorCell>(encode(agrees)), agrees);
  ScanCell sc;
  sc.count[static_cast<size_t>(OrbitClass::fixed)] = 9;
  sc.confirmed = true;
  sc.verdicts = {6, 2, 1};
  sc.artefacts = {3, 8};
  EXPECT_EQ(decode_cell<ScanCell>(encode(sc)), sc);
  ScanCell none;  // confirmed, every start outside: no verdicts
  none.confirmed = true;
  EXPECT_EQ(decode_cell<ScanCell>(encode(none)), none);
  // A tile is read as hostile: the words of what differs are lower-case letters, digits,
  // spaces and '_' only, at most 80 of them.
  for (const char* bad : {"fixed,1,maybe,fixed,1,", "fixed,1,agrees,fixed,", "fixed,1,agrees,sideways,1,",
                          "fixed,1,agrees,fixed,1", "fixed,1,artefact,fixed,2,<script>", "fixed,1,artefact,fixed,2,a\nb",
                          "fixed,1,artefact,fixed,2,period,x"})
    EXPECT_THROW(decode_cell<AttractorCell>(bad), std::runtime_error) << bad;
  // The artefact list must hold as many starts as the artefact count.
  EXPECT_THROW(decode_cell<ScanCell>("0,0,0,0,0,0,0,0,0,0|1,2,0|3"), std::runtime_error);
  EXPECT_THROW(decode_cell<ScanCell>("0,0,0,0,0,0,0,0,0,0|1,2|"), std::runtime_error);
}

// The confirm sample's lattice, by hand: on a 10 x 10 grid with room for 4 starts, the stride
// is 5 (stride 4 at offset 1 keeps 1, 5, 9: 9 starts), the starts at offset 2 of each block of
// 5: columns and rows 2 and 7.
TEST(GridCells, ConfirmSampleLattice) {
  EXPECT_EQ(confirm_stride(10, 10, 1, 0), 1);    // every start
  EXPECT_EQ(confirm_stride(10, 10, 1, 100), 1);
  EXPECT_EQ(confirm_stride(10, 10, 1, 99), 2);   // offset 0: 0, 2, ..., 8: 25 starts
  EXPECT_EQ(confirm_sample_units(10, 10, 2), 25);
  EXPECT_EQ(confirm_stride(10, 10, 1, 4), 5);
  std::vector<std::pair<long, long>> in;
  for (long y = 0; y < 10; ++y)
    for (long x = 0; x < 10; ++x)
      if (in_confirm_sample(x, y, 10, 10, 5)) in.emplace_back(x, y);
  EXPECT_EQ(in, (std::vector<std::pair<long, long>>{{2, 2}, {7, 2}, {2, 7}, {7, 7}}));
  // A budget below one unit's starts (a scan point of 100 starts) still confirms one unit, the
  // centre one.
  EXPECT_EQ(confirm_stride(5, 3, 100, 10), 5);
  EXPECT_EQ(confirm_sample_units(5, 3, 5), 1);
  EXPECT_TRUE(in_confirm_sample(2, 1, 5, 3, 5));
}

TEST(GridCells, TextNoEncoderWroteIsRefused) {
  for (const char* bad : {"", "fixed", "fixed,", "fixed,1,2", "sideways,1", "fixed,x", "fixed,1 "})
    EXPECT_THROW(decode_cell<AttractorCell>(bad), std::runtime_error) << bad;
  EXPECT_THROW(decode_cell<ScanCell>("1,2,3"), std::runtime_error);
  EXPECT_THROW(decode_cell<ScanCell>("1,2,3,4,5,6,7,8,9,10,11"), std::runtime_error);
  EXPECT_THROW(decode_cell<CertifiedCell>("sticking,1,2,x,fixed,1,maybe"), std::runtime_error);
  EXPECT_THROW(decode_cell<BifurcationColumn>("S 1,0.5,4,0\n"), std::runtime_error);  // no value
  EXPECT_THROW(decode_cell<BifurcationColumn>("P 24\nQ what\n"), std::runtime_error);
}

}  // namespace
}  // namespace bouncer
