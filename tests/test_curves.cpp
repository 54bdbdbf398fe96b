// The orbit grids of the library: phase portraits (run/portrait.hpp) and exponent curves
// (run/exponent_curve.hpp), their tile texts, their option readers (io/requests/) and their
// pictures' counts (io/curve_figures.hpp), against truth that does not come from the grid code:
//   * the eq. 5 fixed point (eps = 1/2, a = 24: theta = 1/4, v = 12, flight time one period;
//     derivation in test_orbit_io.cpp) maps to itself: a portrait started there stays there,
//     in double and at 200 bits, and its polar picture puts it at angle pi/2, radius 12;
//   * its multipliers are 1 (along the family) and eps^2, so the leading exponent there is
//     log 1 = 0: marginal, |lambda| small;
//   * the release state (1/2, 4) sticks with period 1 for 200/9 <= a < 32 at eps = 1/4 (the
//     closed form in tests/README.md, "Continuation"): every portrait step is a sticking
//     event back to (1/2, 4), and a sticking step contracts: lambda = -inf, class sticking 1;
//   * an elastic flight from v = 1e15 at a = 1e-300 lasts 2v/a = 2e315 periods, beyond the
//     largest double: the step cannot be completed (undecided), in the portrait and the curve;
//   * a value's exponent is bit for bit the single-point lyapunov() of the model built from
//     the value's printed digits (what `bouncer lyapunov --a DIGITS` computes);
//   * the curve's starts: (0.1, wall speed + 2), then the R2 sequence (the plastic number
//     found here by Newton's method on x^3 = x + 1), inside the trapping region
//     4(1 + 3 eps)/(1 - eps) of every value (the paper's bound, exact rationals);
//   * results do not depend on the thread count; tile texts read back; bad input is refused
//     naming its option.
#include <gtest/gtest.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "bouncer/base/cancel.hpp"
#include "bouncer/io/curve_figures.hpp"
#include "bouncer/io/requests/exponent_curve.hpp"
#include "bouncer/io/requests/portrait.hpp"
#include "bouncer/run/exponent_curve.hpp"
#include "bouncer/run/portrait.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using test_support::expect_input_error;
using test_support::spec;

Decimal dec(const char* s) { return *Decimal::parse(s); }

PortraitRequest fixed_point_portrait(long steps) {
  PortraitRequest r;
  r.model = spec(Law::constant, "24", "0.5");
  r.starts = {{dec("0.25"), dec("12")}};
  r.steps = steps;
  return r;
}

// ---- portraits ----------------------------------------------------------------------------

TEST(Portrait, TheEq5FixedPointMapsToItself) {
  const PortraitResult p = portrait(fixed_point_portrait(50));
  ASSERT_EQ(p.orbits.size(), 1u);
  const PortraitOrbit& o = p.orbits[0];
  ASSERT_EQ(o.points.size(), 51u);  // the start, then 50 steps
  EXPECT_EQ(o.points[0].n, 0);
  EXPECT_FALSE(o.points[0].event);
  EXPECT_EQ(o.points[0].theta.digits, "0.25");
  EXPECT_EQ(o.points[0].v.digits, "12");
  for (size_t j = 1; j < o.points.size(); ++j) {
    EXPECT_EQ(o.points[j].n, static_cast<long>(j));
    EXPECT_EQ(o.points[j].event, EventKind::impact);
    EXPECT_NEAR(o.points[j].theta.value, 0.25, 1e-12);
    EXPECT_NEAR(o.points[j].v.value, 12, 1e-10);
  }
  EXPECT_FALSE(o.undecided_step);
}

