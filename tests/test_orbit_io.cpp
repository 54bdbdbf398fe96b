// `bouncer orbit`'s library layer (io/orbit.hpp): orbit_request's validation and
// write_orbits' CSV, JSON and table output, against independent truth:
//   * the eq. 5 fixed point: constant eps = 1/2, a = 24, start (1/4, 12) on the rising
//     segment (wall height 0, velocity +4). The flight 12 s - 12 s^2 returns to height 0
//     after s = 1 (one period, clear of the wall: 8s - 12s^2 > 0 up to s = 1/4, then
//     -12s^2 + 16s - 2 > 0 and 4(1 - s)(3s + 1) > 0), lands at -12, relative speed 16 on
//     a wall moving at +4, leaves at 4 + 8 = 12: every step is (1/4, 12) with tau = 1;
//   * the period-1 sticking orbit through the release state R = (1/2, 4) (tests/README.md
//     "Continuation"; eps = 1/4, a = 24 lies in 8((1+eps)/(1-eps))^2 = 200/9 <= a < 32):
//     every step sticks after the impact at theta_i = sqrt(8/a) - 1/2 on the rising segment
//     and returns to R one period later (tau = 1);
//   * the exact corner hit of test_sticking.cpp (eps = 1/2, a = 63.5: the 7th impact from R
//     is exactly at theta = 1), which an interval run cannot decide: undecided at step 7;
//   * round trips: a number written then read back in its type (strtod, mpfr_set_str) is
//     the state the impact map computes, bit for bit; interval runs enclose the MPFR run;
//   * an independent JSON parser (nlohmann) and the CSV's own header.
#include <gtest/gtest.h>

#include <mpfr.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bouncer/io/orbit.hpp"
#include "bouncer/base/output.hpp"
#include "bouncer/model/impact_map.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using namespace test_support;

namespace fs = std::filesystem;

Options options(const std::string& eps, const std::string& a, const std::vector<std::string>& theta,
                const std::vector<std::string>& v, const std::string& steps, const std::string& precision) {
  Options o;
  o.set("model", "constant");
  o.set("eps", eps);
  o.set("a", a);
  o.set("theta", theta);
  o.set("v", v);
  o.set("steps", steps);
  o.set("precision", precision);
  return o;
}

Provenance provenance(const Options& o, const OrbitRequest& r) {
  Provenance p;
  p.command = "orbit";
  p.inputs = o.inputs();
  p.precision = r.precision.text();
  p.bits = r.precision.bits;
  p.decimal_note = decimal_note(r.precision);
  return p;
}

struct Written {
  std::string text;
  std::vector<OrbitOutcome> outcomes;
  Provenance p;
};

Written run(const Options& o) {
  const OrbitRequest r = orbit_request(o);
  Written out;
  out.p = provenance(o, r);
  std::ostringstream s;
  out.outcomes = write_orbits(r, out.p, s);
  out.text = s.str();
  return out;
}

// A CSV without its comment lines: the header's names and the rows as name -> cell.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  std::vector<std::string> comments;
};

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream s(line);
  while (std::getline(s, cell, sep)) out.push_back(cell);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

Csv read_csv(const std::string& text) {
  Csv c;
  std::istringstream s(text);
  for (std::string line; std::getline(s, line);) {
    if (line.rfind("#", 0) == 0) {
      c.comments.push_back(line);
      continue;
    }
    const auto cells = split(line, ',');
    if (c.header.empty()) {
      c.header = cells;
      continue;
    }
    EXPECT_EQ(cells.size(), c.header.size()) << line;
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < cells.size() && i < c.header.size(); ++i) row[c.header[i]] = cells[i];
    c.rows.push_back(row);
  }
  return c;
}

double num(const std::string& s) {
  EXPECT_FALSE(s.empty());
  return std::strtod(s.c_str(), nullptr);
}

// An interval column's ends as exact rationals (the writer prints decimals).
mpq_class exact(const std::string& s) {
  auto d = Decimal::parse(s);
  EXPECT_TRUE(d.has_value()) << s;
  return d ? d->value() : mpq_class(0);
}

