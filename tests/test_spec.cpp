// Model specification: wall presets, range validation of the exact decimal parameters and
// initial conditions, and the field names carried by InputError.
//
// Independent truth: the exact rationals written here by hand (knots, heights, wall
// velocities of the presets) and the documented allowed ranges (a > 0, 0 <= eps <= 1 for
// the constant law, c > 0, 0 <= theta < 1, v >= wall velocity with the right-continuous
// corner convention).
#include <gtest/gtest.h>

#include <string>

#include "bouncer/model/spec.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using namespace test_support;

mpq_class Q(const char* s) { return mpq_class(s); }  // "1/2", "-3", ...

Decimal D(const std::string& s) {
  auto d = Decimal::parse(s);
  EXPECT_TRUE(d.has_value()) << s;
  return *d;
}

ModelSpec triangle_spec(Law law = Law::constant) {
  ModelSpec m;
  m.law = law;
  m.a = D("19");
  m.eps = D("0.9");
  m.c = D("1000");
  m.wall = parse_wall("wall", "triangle");
  return m;
}

void expect_wall(const WallSpec& w, std::vector<const char*> knots, std::vector<const char*> heights) {
  ASSERT_EQ(w.knots.size(), knots.size());
  ASSERT_EQ(w.heights.size(), heights.size());
  for (size_t j = 0; j < knots.size(); ++j) {
    EXPECT_EQ(w.knots[j].value(), Q(knots[j])) << "knot " << j << " of " << w.text;
    EXPECT_EQ(w.heights[j].value(), Q(heights[j])) << "height " << j << " of " << w.text;
  }
}

// ---------------------------------------------------------------------------------------
// parse_wall presets

TEST(ParseWall, TrianglePreset) {
  const WallSpec w = parse_wall("wall", "triangle");
  EXPECT_EQ(w.text, "triangle");
  expect_wall(w, {"0", "1/2"}, {"-1", "1"});
  // f = 4 theta - 1 on [0, 1/2), 3 - 4 theta on [1/2, 1): velocities +4 and -4,
  // right-continuous at the corners.
  EXPECT_EQ(wall_velocity_exact(w, Q("0")), 4);
  EXPECT_EQ(wall_velocity_exact(w, Q("1/4")), 4);
  EXPECT_EQ(wall_velocity_exact(w, Q("499999/1000000")), 4);
  EXPECT_EQ(wall_velocity_exact(w, Q("1/2")), -4);
  EXPECT_EQ(wall_velocity_exact(w, Q("3/4")), -4);
  EXPECT_EQ(wall_velocity_exact(w, Q("999999/1000000")), -4);
  EXPECT_EQ(wall_segment_exact(w, Q("0")), 0);
  EXPECT_EQ(wall_segment_exact(w, Q("1/2")), 1);
  EXPECT_EQ(wall_segment_exact(w, Q("1/3")), 0);
}

TEST(ParseWall, SawtoothPreset) {
  const WallSpec w = parse_wall("wall", "sawtooth");
  expect_wall(w, {"0", "9/10"}, {"-1", "1"});
  // Rise 2 in 9/10, fall 2 in 1/10.
  EXPECT_EQ(wall_velocity_exact(w, Q("1/2")), Q("20/9"));
  EXPECT_EQ(wall_velocity_exact(w, Q("9/10")), -20);
}

TEST(ParseWall, AsymmetricPresets) {
  const WallSpec w = parse_wall("wall", "asymmetric:0.3");
  EXPECT_EQ(w.text, "asymmetric:0.3");
  expect_wall(w, {"0", "3/10"}, {"-1", "1"});
  EXPECT_EQ(wall_velocity_exact(w, Q("0")), Q("20/3"));
  EXPECT_EQ(wall_velocity_exact(w, Q("3/10")), Q("-20/7"));
  const WallSpec w2 = parse_wall("wall", "asymmetric:0.25");
  EXPECT_EQ(wall_velocity_exact(w2, Q("1/8")), 8);
  EXPECT_EQ(wall_velocity_exact(w2, Q("1/4")), Q("-8/3"));
  // The triangle is asymmetric:0.5.
  const WallSpec w3 = parse_wall("wall", "asymmetric:0.5");
  expect_wall(w3, {"0", "1/2"}, {"-1", "1"});
}