TEST(Portrait, TheFixedPointAt200BitsStaysWithin1e50) {
  PortraitRequest r = fixed_point_portrait(20);
  r.precision = parse_precision("precision", "mpfr:200");
  const PortraitResult p = portrait(r);
  for (const PortraitPoint& q : p.orbits[0].points) {
    const mpq_class dt = Decimal::parse(q.theta.digits)->value() - mpq_class(1, 4);
    const mpq_class dv = Decimal::parse(q.v.digits)->value() - 12;
    EXPECT_LT(abs(dt), mpq_class(1, mpz_class("100000000000000000000000000000000000000000000000000")));
    EXPECT_LT(abs(dv), mpq_class(1, mpz_class("100000000000000000000000000000000000000000000000000")));
  }
}

TEST(Portrait, TheReleaseStateSticksEveryStep) {
  PortraitRequest r;
  r.model = spec(Law::constant, "24", "0.25");
  r.starts = {{dec("0.5"), dec("4")}};
  r.steps = 10;
  r.transient = 5;
  const PortraitResult p = portrait(r);
  const PortraitOrbit& o = p.orbits[0];
  ASSERT_EQ(o.points.size(), 10u);  // no start point after a transient
  for (size_t j = 0; j < o.points.size(); ++j) {
    EXPECT_EQ(o.points[j].n, static_cast<long>(6 + j));  // counted from the start, 1-based
    EXPECT_EQ(o.points[j].event, EventKind::sticking);
    EXPECT_EQ(o.points[j].theta.value, 0.5);
    EXPECT_EQ(o.points[j].v.value, 4);
  }
}

TEST(Portrait, AnOverflowingFlightStopsOnlyItsOrbit) {
  PortraitRequest r;
  r.model = spec(Law::elastic, "1e-300");
  r.starts = {{dec("0.1"), dec("1e15")}, {dec("0.2"), dec("5")}};
  r.steps = 4;
  const PortraitResult p = portrait(r);
  ASSERT_EQ(p.orbits.size(), 2u);
  EXPECT_EQ(p.orbits[0].undecided_step, 1);
  EXPECT_FALSE(p.orbits[0].undecided_reason.empty());
  EXPECT_EQ(p.orbits[0].points.size(), 1u);  // the start only
  EXPECT_FALSE(p.orbits[1].undecided_step);
  EXPECT_EQ(p.orbits[1].points.size(), 5u);
  const PortraitCounts c = portrait_counts(p);
  EXPECT_EQ(c.points, 6);
  EXPECT_EQ(c.undecided_orbits, 1);
  EXPECT_EQ(c.max_v, 1e15);
}

TEST(Portrait, ThreadsDoNotChangeTheOrbits) {
  PortraitRequest r;
  r.model = spec(Law::veldep, "27");
  r.starts = {{dec("0.3"), dec("6")}, {dec("0.1"), dec("9")}, {dec("0.7"), dec("12")}};
  r.steps = 300;
  GridOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const PortraitResult a = portrait(r, one), b = portrait(r, two);
  ASSERT_EQ(a.orbits.size(), b.orbits.size());
  for (size_t k = 0; k < a.orbits.size(); ++k) EXPECT_EQ(encode(a.orbits[k]), encode(b.orbits[k]));
}

TEST(Portrait, PolarPictureOfTheFixedPoint) {
  const PortraitResult p = portrait(fixed_point_portrait(5));
  PortraitView polar;
  polar.polar = true;
  const Figure f = portrait_figure(p, polar);
  ASSERT_EQ(f.series.size(), 1u);
  ASSERT_EQ(f.series[0].x.size(), 6u);
  for (size_t j = 0; j < 6; ++j) {  // angle 2 pi / 4, radius 12
    EXPECT_NEAR(f.series[0].x[j], 0, 1e-9);
    EXPECT_NEAR(f.series[0].y[j], 12, 1e-9);
  }
  EXPECT_TRUE(f.equal_aspect);
  // A window a double resolves is the frame (points outside it are clipped when drawn); a
  // zoom 1e-20 wide places points from their exact values and leaves out those far outside.
  PortraitView window;
  window.theta_window = std::pair{dec("0.5"), dec("0.6")};
  const Figure w = portrait_figure(p, window);
  EXPECT_EQ(w.x_min, 0.5);
  EXPECT_EQ(w.x_max, 0.6);
  EXPECT_EQ(w.series[0].x.size(), 6u);
  window.theta_window = std::pair{dec("0.5"), dec("0.50000000000000000001")};
  EXPECT_TRUE(portrait_figure(p, window).series[0].x.empty());
}

