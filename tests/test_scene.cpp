// Scenes and the shared option parsers (io/scene.hpp) against independent truth: the model
// built field by field from the same decimals (test_support.hpp's spec()), exact rationals
// written by hand, the documented ranges (precision bits in [kMinBits, kMaxBits], integer
// bounds inclusive), round trips (Options -> as_toml -> load_scene gives the same texts, a
// precision's text parses back to the same precision), and bad input refused with an
// InputError naming the field.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "bouncer/io/scene.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using namespace test_support;

namespace fs = std::filesystem;
using test_support::spec;

Options model_options(const std::string& law, const std::string& a) {
  Options o;
  o.set("model", law);
  o.set("a", a);
  return o;
}

// ---- Options ------------------------------------------------------------------------------

TEST(Options, GetNamesTheMissingOrListValuedKey) {
  Options o;
  o.set("steps", "20");
  o.set("theta", std::vector<std::string>{"0.25", "0.1"});
  EXPECT_EQ(o.get("steps"), "20");
  EXPECT_EQ(o.get_or("steps", "7"), "20");
  EXPECT_EQ(o.get_or("every", "7"), "7");
  // A missing key with a documented range says the range (spec.cpp's allowed_range).
  EXPECT_TRUE(contains(expect_input_error([&] { o.get("a"); }, "a"), "is required (a decimal with 0 < a <= 1e9)"));
  EXPECT_TRUE(contains(expect_input_error([&] { o.get("every"); }, "every"), "is required"));
  EXPECT_TRUE(contains(expect_input_error([&] { o.get("theta"); }, "theta"), "takes one value, got a list"));
  // An empty list is as missing as no key.
  o.set("v", std::vector<std::string>{});
  expect_input_error([&] { o.get("v"); }, "v");
}

TEST(Options, InputsAreTheExactTextsInKeyOrder) {
  Options o;
  o.set("v", std::vector<std::string>{"12", "7"});
  o.set("a", "24.000");  // kept as written, not normalised
  o.set("eps", "0.5");
  const auto in = o.inputs();
  ASSERT_EQ(in.size(), 3u);
  EXPECT_EQ(in[0], (std::pair<std::string, std::string>{"a", "24.000"}));
  EXPECT_EQ(in[1], (std::pair<std::string, std::string>{"eps", "0.5"}));
  EXPECT_EQ(in[2], (std::pair<std::string, std::string>{"v", "12,7"}));
}

TEST(Options, MergePutsTheCommandLineOnTopOfTheScene) {
  Options scene, cli;
  scene.set("a", "24");
  scene.set("eps", "0.5");
  scene.set("theta", std::vector<std::string>{"0.25", "0.1"});
  cli.set("a", "19");
  cli.set("theta", "0.3");
  cli.set("steps", "5");
  const Options m = merge(scene, cli);
  EXPECT_EQ(m.get("a"), "19");
  EXPECT_EQ(m.get("eps"), "0.5");   // kept from the scene
  EXPECT_EQ(m.get("theta"), "0.3");  // a list replaced by one value, not appended to
  EXPECT_EQ(m.get("steps"), "5");
  EXPECT_EQ(m.values.size(), 4u);
}

// ---- scene files ----------------------------------------------------------------------------

TEST(Scene, AsTomlReadsBackAsTheSameOptions) {
  TempDir d;
  Options o;
  o.set("a", "28.82");
  o.set("eps", "0.96");
  o.set("theta", std::vector<std::string>{"0.5", "0.125", "1e-30"});
  o.set("v", std::vector<std::string>{"4", "7", "12"});
  // Texts TOML must escape: quotes, backslashes, a newline, a tab, non-ASCII.
  o.set("out", "dir with space/\"quoted\" \\ back\nline\ttab \xce\xb8.csv");
  const std::set<std::string> allowed{"a", "eps", "theta", "v", "out"};
  const Options back = load_scene(put(d / "s.toml", o.as_toml("orbit")), "orbit", allowed);
  EXPECT_EQ(back.values, o.values);
  EXPECT_EQ(scene_command(d / "s.toml"), "orbit");
}