void expect_encloses(const std::map<std::string, std::string>& row, const std::string& col, const mpq_class& x) {
  EXPECT_LE(exact(row.at(col + "_lo")), x) << col << " row " << row.at("n");
  EXPECT_GE(exact(row.at(col + "_hi")), x) << col << " row " << row.at("n");
}

// sqrt(1/3) - 1/2 to 300 bits, as an exact rational, and its width of uncertainty.
mpq_class sticking_theta(mpfr_rnd_t rnd) {
  mpfr_t x;
  mpfr_init2(x, 300);
  mpfr_set_ui(x, 1, rnd);
  mpfr_div_ui(x, x, 3, rnd);
  mpfr_sqrt(x, x, rnd);
  mpfr_sub_d(x, x, 0.5, rnd);
  mpq_class q;
  mpfr_get_q(q.get_mpq_t(), x);
  mpfr_clear(x);
  return q;
}

// ---- orbit_request ------------------------------------------------------------------------------

TEST(OrbitRequest, DefaultsAndTheIntervalMethod) {
  Options o = options("0.5", "24", {"0.25"}, {"12"}, "10", "double");
  o.values.erase("steps");
  o.values.erase("precision");
  const OrbitRequest r = orbit_request(o);
  EXPECT_EQ(r.steps, 10);
  EXPECT_EQ(r.every, 1);
  EXPECT_EQ(r.precision.text(), "double");
  EXPECT_EQ(r.format, Format::csv);
  EXPECT_EQ(r.method, EnclosureMethod::naive);
  ASSERT_EQ(r.initial.size(), 1u);
  EXPECT_EQ(r.initial[0].theta.value(), mpq_class(1, 4));
  EXPECT_EQ(r.model.eps.value(), mpq_class(1, 2));
  o.set("precision", "interval:128");
  EXPECT_EQ(orbit_request(o).method, EnclosureMethod::lohner);  // the certified commands' default
  o.set("method", "naive");
  EXPECT_EQ(orbit_request(o).method, EnclosureMethod::naive);
  o.set("format", "json");
  EXPECT_EQ(orbit_request(o).format, Format::json);
  o.set("format", "table");
  EXPECT_EQ(orbit_request(o).format, Format::table);
}

TEST(OrbitRequest, BadOptionsNameTheField) {
  const Options good = options("0.5", "24", {"0.25"}, {"12"}, "10", "double");
  auto with = [&](const std::string& k, const std::string& v) {
    Options o = good;
    o.set(k, v);
    return o;
  };
  expect_input_error([&] { orbit_request(with("steps", "-1")); }, "steps");
  expect_input_error([&] { orbit_request(with("steps", "1.5")); }, "steps");
  expect_input_error([&] { orbit_request(with("every", "0")); }, "every");
  EXPECT_TRUE(contains(expect_input_error([&] { orbit_request(with("format", "xml")); }, "format"), "csv, json, table"));
  EXPECT_TRUE(contains(expect_input_error([&] { orbit_request(with("method", "lohner")); }, "method"), "interval"));
  Options m = with("precision", "interval:64");
  m.set("method", "taylor");
  expect_input_error([&] { orbit_request(m); }, "method");
  expect_input_error([&] { orbit_request(with("precision", "mpfr:1")); }, "precision");
  expect_input_error([&] { orbit_request(with("eps", "2")); }, "eps");
  expect_input_error([&] { orbit_request(with("theta", "1.5")); }, "theta");
  expect_input_error([&] { orbit_request(with("v", "-5")); }, "v");  // inside the wall moving up at 4
}

TEST(OrbitRequest, EveryShippedOrbitSceneIsAccepted) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(fs::path(BOUNCER_SOURCE_DIR) / "data/scenes")) {
    if (scene_command(e.path().string()) != "orbit") continue;
    const Options o = load_scene(e.path().string(), "orbit", orbit_keys());
    const OrbitRequest r = orbit_request(o);
    EXPECT_GE(r.initial.size(), 1u) << e.path();
    ++n;
  }
  EXPECT_GE(n, 1);
}