TEST(Portrait, RefusesBadRequests) {
  PortraitRequest r = fixed_point_portrait(10);
  r.precision = parse_precision("precision", "interval:64");
  expect_input_error([&] { portrait(r); }, "precision");
  r = fixed_point_portrait(10);
  r.starts.assign(1001, r.starts[0]);
  expect_input_error([&] { portrait(r); }, "theta");
  r = fixed_point_portrait(100000);
  r.starts.assign(201, r.starts[0]);  // 2.01e7 points
  expect_input_error([&] { portrait(r); }, "steps");
  r = fixed_point_portrait(10);
  r.starts = {{dec("0.1"), dec("3")}};  // below the wall's velocity 4 at theta = 0.1
  expect_input_error([&] { portrait(r); }, "v");
}

TEST(Portrait, CancelledRunThrows) {
  const std::atomic<bool> stop{true};
  const CancelScope scope(&stop);
  EXPECT_THROW(portrait(fixed_point_portrait(1000)), Cancelled);
}

TEST(Portrait, TileTextsReadBack) {
  PortraitOrbit o;
  o.points.push_back({0, {0.25, "0.25"}, {12, "12"}, std::nullopt});
  o.points.push_back({1, {0.5, "0.5"}, {4, "4"}, EventKind::sticking});
  o.points.push_back({2, {0.125, "0.125"}, {6.5, "6.5"}, EventKind::ride});
  o.undecided_step = 3;
  o.undecided_reason = "a value is NaN or infinite (overflow)";
  const PortraitOrbit back = decode_cell<PortraitOrbit>(encode(o));
  ASSERT_EQ(back.points.size(), 3u);
  for (size_t j = 0; j < 3; ++j) {
    EXPECT_EQ(back.points[j].n, o.points[j].n);
    EXPECT_EQ(back.points[j].theta.digits, o.points[j].theta.digits);
    EXPECT_EQ(back.points[j].v.value, o.points[j].v.value);
    EXPECT_EQ(back.points[j].event, o.points[j].event);
  }
  EXPECT_EQ(back.undecided_step, 3);
  EXPECT_EQ(back.undecided_reason, o.undecided_reason);
  EXPECT_TRUE(decode_cell<PortraitOrbit>("").points.empty());
  for (const char* bad : {"S 1,0.5,4\n", "S 1,0.5,4,bounce\n", "S x,0.5,4,impact\n", "Q 1\n", "S 1,0.5,4,impact"})
    EXPECT_THROW(decode_cell<PortraitOrbit>(bad), std::runtime_error) << bad;
}

TEST(Portrait, OptionsAreReadAsTheCommandLineReadsThem) {
  Options o;
  o.set("model", "constant");
  o.set("a", "24");
  o.set("eps", "0.5");
  o.set("theta", std::vector<std::string>{"0.25", "0.3"});
  o.set("v", std::vector<std::string>{"12", "9.5"});
  const PortraitOptions p = portrait_options(o);
  EXPECT_EQ(p.request.starts.size(), 2u);
  EXPECT_EQ(p.request.steps, 1000);
  EXPECT_EQ(p.request.transient, 0);
  EXPECT_EQ(p.request.precision.kind, Precision::Kind::double_);
  EXPECT_FALSE(p.view.polar);
  o.set("polar", "true");
  o.set("theta-range", "0.2:0.3");
  expect_input_error([&] { portrait_options(o); }, "theta-range");  // no window with --polar
}