TEST(Scene, IntegersAndBooleansBecomeTheirTexts) {
  TempDir d;
  const std::string p = put(d / "s.toml", "command = \"orbit\"\nsteps = 20\nevery = -3\nflag = true\nv = [\"4\", 12]\n");
  const Options o = load_scene(p, "orbit", {"steps", "every", "flag", "v"});
  EXPECT_EQ(o.get("steps"), "20");
  EXPECT_EQ(o.get("every"), "-3");
  EXPECT_EQ(o.get("flag"), "true");
  EXPECT_EQ(o.values.at("v"), (std::vector<std::string>{"4", "12"}));
}

TEST(Scene, BadScenesAreRefusedNamingTheField) {
  TempDir d;
  const std::set<std::string> allowed{"a", "eps", "theta"};
  // A TOML float has already lost the exact decimal: refused, naming its key.
  const std::string f = put(d / "f.toml", "command = \"orbit\"\na = 28.82\n");
  EXPECT_TRUE(contains(expect_input_error([&] { load_scene(f, "orbit", allowed); }, "a"), "write decimals as strings"));
  const std::string fl = put(d / "fl.toml", "command = \"orbit\"\ntheta = [\"0.5\", 0.25]\n");
  expect_input_error([&] { load_scene(fl, "orbit", allowed); }, "theta");
  const std::string t = put(d / "t.toml", "command = \"orbit\"\neps = { x = \"1\" }\n");
  EXPECT_TRUE(contains(expect_input_error([&] { load_scene(t, "orbit", allowed); }, "eps"), "must be a string or an integer"));
  const std::string e = put(d / "e.toml", "command = \"orbit\"\ntheta = []\n");
  EXPECT_TRUE(contains(expect_input_error([&] { load_scene(e, "orbit", allowed); }, "theta"), "an empty list"));
  // Scene-level problems name the scene.
  const std::string u = put(d / "u.toml", "command = \"orbit\"\nsteps = 3\n");
  EXPECT_TRUE(contains(expect_input_error([&] { load_scene(u, "orbit", allowed); }, "scene"), "unknown key 'steps'"));
  const std::string w = put(d / "w.toml", "command = \"basin\"\na = \"24\"\n");
  EXPECT_TRUE(contains(expect_input_error([&] { load_scene(w, "orbit", allowed); }, "scene"), "is a scene for 'basin', not 'orbit'"));
  const std::string bad = put(d / "bad.toml", "command = \"orbit\"\na = \"24\n");
  const std::string m = expect_input_error([&] { load_scene(bad, "orbit", allowed); }, "scene");
  EXPECT_TRUE(contains(m, "line 2")) << m;
  const std::string none = put(d / "none.toml", "a = \"24\"\n");
  EXPECT_TRUE(contains(expect_input_error([&] { scene_command(none); }, "scene"), "has no command"));
  expect_input_error([&] { scene_command(d / "missing.toml"); }, "scene");
  expect_input_error([&] { scene_command(d.path.string()); }, "scene");
}

TEST(Scene, EveryShippedSceneNamesItsCommand) {
  // Truth outside the TOML parser: the scene's own `command = "NAME"` line, found by hand.
  const fs::path dir = fs::path(BOUNCER_SOURCE_DIR) / "data/scenes";
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::ifstream f(e.path());
    std::string line, expected;
    const std::string key = "command = \"";
    while (std::getline(f, line))
      if (line.rfind(key, 0) == 0) expected = line.substr(key.size(), line.find('"', key.size()) - key.size());
    ASSERT_FALSE(expected.empty()) << e.path();
    EXPECT_EQ(scene_command(e.path().string()), expected) << e.path();
    ++n;
  }
  EXPECT_GE(n, 10);
}

// ---- the model group --------------------------------------------------------------------------

