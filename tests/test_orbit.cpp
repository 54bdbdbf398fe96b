// The orbit driver (run/orbit.hpp follow_orbit) and its text sink (io/orbit.hpp
// write_orbits, the rows of `bouncer orbit`).
//
// Truth independent of the code:
//  * eq. 5's fixed point (p = 1), derived by hand: constant law, eps = 1/2, a = 24 =
//    8(1+eps)/(1-eps), triangle wall (velocity +4 on [0, 1/2)). From theta = 1/4 with v = 12
//    the flight x(t) = x0 + 12 t - 12 t^2 returns to the height x0 at t = 1, one wall period,
//    so the impact is at theta = 1/4 again with incoming velocity 12 - 24 = -12; the wall
//    moves at +4 there, so v' = 4 - eps(-12 - 4) = 12: (1/4, 12) maps to itself, tau = 1.
//  * which rows are kept: n = 0, then every n with n % every == 0, and the last step;
//  * cancellation is checked before steps 256, 512, ...: a flag set from the start stops
//    the run before step 256, after rows 1..255;
//  * the text sink writes one line per row the driver hands over, with the row's numbers
//    in the scalar's round-trip text (CSV compared cell by cell with the typed rows).
#include <gtest/gtest.h>

#include <atomic>
#include <sstream>
#include <string>
#include <vector>

#include "bouncer/base/cancel.hpp"
#include "bouncer/io/orbit.hpp"
#include "bouncer/run/orbit.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using test_support::spec;

// Keeps what the driver hands over.
template <class T>
struct Recorder final : OrbitSink<T> {
  std::vector<long long> n;
  std::vector<State<T>> states;
  std::vector<StepResult<T>> steps;
  void start(const State<T>& s) override {
    n.push_back(0);
    states.push_back(s);
  }
  void row(long long k, const StepResult<T>& r) override {
    n.push_back(k);
    states.push_back(r.next);
    steps.push_back(r);
  }
};

InitialCondition ic(const std::string& theta, const std::string& v) {
  return {parse_decimal("theta", theta), parse_decimal("v", v)};
}

TEST(OrbitDriver, EqFiveFixedPointMapsToItselfInIntervals) {
  const ModelSpec m = spec(Law::constant, "24", "0.5");
  for (const EnclosureMethod method : {EnclosureMethod::naive, EnclosureMethod::lohner}) {
    const ImpactMap<Mpfi> map(make_model<Mpfi>(m, 256));
    const State<Mpfi> s0 = make_state<Mpfi>(map.model(), ic("0.25", "12"));
    Recorder<Mpfi> rec;
    const OrbitOutcome o = follow_orbit(map, s0, OrbitSteps{5, 1, method}, rec);
    EXPECT_FALSE(o.undecided) << o.reason;
    EXPECT_EQ(o.steps_done, 5);
    EXPECT_EQ(o.fallbacks >= 0, method == EnclosureMethod::lohner);
    ASSERT_EQ(rec.steps.size(), 5u);
    for (const StepResult<Mpfi>& r : rec.steps) {
      EXPECT_EQ(r.kind, EventKind::impact);
      EXPECT_TRUE(r.next.theta.contains(s0.theta)) << r.next.theta;  // 1/4 exactly
      EXPECT_TRUE(r.next.v.contains(Mpfi(12L, 256))) << r.next.v;
      EXPECT_TRUE(r.tau.contains(Mpfi(1L, 256))) << r.tau;
      EXPECT_LT(r.next.v.width().to_double(), 1e-60);
    }
  }
}

TEST(OrbitDriver, EqFiveFixedPointInDouble) {
  const ImpactMap<double> map(make_model<double>(spec(Law::constant, "24", "0.5"), 53));
  Recorder<double> rec;
  follow_orbit(map, make_state<double>(map.model(), ic("0.25", "12")), OrbitSteps{3, 1, EnclosureMethod::naive}, rec);
  ASSERT_EQ(rec.steps.size(), 3u);
  for (const StepResult<double>& r : rec.steps) {
    EXPECT_NEAR(r.next.theta, 0.25, 1e-13);
    EXPECT_NEAR(r.next.v, 12, 1e-12);
    EXPECT_NEAR(r.tau, 1, 1e-13);
  }
}

TEST(OrbitDriver, KeepsEveryNthStepAndTheLast) {
  const ImpactMap<double> map(make_model<double>(spec(Law::constant, "24", "0.5"), 53));
  const State<double> s0 = make_state<double>(map.model(), ic("0.3", "9.5"));
  Recorder<double> rec;
  const OrbitOutcome o = follow_orbit(map, s0, OrbitSteps{10, 3, EnclosureMethod::naive}, rec);
  EXPECT_EQ(o.steps_done, 10);
  EXPECT_EQ(rec.n, (std::vector<long long>{0, 3, 6, 9, 10}));
  EXPECT_EQ(o.fallbacks, -1);  // not a Lohner run
  // The kept rows are the states of the full orbit at those steps.
  Recorder<double> all;
  follow_orbit(map, s0, OrbitSteps{10, 1, EnclosureMethod::naive}, all);
  ASSERT_EQ(all.n.size(), 11u);
  for (size_t i = 0; i < rec.n.size(); ++i) {
    EXPECT_EQ(rec.states[i].theta, all.states[rec.n[i]].theta);
    EXPECT_EQ(rec.states[i].v, all.states[rec.n[i]].v);
  }
  Recorder<double> none;
  EXPECT_EQ(follow_orbit(map, s0, OrbitSteps{0, 1, EnclosureMethod::naive}, none).steps_done, 0);
  EXPECT_EQ(none.n, std::vector<long long>{0});
}