// ---- exponent curves ----------------------------------------------------------------------

ExponentCurveRequest curve(Law law, const char* a, const char* eps, Parameter vary, const char* lo, const char* hi,
                           long samples) {
  ExponentCurveRequest r;
  r.model = spec(law, a, eps);
  r.vary = vary;
  r.lo = dec(lo);
  r.hi = dec(hi);
  r.samples = samples;
  r.lyapunov.transient = 100;
  r.lyapunov.steps = 2000;
  return r;
}

TEST(ExponentCurve, TheFixedPointIsMarginal) {
  ExponentCurveRequest r = curve(Law::constant, "24", "0.5", Parameter::a, "24", "25", 2);
  r.start = InitialCondition{dec("0.25"), dec("12")};
  const ExponentCurveResult c = exponent_curve(r);
  ASSERT_EQ(c.columns.size(), 2u);
  EXPECT_EQ(c.columns[0].value.digits, "24");
  EXPECT_EQ(c.columns[1].value.digits, "25");
  const ExponentRow& at = c.columns[0].rows.at(0);
  EXPECT_LT(std::abs(at.lambda), 1e-3) << at.lambda;
  EXPECT_EQ(at.cls, OrbitClass::fixed);
  EXPECT_EQ(at.period, 1);
}

TEST(ExponentCurve, TheStickingReleaseContracts) {
  // 200/9 <= a < 32 at eps = 1/4: 23 and 31.5 both.
  ExponentCurveRequest r = curve(Law::constant, "23", "0.25", Parameter::a, "23", "31.5", 3);
  r.start = InitialCondition{dec("0.5"), dec("4")};
  for (const ExponentColumn& col : exponent_curve(r).columns) {
    ASSERT_EQ(col.rows.size(), 1u);
    EXPECT_EQ(col.rows[0].lambda, -std::numeric_limits<double>::infinity()) << col.value.digits;
    EXPECT_EQ(col.rows[0].cls, OrbitClass::sticking);
    EXPECT_EQ(col.rows[0].period, 1);
  }
}

TEST(ExponentCurve, EachValueIsTheSinglePointExponentBitForBit) {
  // 20 + 10 k/6: most values are not exact decimals; two starts (the given one and one of R2).
  ExponentCurveRequest r = curve(Law::veldep, "20", "1", Parameter::a, "20", "30", 7);
  r.ics = 2;
  r.start = InitialCondition{dec("0.3"), dec("6")};
  r.lyapunov.transient = 200;
  r.lyapunov.steps = 1000;
  const ExponentCurveResult c = exponent_curve(r);
  ASSERT_EQ(c.starts.size(), 2u);
  for (long k : {0L, 1L, 4L, 6L}) {
    const ExponentColumn& col = c.columns[static_cast<size_t>(k)];
    EXPECT_NEAR(col.value.value, 20 + 10.0 * static_cast<double>(k) / 6, 1e-12);
    const Model<double> m = make_model<double>(with_parameter(r.model, Parameter::a, dec(col.value.digits.c_str())), 53);
    for (size_t j = 0; j < c.starts.size(); ++j) {
      const LyapunovResult single = lyapunov(m, make_state<double>(c.starts[j], 53), r.lyapunov);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(col.rows[j].lambda), std::bit_cast<std::uint64_t>(single.lambda))
          << "a = " << col.value.digits << ", start " << j;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(col.rows[j].stderr_), std::bit_cast<std::uint64_t>(single.stderr_));
    }
  }
}

// The plastic number, the real root of x^3 = x + 1, by Newton's method.
double plastic() {
  double x = 1.3;
  for (int i = 0; i < 50; ++i) x -= (x * x * x - x - 1) / (3 * x * x - 1);
  return x;
}