// ---- the analytic orbits ----------------------------------------------------------------------------

TEST(WriteOrbits, TheEq5FixedPointStaysPutInDouble) {
  const Written r = run(options("0.5", "24", {"0.25"}, {"12"}, "10", "double"));
  ASSERT_EQ(r.outcomes.size(), 1u);
  EXPECT_EQ(r.outcomes[0].steps_done, 10);
  EXPECT_FALSE(r.outcomes[0].undecided);
  EXPECT_EQ(r.outcomes[0].fallbacks, -1);  // no Lohner run
  const Csv c = read_csv(r.text);
  ASSERT_EQ(c.rows.size(), 11u);
  EXPECT_EQ(c.rows[0].at("event"), "start");
  for (size_t n = 0; n < c.rows.size(); ++n) {
    const auto& row = c.rows[n];
    EXPECT_EQ(row.at("n"), std::to_string(n));
    EXPECT_NEAR(num(row.at("theta")), 0.25, 1e-13) << n;
    EXPECT_NEAR(num(row.at("v")), 12, 1e-12) << n;
    EXPECT_EQ(row.at("orbit"), "0");
    if (n == 0) continue;
    EXPECT_EQ(row.at("event"), "impact");
    EXPECT_NEAR(num(row.at("tau")), 1, 1e-12) << n;
    EXPECT_EQ(row.at("periods"), "1");
    EXPECT_EQ(row.at("segment"), "0");
    EXPECT_EQ(row.at("wall"), "up");
    EXPECT_EQ(row.at("sticking"), "");
  }
  EXPECT_EQ(c.comments.back(), "# end: orbit 0 completed 10 steps");
}

TEST(WriteOrbits, TheEq5FixedPointIsEnclosedInIntervals) {
  for (const char* method : {"lohner", "naive"}) {
    Options o = options("0.5", "24", {"0.25"}, {"12"}, "12", "interval:128");
    o.set("method", method);
    const Written r = run(o);
    EXPECT_EQ(r.outcomes[0].steps_done, 12) << method;
    EXPECT_EQ(r.outcomes[0].fallbacks >= 0, std::string(method) == "lohner");
    const Csv c = read_csv(r.text);
    ASSERT_EQ(c.rows.size(), 13u);
    EXPECT_EQ(std::count(c.header.begin(), c.header.end(), "theta"), 0);
    for (const auto& row : c.rows) {
      expect_encloses(row, "theta", mpq_class(1, 4));
      expect_encloses(row, "v", mpq_class(12));
      if (row.at("n") == "0") continue;
      expect_encloses(row, "tau", mpq_class(1));
      EXPECT_EQ(row.at("event"), "impact");
      // Enclosures of a fixed point at 128 bits stay far tighter than 1e-20.
      EXPECT_LT(exact(row.at("theta_hi")) - exact(row.at("theta_lo")), mpq_class(1, mpz_class("100000000000000000000")));
    }
  }
}