void expect_same_model(const ModelSpec& x, const ModelSpec& y) {
  EXPECT_EQ(x.law, y.law);
  EXPECT_EQ(x.a, y.a);
  if (x.law == Law::constant) {
    EXPECT_EQ(x.eps, y.eps);
  }
  if (x.law == Law::veldep) {
    EXPECT_EQ(x.c, y.c);
  }
  EXPECT_EQ(x.wall.text, y.wall.text);
  EXPECT_EQ(x.wall.knots, y.wall.knots);
  EXPECT_EQ(x.wall.heights, y.wall.heights);
  EXPECT_EQ(x.downward, y.downward);
  EXPECT_EQ(x.veldep_collapse, y.veldep_collapse);
}

TEST(ModelFrom, BuildsTheModelOfTheDecimals) {
  Options o = model_options("constant", "24");
  o.set("eps", "0.5");
  const ModelSpec m = model_from(o);
  expect_same_model(m, spec(Law::constant, "24", "0.5"));
  EXPECT_EQ(m.a.value(), mpq_class(24));
  EXPECT_EQ(m.eps.value(), mpq_class(1, 2));
  // The defaults: the triangle wall and the paper's downward-sticking convention.
  EXPECT_EQ(m.downward, DownwardSticking::paper);
  EXPECT_FALSE(m.veldep_collapse);
  Options v = model_options("veldep", "28.82");
  v.set("c", "1000");
  v.set("veldep-collapse", "on");
  v.set("downward-sticking", "impact");
  const ModelSpec mv = model_from(v);
  EXPECT_EQ(mv.a.value(), mpq_class(1441, 50));
  EXPECT_EQ(mv.c.value(), mpq_class(1000));
  EXPECT_TRUE(mv.veldep_collapse);
  EXPECT_EQ(mv.downward, DownwardSticking::impact);
  expect_same_model(model_from(model_options("elastic", "18")), spec(Law::elastic, "18"));
  Options w = model_options("elastic", "18");
  w.set("wall", "asymmetric:0.25");
  EXPECT_EQ(model_from(w).wall.knots.size(), 2u);
  EXPECT_EQ(model_from(w).wall.knots[1].value(), mpq_class(1, 4));
}

TEST(ModelFrom, BadModelsNameTheField) {
  expect_input_error([] { model_from(model_options("constant", "24")); }, "eps");  // eps required
  expect_input_error([] { model_from(model_options("veldep", "24")); }, "c");      // c required
  expect_input_error([] { model_from(model_options("inelastic", "24")); }, "model");
  Options no_a;
  no_a.set("model", "elastic");
  expect_input_error([&] { model_from(no_a); }, "a");
  expect_input_error([] { model_from(model_options("elastic", "nan")); }, "a");
  expect_input_error([] { model_from(model_options("elastic", "0")); }, "a");
  Options e = model_options("elastic", "24");
  e.set("eps", "0.5");
  EXPECT_TRUE(contains(expect_input_error([&] { model_from(e); }, "eps"), "only used with --model constant"));
  Options c = model_options("constant", "24");
  c.set("eps", "0.5");
  c.set("c", "10");
  EXPECT_TRUE(contains(expect_input_error([&] { model_from(c); }, "c"), "only used with --model veldep"));
  Options big_eps = model_options("constant", "24");
  big_eps.set("eps", "1.0000000000000000001");
  expect_input_error([&] { model_from(big_eps); }, "eps");
  Options col = model_options("veldep", "24");
  col.set("c", "10");
  col.set("veldep-collapse", "yes");
  EXPECT_TRUE(contains(expect_input_error([&] { model_from(col); }, "veldep-collapse"), "must be on or off"));
  Options col2 = model_options("constant", "24");
  col2.set("eps", "0.5");
  col2.set("veldep-collapse", "on");
  expect_input_error([&] { model_from(col2); }, "veldep-collapse");
  Options wall = model_options("elastic", "24");
  wall.set("wall", "square");
  expect_input_error([&] { model_from(wall); }, "wall");
  Options down = model_options("elastic", "24");
  down.set("downward-sticking", "slide");
  expect_input_error([&] { model_from(down); }, "downward-sticking");
}