TEST(ParseWall, KnotList) {
  const WallSpec w = parse_wall("wall", "knots:0:0,0.25:1,0.75:-1");
  expect_wall(w, {"0", "1/4", "3/4"}, {"0", "1", "-1"});
  EXPECT_EQ(wall_velocity_exact(w, Q("0")), 4);
  EXPECT_EQ(wall_velocity_exact(w, Q("1/4")), -4);
  EXPECT_EQ(wall_velocity_exact(w, Q("3/4")), 4);  // closes back to h_0 = 0 at theta = 1
  EXPECT_EQ(wall_segment_exact(w, Q("3/4")), 2);
  ModelSpec m = triangle_spec();
  m.wall = w;
  EXPECT_NO_THROW(validate(m));
}

TEST(ParseWall, RejectsBadWallsNamingTheField) {
  for (const char* bad : {"asymmetric:0", "asymmetric:1", "asymmetric:1.5", "asymmetric:-0.2",
                          "asymmetric:x", "asymmetric:", "knots:0:0,0.5", "knots:0:0,0.5:x",
                          "zigzag", "", "Triangle", "triangle "}) {
    SCOPED_TRACE(bad);
    expect_input_error([&] { parse_wall("--wall", bad); }, "--wall");
  }
}

TEST(ParseWall, ValidateRejectsBadKnotLists) {
  ModelSpec m = triangle_spec();
  m.wall = parse_wall("wall", "knots:0.1:0,0.5:1");  // first knot not at 0
  expect_input_error([&] { validate(m); }, "wall");
  m.wall = parse_wall("wall", "knots:0:0,0.5:1,0.5:-1");  // not strictly increasing
  expect_input_error([&] { validate(m); }, "wall");
  m.wall = parse_wall("wall", "knots:0:0,1:1");  // knot at 1
  expect_input_error([&] { validate(m); }, "wall");
  m.wall = parse_wall("wall", "knots:0:1,0.5:1");  // flat
  expect_input_error([&] { validate(m); }, "wall");
  m.wall = parse_wall("wall", "knots:0:1");  // a single knot
  expect_input_error([&] { validate(m); }, "wall");
}

// ---------------------------------------------------------------------------------------
// Decimal fields and the other parsers

TEST(ParseFields, DecimalLawDownward) {
  EXPECT_EQ(parse_decimal("a", "28.82").value(), Q("1441/50"));
  for (const char* bad : {"inf", "nan", "0x10", "", " 1", "1,5", "1e", "abc"}) {
    SCOPED_TRACE(bad);
    expect_input_error([&] { parse_decimal("--a", bad); }, "--a");
  }
  EXPECT_EQ(parse_law("model", "elastic"), Law::elastic);
  EXPECT_EQ(parse_law("model", "constant"), Law::constant);
  EXPECT_EQ(parse_law("model", "veldep"), Law::veldep);
  expect_input_error([&] { parse_law("model", "Elastic"); }, "model");
  EXPECT_EQ(parse_downward("downward", "paper"), DownwardSticking::paper);
  EXPECT_EQ(parse_downward("downward", "impact"), DownwardSticking::impact);
  expect_input_error([&] { parse_downward("downward", "ride"); }, "downward");
}

// ---------------------------------------------------------------------------------------
// validate(ModelSpec)

TEST(ValidateModel, AcceptsThePapersParameters) {
  ModelSpec m = triangle_spec(Law::constant);
  EXPECT_NO_THROW(validate(m));
  m.eps = D("0.96");
  m.a = D("28.82");
  EXPECT_NO_THROW(validate(m));
  m.eps = D("0");  // the closed range [0, 1]
  EXPECT_NO_THROW(validate(m));
  m.eps = D("1");
  EXPECT_NO_THROW(validate(m));
  m.eps = D("1.000");
  EXPECT_NO_THROW(validate(m));
  EXPECT_NO_THROW(validate(triangle_spec(Law::elastic)));
  ModelSpec v = triangle_spec(Law::veldep);
  v.a = D("25");
  EXPECT_NO_THROW(validate(v));
  v.c = D("1e-9");
  EXPECT_NO_THROW(validate(v));
}

TEST(ValidateModel, RejectsNonPositiveA) {
  for (Law law : {Law::elastic, Law::constant, Law::veldep}) {
    for (const char* a : {"0", "-1", "-0.0", "0e5", "-1e-30"}) {
      SCOPED_TRACE(a);
      ModelSpec m = triangle_spec(law);
      m.a = D(a);
      expect_input_error([&] { validate(m); }, "a");
    }
  }
  ModelSpec m = triangle_spec();
  m.a = D("1e-30");  // tiny but positive
  EXPECT_NO_THROW(validate(m));
  m.a = D("1e9");  // documented upper limit
  EXPECT_NO_THROW(validate(m));
  m.a = D("1.0000000001e9");
  expect_input_error([&] { validate(m); }, "a");
}