TEST(WriteOrbits, ThePeriodOneStickingOrbitReturnsToTheReleaseState) {
  const mpq_class lo = sticking_theta(MPFR_RNDD) - mpq_class(1, 1000000000), hi = sticking_theta(MPFR_RNDU) + mpq_class(1, 1000000000);
  const double ti = std::sqrt(1.0 / 3.0) - 0.5;
  {
    const Csv c = read_csv(run(options("0.25", "24", {"0.5"}, {"4"}, "5", "double")).text);
    ASSERT_EQ(c.rows.size(), 6u);
    for (size_t n = 1; n < c.rows.size(); ++n) {
      const auto& row = c.rows[n];
      EXPECT_EQ(row.at("event"), "sticking") << n;
      EXPECT_EQ(num(row.at("theta")), 0.5) << n;  // the release corner, exactly
      EXPECT_EQ(num(row.at("v")), 4) << n;
      EXPECT_NEAR(num(row.at("tau")), 1, 1e-12) << n;
      EXPECT_NEAR(num(row.at("stuck_theta")), ti, 1e-12) << n;
      EXPECT_EQ(row.at("sticking").substr(0, 2), "up") << n;  // the collapse is on the rising segment
    }
  }
  const Written r = run(options("0.25", "24", {"0.5"}, {"4"}, "5", "interval:128"));
  EXPECT_EQ(r.outcomes[0].steps_done, 5);
  const Csv c = read_csv(r.text);
  for (size_t n = 1; n < c.rows.size(); ++n) {
    const auto& row = c.rows[n];
    EXPECT_EQ(row.at("event"), "sticking");
    expect_encloses(row, "theta", mpq_class(1, 2));
    expect_encloses(row, "v", mpq_class(4));
    expect_encloses(row, "tau", mpq_class(1));
    // The enclosure of the collision phase meets [sqrt(1/3) - 1/2 +- 1e-9].
    EXPECT_LE(exact(row.at("stuck_theta_lo")), hi);
    EXPECT_GE(exact(row.at("stuck_theta_hi")), lo);
  }
  // Outside the existence interval (a < 200/9 at eps = 1/4) the first step does not stick.
  const Csv below = read_csv(run(options("0.25", "22", {"0.5"}, {"4"}, "1", "double")).text);
  ASSERT_EQ(below.rows.size(), 2u);
  EXPECT_EQ(below.rows[1].at("event"), "impact");
}

TEST(WriteOrbits, AnExactCornerHitIsUndecidedInIntervalsOnly) {
  // eps = 1/2, a = 63.5 from R: the 7th impact is exactly at theta = 1 (test_sticking.cpp).
  Options o = options("0.5", "63.5", {"0.5"}, {"4"}, "10", "interval:128");
  o.set("method", "naive");
  const Written r = run(o);
  ASSERT_EQ(r.outcomes.size(), 1u);
  EXPECT_TRUE(r.outcomes[0].undecided);
  EXPECT_EQ(r.outcomes[0].steps_done, 6);
  EXPECT_FALSE(r.outcomes[0].reason.empty());
  const Csv c = read_csv(r.text);
  EXPECT_EQ(c.rows.size(), 7u);  // the start and steps 1..6
  EXPECT_TRUE(contains(c.comments.back(), "# end: orbit 0 undecided at step 7: ")) << c.comments.back();
  EXPECT_TRUE(contains(c.comments.back(), "(steps 1..6 done; rerun at more bits)")) << c.comments.back();
  // A point run takes one of the branches and goes on.
  const Written d = run(options("0.5", "63.5", {"0.5"}, {"4"}, "10", "double"));
  EXPECT_FALSE(d.outcomes[0].undecided);
  EXPECT_EQ(d.outcomes[0].steps_done, 10);
}

// ---- round trips and agreement between precisions ------------------------------------------------------

TEST(WriteOrbits, DoubleCellsReadBackAsTheMapsDoubles) {
  const Options o = options("0.5", "24", {"0.1"}, {"7"}, "30", "double");
  const OrbitRequest req = orbit_request(o);
  const ImpactMap<double> map(make_model<double>(req.model, 53));
  State<double> s = make_state<double>(map.model(), req.initial[0]);
  const Csv c = read_csv(run(o).text);
  ASSERT_EQ(c.rows.size(), 31u);
  EXPECT_EQ(num(c.rows[0].at("theta")), s.theta);
  for (size_t n = 1; n < c.rows.size(); ++n) {
    const StepResult<double> r = map.step(s);
    s = r.next;
    EXPECT_EQ(num(c.rows[n].at("theta")), r.next.theta) << n;
    EXPECT_EQ(num(c.rows[n].at("v")), r.next.v) << n;
    EXPECT_EQ(num(c.rows[n].at("tau")), r.tau) << n;
    EXPECT_EQ(c.rows[n].at("event"), name(r.kind)) << n;
  }
}