std::string fixed(double x, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

TEST(ExponentCurve, StartsAreTheDefaultThenR2InsideEveryTrappingRegion) {
  // eps in [0.3, 0.7]: the trapping region is lowest at eps = 0.3, 4(1 + 0.9)/0.7 = 76/7.
  ExponentCurveRequest r = curve(Law::constant, "24", "0.3", Parameter::eps, "0.3", "0.7", 2);
  r.ics = 40;
  const std::vector<InitialCondition> s = exponent_curve_starts(r);
  ASSERT_EQ(s.size(), 40u);
  EXPECT_EQ(s[0].theta.value(), mpq_class(1, 10));
  EXPECT_EQ(s[0].v.value(), 6);  // the triangle's wall speed 4, + 2
  const double g = plastic(), top = 4 * (1 + 3 * 0.3) / (1 - 0.3);
  for (size_t j = 1; j < s.size(); ++j) {
    const double x = 0.5 + static_cast<double>(j) / g, u = 0.5 + static_cast<double>(j) / (g * g);
    EXPECT_EQ(s[j].theta.text(), fixed(x - std::floor(x), 6)) << j;
    EXPECT_EQ(s[j].v.text(), fixed(4 + (u - std::floor(u)) * (top - 4), 4)) << j;
    EXPECT_GT(s[j].v.value(), 4);
    EXPECT_LE(s[j].v.value(), mpq_class(76, 7)) << s[j].v.text();  // in the region at every eps >= 0.3
  }
}

TEST(ExponentCurve, AnOverflowingFlightIsAnUndecidedRow) {
  ExponentCurveRequest r = curve(Law::elastic, "1e-300", "1", Parameter::a, "1e-300", "2e-300", 2);
  r.start = InitialCondition{dec("0.1"), dec("1e15")};
  for (const ExponentColumn& col : exponent_curve(r).columns) {
    ASSERT_EQ(col.rows.size(), 1u);
    EXPECT_TRUE(std::isnan(col.rows[0].lambda));
    EXPECT_EQ(col.rows[0].cls, OrbitClass::undecided);
    EXPECT_EQ(col.rows[0].period, 0);
  }
}

TEST(ExponentCurve, ThreadsDoNotChangeTheCurve) {
  ExponentCurveRequest r = curve(Law::constant, "20", "0.5", Parameter::a, "20", "25", 9);
  r.ics = 3;
  r.lyapunov.steps = 500;
  GridOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const ExponentCurveResult a = exponent_curve(r, one), b = exponent_curve(r, two);
  ASSERT_EQ(a.columns.size(), b.columns.size());
  for (size_t k = 0; k < a.columns.size(); ++k) EXPECT_EQ(encode(a.columns[k]), encode(b.columns[k]));
}

TEST(ExponentCurve, RefusesBadRequests) {
  ExponentCurveRequest r = curve(Law::veldep, "24", "1", Parameter::eps, "0.1", "0.2", 3);
  expect_input_error([&] { exponent_curve(r); }, "vary");
  r = curve(Law::constant, "24", "0.5", Parameter::eps, "0.5", "1.5", 3);
  expect_input_error([&] { exponent_curve(r); }, "range");
  r = curve(Law::constant, "24", "0.5", Parameter::a, "25", "24", 3);
  expect_input_error([&] { exponent_curve(r); }, "range");
  r = curve(Law::constant, "24", "0.5", Parameter::a, "24", "25", 3);
  r.precision = parse_precision("precision", "interval:64");
  expect_input_error([&] { exponent_curve(r); }, "precision");
  r = curve(Law::constant, "24", "0.5", Parameter::a, "24", "25", 3);
  r.ics = 0;
  expect_input_error([&] { exponent_curve(r); }, "ics");
}

TEST(ExponentCurve, TileTextsReadBack) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  ExponentColumn col;
  col.value = {20 + 10.0 / 6, "21.666666666666668"};
  col.rows = {{0.1133352245852151, 0.0028363231335, OrbitClass::chaotic, 0},
              {-inf, 0, OrbitClass::sticking, 4},
              {nan, nan, OrbitClass::undecided, 0},
              {inf, -0.0, OrbitClass::transient_chaos, 2}};
  const ExponentColumn back = decode_cell<ExponentColumn>(encode(col));
  EXPECT_EQ(back.value.digits, col.value.digits);
  EXPECT_EQ(back.value.value, col.value.value);
  ASSERT_EQ(back.rows.size(), 4u);
  for (size_t j = 0; j < 4; ++j) {
    if (std::isnan(col.rows[j].lambda)) {
      EXPECT_TRUE(std::isnan(back.rows[j].lambda));
    } else {
      EXPECT_EQ(back.rows[j].lambda, col.rows[j].lambda);
    }
    EXPECT_EQ(back.rows[j].cls, col.rows[j].cls);
    EXPECT_EQ(back.rows[j].period, col.rows[j].period);
  }
  for (const char* bad : {"", "R 1,2,chaotic,0\n", "P 20\nR 1,2,sideways,0\n", "P 20\nR 1,2,chaotic\n",
                          "P 20\nR 1,2,chaotic,x\n", "P 20\nP 21\n", "P 20"})
    EXPECT_THROW(decode_cell<ExponentColumn>(bad), std::runtime_error) << bad;
}