TEST(ModelKeys, AreTheKeysModelFromReads) {
  const std::set<std::string> expected{"model", "a", "eps", "c", "wall", "downward-sticking", "veldep-collapse"};
  EXPECT_EQ(model_keys(), expected);
}

// ---- precision ----------------------------------------------------------------------------

TEST(PrecisionOption, ParsesEveryFamilyAndItsTextReadsBack) {
  struct Case {
    const char* text;
    Precision::Kind kind;
    long bits;
    bool interval;
  };
  const Case cases[] = {{"double", Precision::Kind::double_, 53, false},
                        {"long", Precision::Kind::long_double, 64, false},
                        {"dd", Precision::Kind::dd, 106, false},
                        {"quad", Precision::Kind::quad, 113, false},
                        {"mpfr:200", Precision::Kind::mpfr, 200, false},
                        {"interval:128", Precision::Kind::interval, 128, true},
                        {"interval:double", Precision::Kind::interval_double, 53, true}};
  for (const Case& c : cases) {
    const Precision p = parse_precision("precision", c.text);
    EXPECT_EQ(p.kind, c.kind) << c.text;
    EXPECT_EQ(p.bits, c.bits) << c.text;
    EXPECT_EQ(p.is_interval(), c.interval) << c.text;
    EXPECT_EQ(p.text(), c.text);
    const Precision back = parse_precision("precision", p.text());
    EXPECT_EQ(back.kind, p.kind);
    EXPECT_EQ(back.bits, p.bits);
  }
  Options o;
  EXPECT_EQ(precision_from(o).kind, Precision::Kind::double_);  // the default
  o.set("precision", "mpfr:64");
  EXPECT_EQ(precision_from(o).bits, 64);
}

TEST(PrecisionOption, BitsAreBoundedAndWhole) {
  const std::string lo = std::to_string(kMinBits), hi = std::to_string(kMaxBits);
  EXPECT_EQ(parse_precision("precision", "mpfr:" + lo).bits, kMinBits);
  EXPECT_EQ(parse_precision("precision", "interval:" + hi).bits, kMaxBits);
  for (const std::string& bad : {"mpfr:" + std::to_string(kMinBits - 1), "interval:" + std::to_string(kMaxBits + 1),
                                std::string("mpfr:99999999999999999999999")})
    EXPECT_TRUE(contains(expect_input_error([&] { parse_precision("precision", bad); }, "precision"), "bits out of range"))
        << bad;
  for (const char* bad : {"mpfr:64.5", "mpfr:+64", "mpfr:6.4e1", "mpfr:", "mpfr:-64", "mpfr: 64"})
    EXPECT_TRUE(contains(expect_input_error([&] { parse_precision("precision", bad); }, "precision"), "whole number")) << bad;
  for (const char* bad : {"float", "MPFR:64", "mpfr", "double:53", "", "interval"})
    EXPECT_TRUE(contains(expect_input_error([&] { parse_precision("precision", bad); }, "precision"), "unknown precision")) << bad;
  // The field given is the one named (a scene key other than "precision").
  expect_input_error([] { parse_precision("reference", "triple"); }, "reference");
  Options o;
  o.set("precision", "mpfr:8");
  expect_input_error([&] { precision_from(o); }, "precision");
}

TEST(PrecisionOption, DecimalNoteSaysRoundedOrEnclosed) {
  const std::string point = decimal_note(parse_precision("p", "mpfr:256"));
  EXPECT_TRUE(contains(point, "rounded to the nearest mpfr:256 value")) << point;
  const std::string box = decimal_note(parse_precision("p", "interval:256"));
  EXPECT_TRUE(contains(box, "enclosed exactly")) << box;
  EXPECT_FALSE(contains(box, "rounded to the nearest")) << box;
}