TEST(WriteOrbits, MpfrCellsReadBackAndIntervalsEncloseThem) {
  const Options o = options("0.5", "24", {"0.1"}, {"7"}, "15", "mpfr:200");
  const OrbitRequest req = orbit_request(o);
  const ImpactMap<Mpfr> map(make_model<Mpfr>(req.model, 200));
  State<Mpfr> s = make_state<Mpfr>(map.model(), req.initial[0]);
  const Csv c = read_csv(run(o).text);
  const Csv box = read_csv(run(options("0.5", "24", {"0.1"}, {"7"}, "15", "interval:128")).text);
  ASSERT_EQ(c.rows.size(), 16u);
  ASSERT_EQ(box.rows.size(), 16u);
  mpfr_t x;
  mpfr_init2(x, 200);
  for (size_t n = 1; n < c.rows.size(); ++n) {
    s = map.step(s).next;
    for (const char* col : {"theta", "v"}) {
      ASSERT_EQ(mpfr_set_str(x, c.rows[n].at(col).c_str(), 10, MPFR_RNDN), 0) << c.rows[n].at(col);
      EXPECT_TRUE(mpfr_equal_p(x, (std::string(col) == "theta" ? s.theta : s.v).get())) << col << " row " << n;
      // The exact orbit is in the box; the 200-bit point is within 2^-150 of it here.
      mpq_class q;
      mpfr_get_q(q.get_mpq_t(), x);
      const mpq_class slack(1, mpz_class(1) << 150);
      EXPECT_LE(exact(box.rows[n].at(std::string(col) + "_lo")) - slack, q) << col << " row " << n;
      EXPECT_GE(exact(box.rows[n].at(std::string(col) + "_hi")) + slack, q) << col << " row " << n;
    }
    EXPECT_EQ(c.rows[n].at("event"), box.rows[n].at("event"));
  }
  mpfr_clear(x);
}

// ---- layout: every, several orbits, formats ---------------------------------------------------------------

TEST(WriteOrbits, EveryKeepsEveryKthRowAndTheLast) {
  Options o = options("0.5", "24", {"0.25", "0.1"}, {"12", "7"}, "10", "double");
  o.set("every", "3");
  const Written r = run(o);
  ASSERT_EQ(r.outcomes.size(), 2u);
  const Csv c = read_csv(r.text);
  std::vector<std::string> got;
  for (const auto& row : c.rows) got.push_back(row.at("orbit") + ":" + row.at("n"));
  EXPECT_EQ(got, (std::vector<std::string>{"0:0", "0:3", "0:6", "0:9", "0:10", "1:0", "1:3", "1:6", "1:9", "1:10"}));
  // The provenance comes first, as written by the Provenance; each orbit ends with its line.
  EXPECT_EQ(r.text.rfind(r.p.as_comment_lines(), 0), 0u);
  EXPECT_TRUE(contains(r.text, "# end: orbit 0 completed 10 steps\n"));
  EXPECT_EQ(c.comments.back(), "# end: orbit 1 completed 10 steps");
}

TEST(WriteOrbits, JsonHasTheCsvColumnsAndRows) {
  for (const char* precision : {"double", "interval:64"}) {
    Options o = options("0.5", "24", {"0.25", "0.1"}, {"12", "7"}, "4", precision);
    const Csv csv = read_csv(run(o).text);
    o.set("format", "json");
    const Written r = run(o);
    const nlohmann::json j = nlohmann::json::parse(r.text);
    EXPECT_EQ(j.at("provenance"), nlohmann::json::parse(r.p.as_json()));
    EXPECT_EQ(j.at("columns").get<std::vector<std::string>>(), csv.header) << precision;
    ASSERT_EQ(j.at("orbits").size(), 2u);
    size_t k = 0;
    for (size_t orbit = 0; orbit < 2; ++orbit) {
      const auto& ob = j.at("orbits")[orbit];
      EXPECT_EQ(ob.at("orbit"), orbit);
      EXPECT_EQ(ob.at("end").at("status"), "completed");
      EXPECT_EQ(ob.at("end").at("steps_done"), 4);
      EXPECT_EQ(ob.at("end").contains("lohner_fallbacks"), std::string(precision) != "double");
      ASSERT_EQ(ob.at("rows").size(), 5u);
      for (const auto& row : ob.at("rows")) {
        ASSERT_LT(k, csv.rows.size());
        for (size_t i = 0; i < csv.header.size(); ++i)
          EXPECT_EQ(row[i].get<std::string>(), csv.rows[k].at(csv.header[i])) << csv.header[i];
        ++k;
      }
    }
    EXPECT_EQ(k, csv.rows.size());
  }
}