TEST(ValidateModel, RejectsEpsOutsideTheClosedUnitInterval) {
  for (const char* eps : {"-0.1", "-1e-30", "1.5", "1.0000000000000000000000001", "2"}) {
    SCOPED_TRACE(eps);
    ModelSpec m = triangle_spec(Law::constant);
    m.eps = D(eps);
    expect_input_error([&] { validate(m); }, "eps");
  }
  // "1.0000000000000000000000001" rounds to 1 in double: the check must be exact.
  EXPECT_EQ(D("1.0000000000000000000000001").approx(), 1.0);
  ModelSpec m = triangle_spec(Law::constant);
  m.eps = D("0.9999999999999999999999999");
  EXPECT_NO_THROW(validate(m));
}

TEST(ValidateModel, RejectsNonPositiveC) {
  for (const char* c : {"0", "-1", "-1e-100"}) {
    SCOPED_TRACE(c);
    ModelSpec m = triangle_spec(Law::veldep);
    m.c = D(c);
    expect_input_error([&] { validate(m); }, "c");
  }
}

// ---------------------------------------------------------------------------------------
// validate(ModelSpec, InitialCondition)

void ic_ok(const ModelSpec& m, const char* theta, const char* v) {
  SCOPED_TRACE(std::string("theta=") + theta + " v=" + v);
  EXPECT_NO_THROW(validate(m, InitialCondition{D(theta), D(v)}, "theta0", "v0"));
}

void ic_bad(const ModelSpec& m, const char* theta, const char* v, const std::string& field) {
  SCOPED_TRACE(std::string("theta=") + theta + " v=" + v);
  expect_input_error([&] { validate(m, InitialCondition{D(theta), D(v)}, "theta0", "v0"); }, field);
}

TEST(ValidateInitialCondition, ThetaMustBeInTheHalfOpenUnitInterval) {
  const ModelSpec m = triangle_spec();
  ic_ok(m, "0", "4");
  ic_ok(m, "0.999999999999999999999", "10");
  ic_bad(m, "1", "10", "theta0");
  ic_bad(m, "1.5", "10", "theta0");
  ic_bad(m, "-0.1", "10", "theta0");
  ic_bad(m, "-1e-40", "10", "theta0");
}

TEST(ValidateInitialCondition, VelocityAtLeastTheWallVelocity) {
  const ModelSpec m = triangle_spec();
  // Up segment: u = +4.
  ic_ok(m, "0.2", "4");
  ic_ok(m, "0.2", "4.0000000000000000000001");
  ic_bad(m, "0.2", "3.9999", "v0");
  ic_bad(m, "0.2", "3.9999999999999999999999", "v0");  // rounds to 4 in double
  ic_ok(m, "0", "4");   // corner theta = 0: u = +4
  ic_bad(m, "0", "3.99", "v0");
  ic_bad(m, "0", "-4", "v0");
  // Corner theta = 1/2: right-continuous, u = -4.
  ic_ok(m, "0.5", "-4");
  ic_ok(m, "0.5", "4");
  ic_bad(m, "0.5", "-4.0001", "v0");
  // Just below the corner the wall still moves up, although the decimal rounds to 0.5.
  ic_bad(m, "0.49999999999999999999999", "-4", "v0");
  ic_ok(m, "0.49999999999999999999999", "4");
  ic_ok(m, "0.50000000000000000000001", "-4");
  // Down segment: u = -4.
  ic_ok(m, "0.75", "-4");
  ic_ok(m, "0.75", "-3.9");
  ic_bad(m, "0.75", "-4.0000000000000000000001", "v0");
  // Upper bound of the accepted velocities (documented: 1e15).
  ic_ok(m, "0.3", "1e12");
  ic_bad(m, "0.3", "1e16", "v0");
}

TEST(ValidateInitialCondition, AsymmetricWallVelocities) {
  ModelSpec m = triangle_spec();
  m.wall = parse_wall("wall", "asymmetric:0.25");  // u = 8 on [0, 1/4), -8/3 on [1/4, 1)
  ic_ok(m, "0.1", "8");
  ic_bad(m, "0.1", "7.999", "v0");
  ic_ok(m, "0.25", "-2.6666666");  // above -8/3
  ic_bad(m, "0.25", "-2.6666667", "v0");  // below -8/3
  ic_ok(m, "0.5", "-2.6666666");
}

}  // namespace
}  // namespace bouncer