TEST(OrbitDriver, CancellationStopsItBeforeStep256) {
  const ImpactMap<double> map(make_model<double>(spec(Law::constant, "24", "0.5"), 53));
  const std::atomic<bool> flag{true};
  const CancelScope scope(&flag);
  Recorder<double> rec;
  EXPECT_THROW(follow_orbit(map, make_state<double>(map.model(), ic("0.3", "9.5")), OrbitSteps{1000, 1, EnclosureMethod::naive}, rec),
               Cancelled);
  ASSERT_EQ(rec.n.size(), 256u);  // the start and steps 1..255
  EXPECT_EQ(rec.n.back(), 255);
}

TEST(OrbitDriver, AnUndecidedStepEndsTheRun) {
  // 16 bits: the boxes of a chaotic orbit grow until a branch cannot be decided.
  const ImpactMap<Mpfi> map(make_model<Mpfi>(spec(Law::constant, "28.82", "0.96"), 16));
  Recorder<Mpfi> rec;
  const OrbitOutcome o =
      follow_orbit(map, make_state<Mpfi>(map.model(), ic("0.3", "9.5")), OrbitSteps{100000, 1, EnclosureMethod::naive}, rec);
  ASSERT_TRUE(o.undecided);
  EXPECT_FALSE(o.reason.empty());
  EXPECT_LT(o.steps_done, 100000);
  EXPECT_EQ(rec.n.back(), o.steps_done);  // every decided step was handed over, no more
  EXPECT_EQ(static_cast<long long>(rec.n.size()), o.steps_done + 1);
}

// The CSV of write_orbits without its provenance lines: the header, then the rows' cells.
std::vector<std::vector<std::string>> csv_rows(const OrbitRequest& req, std::string* end_line) {
  std::ostringstream out;
  write_orbits(req, Provenance{}, out);
  std::istringstream in(out.str());
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# end:", 0) == 0) *end_line = line;
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream ls(line);
    while (std::getline(ls, cell, ',')) cells.push_back(cell);
    if (line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

TEST(OrbitTextSink, WritesExactlyTheDriversRowsInDouble) {
  OrbitRequest req;
  req.model = spec(Law::constant, "24", "0.5");
  req.initial = {ic("0.3", "9.5")};
  req.steps = 20;
  req.every = 3;
  req.precision = parse_precision("precision", "double");
  std::string end;
  const auto rows = csv_rows(req, &end);
  const ImpactMap<double> map(make_model<double>(req.model, 53));
  Recorder<double> rec;
  follow_orbit(map, make_state<double>(map.model(), req.initial[0]), orbit_steps(req), rec);
  ASSERT_EQ(rows.size(), rec.n.size() + 1);  // the header
  EXPECT_EQ(rows[0][0], "n");
  EXPECT_EQ(rows[0][1], "theta");
  using Tr = ScalarTraits<double>;
  for (size_t i = 0; i < rec.n.size(); ++i) {
    const auto& c = rows[i + 1];
    ASSERT_EQ(c.size(), rows[0].size());
    EXPECT_EQ(c[0], std::to_string(rec.n[i]));
    EXPECT_EQ(c[1], Tr::to_string(rec.states[i].theta));
    EXPECT_EQ(c[2], Tr::to_string(rec.states[i].v));
    if (i == 0) {
      EXPECT_EQ(c[3], "start");
    } else {
      EXPECT_EQ(c[3], name(rec.steps[i - 1].kind));
      EXPECT_EQ(c[4], Tr::to_string(rec.steps[i - 1].tau));
    }
  }
  EXPECT_EQ(end, "# end: orbit 0 completed 20 steps");
}

TEST(OrbitTextSink, WritesExactlyTheDriversBoxesWithLohner) {
  OrbitRequest req;
  req.model = spec(Law::constant, "24", "0.5");
  req.initial = {ic("0.3", "9.5")};
  req.steps = 12;
  req.precision = parse_precision("precision", "interval:double");
  req.method = EnclosureMethod::lohner;
  std::string end;
  const auto rows = csv_rows(req, &end);
  const ImpactMap<DoubleInterval> map(make_model<DoubleInterval>(req.model, 53));
  Recorder<DoubleInterval> rec;
  const OrbitOutcome o = follow_orbit(map, make_state<DoubleInterval>(map.model(), req.initial[0]), orbit_steps(req), rec);
  ASSERT_EQ(rows.size(), rec.n.size() + 1);
  EXPECT_EQ(rows[0][1], "theta_lo");
  EXPECT_EQ(rows[0][2], "theta_hi");
  using Tr = ScalarTraits<DoubleInterval>;
  for (size_t i = 0; i < rec.n.size(); ++i) {
    const auto& c = rows[i + 1];
    EXPECT_EQ(c[0], std::to_string(rec.n[i]));
    EXPECT_EQ(c[1], Tr::lower_string(rec.states[i].theta));
    EXPECT_EQ(c[2], Tr::upper_string(rec.states[i].theta));
    EXPECT_EQ(c[3], Tr::lower_string(rec.states[i].v));
    EXPECT_EQ(c[4], Tr::upper_string(rec.states[i].v));
  }
  const std::string expected = o.undecided ? "# end: orbit 0 undecided at step " + std::to_string(o.steps_done + 1) + ": "
                                           : "# end: orbit 0 completed 12 steps";
  EXPECT_EQ(end.substr(0, expected.size()), expected);
}

}  // namespace
}  // namespace bouncer