// ---- integers and initial conditions -------------------------------------------------------------

TEST(IntegerFrom, BoundsAreInclusiveAndOutOfRangeNamesTheKey) {
  Options o;
  EXPECT_EQ(integer_from(o, "steps", 0, 100, 10), 10);  // absent: the fallback
  for (const auto& [text, value] : std::vector<std::pair<std::string, long long>>{
           {"0", 0}, {"100", 100}, {"37", 37}, {"007", 7}, {"-0", 0}, {"5.0", 5}}) {
    o.set("steps", text);
    EXPECT_EQ(integer_from(o, "steps", 0, 100, 10), value) << text;
  }
  o.set("every", "-5");
  EXPECT_EQ(integer_from(o, "every", -5, 5, 1), -5);
  // The extremes of long long, exactly.
  o.set("n", "9223372036854775807");
  EXPECT_EQ(integer_from(o, "n", 0, 9223372036854775807LL, 0), 9223372036854775807LL);
  for (const char* bad : {"-1", "101", "100000000000000000000000000000"}) {
    o.set("steps", bad);
    EXPECT_TRUE(contains(expect_input_error([&] { integer_from(o, "steps", 0, 100, 10); }, "steps"),
                         "an integer in [0, 100]"))
        << bad;
  }
  for (const char* bad : {"2.5", "ten", "", "1/2", "0x10", "inf"}) {
    o.set("steps", bad);
    EXPECT_TRUE(contains(expect_input_error([&] { integer_from(o, "steps", 0, 100, 10); }, "steps"),
                         "must be an integer in [0, 100]"))
        << bad;
  }
  o.set("steps", std::vector<std::string>{"1", "2"});
  expect_input_error([&] { integer_from(o, "steps", 0, 100, 10); }, "steps");
}

TEST(InitialConditions, ListsPairUpAndEachStartIsValidated) {
  const ModelSpec m = spec(Law::constant, "24", "0.5");
  Options o;
  o.set("theta", std::vector<std::string>{"0.25", "0.5", "0.75"});
  o.set("v", std::vector<std::string>{"12", "4", "-4"});
  const auto ics = initial_conditions_from(o, m);
  ASSERT_EQ(ics.size(), 3u);
  EXPECT_EQ(ics[0].theta.value(), mpq_class(1, 4));
  EXPECT_EQ(ics[0].v.value(), mpq_class(12));
  EXPECT_EQ(ics[1].theta.value(), mpq_class(1, 2));
  EXPECT_EQ(ics[2].v.value(), mpq_class(-4));
  // The triangle wall moves at +4 on [0, 1/2) and -4 on [1/2, 1): v = -4 at theta = 0.25
  // is inside the wall, at theta = 0.75 it moves with it.
  Options inside;
  inside.set("theta", "0.25");
  inside.set("v", "-4");
  expect_input_error([&] { initial_conditions_from(inside, m); }, "v");
  inside.set("theta", "0.75");
  EXPECT_EQ(initial_conditions_from(inside, m).size(), 1u);
  Options one_v;
  one_v.set("theta", std::vector<std::string>{"0.25", "0.5"});
  one_v.set("v", "12");
  EXPECT_TRUE(contains(expect_input_error([&] { initial_conditions_from(one_v, m); }, "v"), "as many values as theta (2)"));
  Options phase;
  phase.set("theta", "1");
  phase.set("v", "12");
  expect_input_error([&] { initial_conditions_from(phase, m); }, "theta");
  Options no_theta;
  no_theta.set("v", "12");
  EXPECT_TRUE(contains(expect_input_error([&] { initial_conditions_from(no_theta, m); }, "theta"), "is required"));
  Options bad_v;
  bad_v.set("theta", "0.25");
  bad_v.set("v", "12,5");
  expect_input_error([&] { initial_conditions_from(bad_v, m); }, "v");
}

}  // namespace
}  // namespace bouncer