TEST(ExponentCurve, SummariesSkipNaNInTheMaximumNotInTheMean) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ExponentColumn col;
  col.rows = {{0.5, 0, OrbitClass::chaotic, 0}, {nan, nan, OrbitClass::undecided, 0}, {-1, 0, OrbitClass::periodic, 2}};
  EXPECT_EQ(col.max_lambda(), 0.5);
  EXPECT_TRUE(std::isnan(col.mean_lambda()));
  col.rows.erase(col.rows.begin() + 1);
  EXPECT_EQ(col.mean_lambda(), -0.25);
  ExponentCurveResult c;
  c.columns = {col, col};
  c.columns[1].rows[1].cls = OrbitClass::chaotic;
  const std::vector<CurveClassCount> census = exponent_census(c);  // chaotic 3, periodic 1
  ASSERT_EQ(census.size(), 2u);
  EXPECT_EQ(census[0].cls, OrbitClass::chaotic);
  EXPECT_EQ(census[0].rows, 3);
  c.columns[1].rows[0].cls = OrbitClass::periodic;  // 2 and 2: by name
  EXPECT_EQ(exponent_census(c)[0].cls, OrbitClass::chaotic);
  EXPECT_EQ(exponent_census(c)[1].cls, OrbitClass::periodic);
}

TEST(ExponentCurve, OptionsAreReadAsTheCommandLineReadsThem) {
  Options o;
  o.set("model", "veldep");
  o.set("c", "1000");
  o.set("vary", "a");
  o.set("range", "20:30");
  const ExponentCurveRequest r = exponent_curve_request(o);
  EXPECT_EQ(r.model.a.text(), "20");  // the range's start
  EXPECT_EQ(r.vary, Parameter::a);
  EXPECT_EQ(r.samples, 100);
  EXPECT_EQ(r.ics, 1);
  EXPECT_FALSE(r.start);
  EXPECT_EQ(r.lyapunov.transient, 1000);
  EXPECT_EQ(r.lyapunov.steps, 10000);
  EXPECT_EQ(r.lyapunov.blocks, 20);
  EXPECT_EQ(r.classify.transient, 0);  // classified where the exponent's window ended
  EXPECT_EQ(r.classify.steps, 500);
  EXPECT_EQ(r.classify.max_period, 64);
  o.set("theta", "0.3");
  expect_input_error([&] { exponent_curve_request(o); }, "v");  // a start needs both
  o.values.erase("theta");
  o.values.erase("range");
  o.set("a", "20");
  expect_input_error([&] { exponent_curve_request(o); }, "range");
}

}  // namespace
}  // namespace bouncer