TEST(WriteOrbits, TableRowsHoldTheCsvCells) {
  Options o = options("0.5", "24", {"0.1"}, {"7"}, "5", "double");
  const Csv csv = read_csv(run(o).text);
  o.set("format", "table");
  const Written r = run(o);
  std::istringstream s(r.text);
  std::vector<std::vector<std::string>> lines;
  for (std::string line; std::getline(s, line);) {
    if (line.rfind("#", 0) == 0) continue;
    std::istringstream w(line);
    std::vector<std::string> tokens;
    for (std::string t; w >> t;) tokens.push_back(t);
    lines.push_back(tokens);
  }
  ASSERT_EQ(lines.size(), csv.rows.size() + 1);
  EXPECT_EQ(lines[0], csv.header);  // the header has no empty cells
  for (size_t n = 0; n < csv.rows.size(); ++n) {
    ASSERT_GE(lines[n + 1].size(), 4u);
    EXPECT_EQ(lines[n + 1][0], csv.rows[n].at("n"));
    EXPECT_EQ(lines[n + 1][1], csv.rows[n].at("theta"));
    EXPECT_EQ(lines[n + 1][2], csv.rows[n].at("v"));
    EXPECT_EQ(lines[n + 1][3], csv.rows[n].at("event"));
  }
}

// ---- failures ---------------------------------------------------------------------------------------------

TEST(WriteOrbits, AStartThatRoundsToOneWritesNothing) {
  // 0.99999999999999999999 < 1 exactly (accepted by the request), but it rounds to 1 in
  // double: refused naming theta before a byte is written. At 128 bits it is a fine start.
  const Options o = options("0.5", "24", {"0.25", "0.99999999999999999999"}, {"12", "20"}, "3", "double");
  const OrbitRequest req = orbit_request(o);
  std::ostringstream out;
  EXPECT_TRUE(contains(expect_input_error([&] { write_orbits(req, provenance(o, req), out); }, "theta"), "rounds to 1"));
  EXPECT_EQ(out.str(), "");
  Options fine = o;
  fine.set("precision", "mpfr:128");
  EXPECT_EQ(run(fine).outcomes.size(), 2u);
}

TEST(WriteOrbits, AFailedStreamIsAnOutputError) {
  const Options o = options("0.5", "24", {"0.25"}, {"12"}, "3", "double");
  const OrbitRequest req = orbit_request(o);
  std::ostringstream out;
  out.setstate(std::ios::badbit);
  EXPECT_THROW(write_orbits(req, provenance(o, req), out), OutputError);
}

// --format npy: the period-1 sticking orbit through R = (1/2, 4) (eps = 1/4, a = 24, see the
// top of this file) in float64: every step sticks on the rising segment at theta_i =
// sqrt(1/3) - 1/2 and returns to R exactly, tau = 1. The header is the NumPy format 1.0
// preamble, written here from its specification; empty CSV cells are NaN.
TEST(WriteOrbitsNpy, TheStickingOrbitAsFloat64Rows) {
  Options o = options("0.25", "24", {"0.5", "0.5"}, {"4", "4"}, "10", "double");
  o.set("format", "npy");
  expect_input_error([&] { orbit_request(o); }, "out");  // binary output needs a file
  o.set("out", "x.npy");
  o.set("every", "3");
  const OrbitRequest req = orbit_request(o);
  EXPECT_EQ(req.format, Format::npy);
  EXPECT_EQ(planned_orbit_rows(req), 2 * 5);  // per orbit: n = 0, 3, 6, 9 and the last, 10
  std::ostringstream out;
  const NpyOrbits w = write_orbits_npy(req, planned_orbit_rows(req), out);
  const std::string bytes = out.str();
  const size_t cols = npy_orbit_columns().size();
  ASSERT_EQ(cols, 16u);
  ASSERT_EQ(w.total_rows, 10);
  ASSERT_EQ(w.rows, (std::vector<long long>{5, 5}));
  ASSERT_EQ(bytes.size(), 128 + 10 * cols * 8);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  EXPECT_EQ(static_cast<unsigned char>(bytes[8]) + 256 * static_cast<unsigned char>(bytes[9]), 118);
  const std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (10, 16), }";
  EXPECT_EQ(bytes.substr(10, dict.size()), dict);
  EXPECT_EQ(bytes[127], '\n');
  EXPECT_EQ(bytes.find_first_not_of(' ', 10 + dict.size()), 127u);
  auto at = [&](size_t row, const std::string& name) {
    const size_t c = static_cast<size_t>(std::find(npy_orbit_columns().begin(), npy_orbit_columns().end(), name) -
                                         npy_orbit_columns().begin());
    double x;
    std::memcpy(&x, bytes.data() + 128 + (row * cols + c) * 8, 8);
    return x;
  };
  const double ti = std::sqrt(1.0 / 3.0) - 0.5;
  const long long n_of[] = {0, 3, 6, 9, 10};
  for (size_t r = 0; r < 10; ++r) {
    EXPECT_EQ(at(r, "n"), static_cast<double>(n_of[r % 5])) << r;
    EXPECT_EQ(at(r, "orbit"), static_cast<double>(r / 5)) << r;
    EXPECT_EQ(at(r, "theta"), 0.5) << r;
    EXPECT_EQ(at(r, "v"), 4.0) << r;
    if (r % 5 == 0) {
      EXPECT_EQ(at(r, "event"), 0.0);
      for (const char* empty : {"tau", "periods", "segment", "wall", "corner", "indirect", "stick_wall",
                                "passed_upward_turn", "stuck_theta", "stuck_v", "phase_bits"})
        EXPECT_TRUE(std::isnan(at(r, empty))) << empty;
      continue;
    }
    EXPECT_EQ(at(r, "event"), 2.0) << r;  // sticking
    EXPECT_NEAR(at(r, "tau"), 1, 1e-12) << r;
    EXPECT_EQ(at(r, "stick_wall"), 1.0) << r;  // the rising segment
    EXPECT_NEAR(at(r, "stuck_theta"), ti, 1e-12) << r;
    EXPECT_GE(at(r, "phase_bits"), 51) << r;  // one period's flight costs theta at most a bit or two
    EXPECT_LE(at(r, "phase_bits"), 53) << r;
  }
  // The header rewritten in place for another row count keeps its 128 bytes.
  const fs::path tmp = fs::temp_directory_path() / ("bouncer_npy_" + std::to_string(::getpid()));
  {
    std::ofstream f(tmp, std::ios::binary);
    f << bytes;
  }
  const int fd = ::open(tmp.c_str(), O_WRONLY);
  ASSERT_GE(fd, 0);
  rewrite_npy_header(fd, tmp.string(), 7, cols);
  ::close(fd);
  std::ifstream f(tmp, std::ios::binary);
  const std::string back((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  fs::remove(tmp);
  ASSERT_EQ(back.size(), bytes.size());
  EXPECT_EQ(back.substr(0, 128), npy_header(7, cols));
  EXPECT_NE(back.find("'shape': (7, 16), }"), std::string::npos);
  EXPECT_EQ(back.substr(128), bytes.substr(128));
  // Precisions whose values are not doubles are refused, naming --format.
  for (const char* p : {"long", "dd", "quad", "mpfr:53", "interval:double"}) {
    Options q = o;
    q.set("precision", p);
    EXPECT_TRUE(contains(expect_input_error([&] { orbit_request(q); }, "format"), "--precision double")) << p;
  }
}

}  // namespace
}  // namespace bouncer
