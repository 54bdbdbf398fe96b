// The command reports of the io layer (io/reports/: continue, sweep, certify-periodic,
// certify-sticking) on small typed results built by hand. The truth is derived here from
// the values given, never from the program's output:
//   * the JSON parses with an independent parser (nlohmann) and holds the given values
//     (numbers that read back to the same double, exact decimal texts);
//   * a CSV has its header, one row per item, and fields that an RFC 4180 reader (below)
//     reads back as the given texts;
//   * a sentence names the cause of an end and the parameter value where it lies.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "bouncer/io/grid_figures.hpp"
#include "bouncer/io/reports/certify_periodic.hpp"
#include "bouncer/io/reports/certify_sticking.hpp"
#include "bouncer/io/reports/continue.hpp"
#include "bouncer/io/reports/sweep.hpp"
#include "bouncer/model/model.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using json = nlohmann::ordered_json;  // keeps the order of the keys as written

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

Provenance sample_provenance(const std::string& command) {
  Provenance p;
  p.command = command;
  p.inputs = {{"a", "0.5"}};
  p.precision = "double";
  p.bits = 53;
  p.invocation = "bouncer " + command;
  return p;
}

// The lines of a text without the "# " provenance lines.
std::vector<std::string> data_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("#", 0) != 0) lines.push_back(line);
  return lines;
}

// An RFC 4180 record: fields split at commas outside double quotes, "" inside quotes a quote.
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> f(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        f.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        f.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      f.emplace_back();
    } else {
      f.back() += c;
    }
  }
  EXPECT_FALSE(quoted) << "unterminated quote in " << line;
  return f;
}

// ---- sweep -------------------------------------------------------------------------------

SweepQuestion sweep_question() {
  SweepQuestion q;
  q.model = test_support::spec(Law::constant, "0.5", "0.7");
  q.start = {parse_decimal("theta", "0.25"), parse_decimal("v", "3")};
  q.steps = 200;
  q.tolerance = 0x1p-20;
  return q;
}

// Two rows leave the enclosure (at steps 40 and 52, bits 53 and 64), one stays; the answer
// texts hold a comma and quotes.
SweepReport sweep_report() {
  SweepReport r;
  r.reference_bits = 128;
  r.reference_steps = 150;  // fewer than the 200 asked
  r.reference_status = "covers 150 of 200 steps";
  r.reference_answer = "sticks, period 7";
  Attempt a;
  a.bits = 128;
  a.decided = true;
  a.steps = 150;
  a.seconds = 0.25;
  r.reference_attempts = {a};
  SweepRow d;
  d.precision = "double";
  d.bits = 53;
  d.leaves_at = 40;
  d.answer = "sticks, period 9";
  SweepRow l;
  l.precision = "long";
  l.bits = 64;
  l.leaves_at = 52;
  l.answer = "the \"same\" orbit, period 7";
  Classification c;
  c.cls = OrbitClass::chaotic;
  c.lambda = 0.1;
  c.evidence = "positive exponent";
  l.classification = c;
  SweepRow m;
  m.precision = "mpfr:256";
  m.bits = 256;
  m.answer = "sticks, period 7";
  r.rows = {d, l, m};
  r.slope = 12.0 / 11.0;  // (52 - 40) / (64 - 53)
  r.implied_lyapunov = std::log(2.0) / *r.slope;
  r.seconds = 1.5;
  return r;
}

TEST(SweepReport, JsonHoldsTheGivenNumbers) {
  const SweepQuestion q = sweep_question();
  const SweepReport rep = sweep_report();
  const json j = json::parse(sweep_json(rep, q, sample_provenance("sweep")));
  EXPECT_EQ(j.begin().key(), "provenance");
  EXPECT_EQ(j["provenance"]["command"], "sweep");
  EXPECT_EQ(j["inputs"]["a"], "0.5");
  EXPECT_EQ(j["inputs"]["eps"], "0.7");
  EXPECT_EQ(j["inputs"]["steps"], 200);
  EXPECT_EQ(j["tolerance"].get<double>(), 0x1p-20);
  EXPECT_EQ(j["reference"]["bits"], 128);
  EXPECT_EQ(j["reference"]["steps"], 150);
  EXPECT_EQ(j["reference"]["answer"], "sticks, period 7");
  ASSERT_EQ(j["reference"]["attempts"].size(), 1u);
  EXPECT_EQ(j["reference"]["attempts"][0]["seconds"].get<double>(), 0.25);
  ASSERT_EQ(j["rows"].size(), 3u);
  EXPECT_EQ(j["rows"][0]["leaves_enclosure_at"], 40);
  EXPECT_TRUE(j["rows"][0]["class"].is_null());
  EXPECT_EQ(j["rows"][1]["class"], "chaotic");
  EXPECT_EQ(j["rows"][1]["lambda"].get<double>(), 0.1);
  EXPECT_EQ(j["rows"][1]["answer"], "the \"same\" orbit, period 7");
  EXPECT_TRUE(j["rows"][2]["leaves_enclosure_at"].is_null());
  EXPECT_EQ(j["slope_steps_per_bit"].get<double>(), 12.0 / 11.0);
  EXPECT_EQ(j["implied_lyapunov"].get<double>(), std::log(2.0) / (12.0 / 11.0));
  EXPECT_EQ(j["seconds"].get<double>(), 1.5);
}

TEST(SweepReport, JsonWithoutASlopeHasNulls) {
  SweepReport rep = sweep_report();
  rep.slope.reset();
  rep.implied_lyapunov.reset();
  const json j = json::parse(sweep_json(rep, sweep_question(), sample_provenance("sweep")));
  EXPECT_TRUE(j["slope_steps_per_bit"].is_null());
  EXPECT_TRUE(j["implied_lyapunov"].is_null());
}

TEST(SweepReport, CsvHasTheHeaderAndOneQuotedRowPerPrecision) {
  const SweepReport rep = sweep_report();
  const std::string csv = sweep_csv(rep, sample_provenance("sweep"));
  EXPECT_EQ(csv.rfind(sample_provenance("sweep").as_comment_lines(), 0), 0u);  // the provenance first
  EXPECT_TRUE(contains(csv, "# reference: sticks, period 7 (128 bits; covers 150 of 200 steps)\n"));
  const std::vector<std::string> lines = data_lines(csv);
  ASSERT_EQ(lines.size(), 1 + rep.rows.size());
  EXPECT_EQ(lines[0], "precision,bits,leaves_enclosure_at,answer");
  for (size_t i = 0; i < rep.rows.size(); ++i) {
    const std::vector<std::string> f = csv_fields(lines[i + 1]);
    ASSERT_EQ(f.size(), 4u) << lines[i + 1];
    EXPECT_EQ(f[0], rep.rows[i].precision);
    EXPECT_EQ(f[1], std::to_string(rep.rows[i].bits));
    EXPECT_EQ(f[2], rep.rows[i].leaves_at ? std::to_string(*rep.rows[i].leaves_at) : "");
    EXPECT_EQ(f[3], rep.rows[i].answer);
  }
}

TEST(SweepReport, TableMarksTheRowsThatStayAndTheReferenceReach) {
  const SweepReport rep = sweep_report();
  const std::vector<std::string> lines = data_lines(sweep_table(rep, sweep_question()));
  ASSERT_EQ(lines.size(), 2 + rep.rows.size() + 2);  // reference, header, rows, the '-' note, lambda
  EXPECT_EQ(lines[0].rfind("reference: sticks, period 7 (128 bits;", 0), 0u);
  EXPECT_TRUE(contains(lines[2], "40"));
  std::istringstream stays(lines[4]);
  std::string precision, bits, leaves;
  stays >> precision >> bits >> leaves;
  EXPECT_EQ(precision, "mpfr:256");
  EXPECT_EQ(bits, "256");
  EXPECT_EQ(leaves, "-");
  // The reference covers 150 of the 200 steps: the rows that stay, stay for 150.
  EXPECT_TRUE(contains(lines[5], "all 150 certified steps"));
  EXPECT_EQ(lines[6].rfind("implied_lyapunov: ", 0), 0u);
  SweepReport none = rep;
  none.slope.reset();
  none.implied_lyapunov.reset();
  EXPECT_EQ(data_lines(sweep_table(none, sweep_question())).back().rfind("implied_lyapunov: none", 0), 0u);
}

TEST(SweepReport, FigurePlotsWhereEachPrecisionLeaves) {
  const SweepReport rep = sweep_report();
  const Figure f = sweep_divergence_figure(rep, sweep_question(), sample_provenance("sweep"));
  ASSERT_EQ(f.series.size(), 3u);  // leaves, stays, the fit
  EXPECT_EQ(f.series[0].x, (std::vector<double>{53, 64}));
  EXPECT_EQ(f.series[0].y, (std::vector<double>{40, 52}));
  EXPECT_EQ(f.series[1].x, (std::vector<double>{256}));
  EXPECT_EQ(f.series[1].y, (std::vector<double>{150}));
  // The fit is the line through the two points: its ends are the points themselves.
  const Series& fit = f.series[2];
  EXPECT_NEAR(fit.x.front(), 53, 1e-9);
  EXPECT_NEAR(fit.y.front(), 40, 1e-9);
  EXPECT_NEAR(fit.x.back(), 64, 1e-9);
  EXPECT_NEAR(fit.y.back(), 52, 1e-9);
  EXPECT_TRUE(f.log_x);
}

// ---- continue ----------------------------------------------------------------------------

// A period-1 branch of two points in a, from 0.5 to 0.6: the low end a grazing at the
// wall's top knot (1/2), the high end the range's end.
Branch<double> branch() {
  Branch<double> b;
  b.period = 1;
  b.started = true;
  for (double a : {0.5, 0.6}) {
    BranchPoint<double> p;
    p.param = a;
    p.orbit.converged = true;
    p.orbit.period = 1;
    p.orbit.points = {State<double>{0.25, 2 * a}};
    p.orbit.multipliers.re[0] = 0.5;
    p.orbit.multipliers.re[1] = -0.25;
    p.orbit.multipliers.im[0] = p.orbit.multipliers.im[1] = 0;  // (plain doubles: not set by default)
    p.orbit.residual = 1e-15;
    p.events = {StepEvent{}};
    p.min_margin = {0.25, 0.125, 1.5, NAN};
    p.min_impact = {0, 0, 0, -1};
    p.stability = a < 0.55 ? "stable" : "unstable";
    b.points.push_back(p);
  }
  b.start = 1;
  b.low.reason = EndReason::border;
  b.low.margin = static_cast<int>(Margin::clearance);
  b.low.impact = 0;
  b.low.knot = 1;
  b.low.param = 0.4375;
  b.low.bracket_lo = 0.4374;
  b.low.bracket_hi = 0.4376;
  b.low.detail = "flight 1 grazes the knot theta = 1/2";
  b.low.beyond_done = true;
  b.low.beyond_param = 0.437;
  b.low.beyond.cls = OrbitClass::periodic;
  b.low.beyond.period = 3;
  // An error estimate (analysis/end_estimate.hpp): 0.4375 -+ 3.5e-4 backs 4 digits,
  // 0.4375 -+ 4e-4 (by hand: the 1e-4 place, ceil(3.5) = 4 units), outward [0.4371, 0.4379].
  b.low.estimate.kind = EndEstimate::Kind::estimate;
  b.low.estimate.center = mpq_class(7, 16);
  b.low.estimate.radius = 3.5e-4;
  b.low.estimate.error = 2e-5;
  b.low.estimate.refined = "0.43752";
  b.low.estimate.bits = 117;
  b.high.estimate.kind = EndEstimate::Kind::given;
  b.high.reason = EndReason::range_end;
  b.high.param = 0.6;
  b.high.bracket_lo = b.high.bracket_hi = 0.6;
  Bifurcation<double> pd{SmoothKind::period_doubling, 0.55, 0.549, 0.551};
  b.bifurcations = {pd};
  b.corrector_runs = 17;
  return b;
}

ContinueRequest continue_request_for_test() {
  ContinueRequest r;
  r.model = test_support::spec(Law::constant, "0.6", "0.8");
  r.vary = Parameter::a;
  r.lo = parse_decimal("range", "0.4");
  r.hi = parse_decimal("range", "0.6");
  r.period = 1;
  r.precision = Precision{};
  return r;
}

TEST(ContinueReport, WordsNameEachCause) {
  EXPECT_EQ(cause_words(EndReason::border, static_cast<int>(Margin::knot)), "a border collision");
  EXPECT_EQ(cause_words(EndReason::border, static_cast<int>(Margin::clearance)), "a grazing");
  EXPECT_EQ(cause_words(EndReason::border, static_cast<int>(Margin::speed)), "a touchdown");
  EXPECT_EQ(cause_words(EndReason::border, static_cast<int>(Margin::sticking)), "the sticking threshold");
  EXPECT_EQ(cause_words(EndReason::fold, -1), "a fold");
  EXPECT_EQ(cause_words(EndReason::range_end, -1), "");
  Classification c;
  c.cls = OrbitClass::periodic;
  c.period = 4;
  EXPECT_EQ(class_words(c), "a periodic orbit of period 4");
  c.cls = OrbitClass::undecided;
  c.evidence = "no recurrence";
  EXPECT_TRUE(contains(class_words(c), "no recurrence"));
}

TEST(ContinueReport, SentencesNameWhereAndWhyEachEndLies) {
  const Branch<double> b = branch();
  const std::string low = branch_end_sentence(b, b.low, Parameter::a);
  EXPECT_EQ(low.rfind("period 1 ends at a* = 0.4375 ± 4e-4 (estimate) by a grazing (flight 1 grazes the knot theta = 1/2)", 0), 0u)
      << low;
  BranchEnd<double> plain = b.low;
  plain.estimate = EndEstimate{};  // never estimated: the computed digits, said to be unchecked
  EXPECT_EQ(branch_end_sentence(b, plain, Parameter::a).rfind("period 1 ends at a* = 0.4375 (accuracy not estimated) by", 0), 0u);
  EXPECT_TRUE(contains(low, "beyond it the orbit goes to a periodic orbit of period 3")) << low;
  const std::string high = branch_end_sentence(b, b.high, Parameter::a);
  EXPECT_EQ(high, "period 1 reaches the range end a = 0.6");
  BranchEnd<double> cap = b.high;
  cap.reason = EndReason::max_points;
  EXPECT_TRUE(contains(branch_end_sentence(b, cap, Parameter::eps), "stops at eps = 0.6 (--max-points)"));
}

TEST(ContinueReport, CsvHasOneRowPerBranchPoint) {
  const Branch<double> b = branch();
  const std::vector<std::string> lines = data_lines(branch_csv(b, Parameter::a));
  ASSERT_EQ(lines.size(), 1 + b.points.size());
  const std::vector<std::string> head = csv_fields(lines[0]);
  // a, stability, 2 x (re, im, abs), events, 4 x (margin, impact), residual, 1 x (theta, v)
  ASSERT_EQ(head.size(), 2u + 6 + 1 + 8 + 1 + 2);
  EXPECT_EQ(head[0], "a");
  EXPECT_EQ(head[9], name(Margin::knot));
  EXPECT_EQ(head[10], std::string(name(Margin::knot)) + "_impact");
  EXPECT_EQ(head[11], name(Margin::clearance));
  EXPECT_EQ(head.back(), "v_0");
  for (size_t i = 0; i < b.points.size(); ++i) {
    const std::vector<std::string> f = csv_fields(lines[i + 1]);
    ASSERT_EQ(f.size(), head.size());
    EXPECT_EQ(std::stod(f[0]), b.points[i].param);
    EXPECT_EQ(f[1], b.points[i].stability);
    EXPECT_EQ(std::stod(f[2]), 0.5);    // mu1_re
    EXPECT_EQ(std::stod(f[4]), 0.5);    // |mu1|
    EXPECT_EQ(std::stod(f[7]), 0.25);   // |mu2|
    EXPECT_EQ(std::stod(f[9]), 0.25);   // the knot margin
    EXPECT_EQ(f[10], "1");              // at impact 1 (counted from 1)
    EXPECT_EQ(f[15], "nan");            // the sticking margin is not defined
    EXPECT_EQ(f[16], "");               // and has no impact
    EXPECT_EQ(std::stod(f.back()), 2 * b.points[i].param);
  }
}

TEST(ContinueReport, JsonHoldsTheBranchAndItsEnds) {
  const ContinueRequest r = continue_request_for_test();
  const Model<double> m = make_model<double>(r.model, 53);
  const Branch<double> b = branch();
  const json j = json::parse(branch_json(r, m, b, {}, sample_provenance("continue")));
  EXPECT_EQ(j.begin().key(), "provenance");
  const json& s = j["summary"];
  EXPECT_EQ(s["command"], "continue");
  EXPECT_EQ(s["vary"], "a");
  EXPECT_EQ(s["range"], (json{"0.4", "0.6"}));
  EXPECT_EQ(s["points"], 2);
  EXPECT_EQ(std::stod(s["start"]["param"].get<std::string>()), 0.6);  // b.start = 1
  EXPECT_EQ(s["start"]["multiplier_moduli"][1].get<double>(), 0.25);
  EXPECT_EQ(s["corrector_runs"], 17);
  EXPECT_EQ(s["low"]["reason"], "border");
  EXPECT_EQ(s["low"]["margin"], "clearance");
  EXPECT_EQ(s["low"]["impact"], 1);
  EXPECT_EQ(s["low"]["knot"], "1/2");  // the triangle's top
  EXPECT_EQ(std::stod(s["low"]["param"].get<std::string>()), 0.4375);
  EXPECT_EQ(s["low"]["beyond"]["class"], "periodic");
  EXPECT_EQ(s["low"]["sentence"], branch_end_sentence(b, b.low, Parameter::a));
  // The computed a* (round trip) and, beside it, what the error estimate backs.
  EXPECT_EQ(s["low"]["accuracy"], "estimate");
  EXPECT_EQ(s["low"]["a_star_backed"], "0.4375");
  EXPECT_EQ(s["low"]["a_star_plus_minus"], "4e-4");
  EXPECT_EQ(s["low"]["a_star_digits"], 4);
  EXPECT_EQ(s["low"]["bracket_estimate"], (json{"0.4371", "0.4379"}));
  EXPECT_EQ(s["low"]["bracket"], (json{"0.4374", "0.4376"}));
  EXPECT_EQ(s["low"]["error_estimate"].get<double>(), 2e-5);
  EXPECT_EQ(s["low"]["refined_param"], "0.43752");
  EXPECT_EQ(s["low"]["refined_bits"], 117);
  EXPECT_EQ(s["high"]["accuracy"], "given");
  EXPECT_FALSE(s["high"].contains("bracket_estimate"));
  EXPECT_FALSE(s["low"].contains("certified"));
  EXPECT_TRUE(s["high"]["beyond"].is_null());
  EXPECT_TRUE(s["high"]["margin"].is_null());
  ASSERT_EQ(s["bifurcations"].size(), 1u);
  EXPECT_EQ(s["bifurcations"][0]["kind"], name(SmoothKind::period_doubling));
  EXPECT_EQ(std::stod(s["bifurcations"][0]["param"].get<std::string>()), 0.55);
  EXPECT_EQ(s["bifurcations"][0]["accuracy"], "not_estimated");
}

TEST(ContinueReport, ACertifiedEndStatesItsOneSidedBound) {
  CertifiedBranchEnd c;
  c.high_end = false;
  c.lo = "0.4375";
  c.hi = "0.4376";
  c.certificate.certified = true;
  c.certificate.from = mpq_class(4375, 10000);
  c.certificate.to = mpq_class(4376, 10000);
  c.certificate.bound = c.certificate.from;
  c.certificate.pieces = 3;
  const std::string s = certified_end_statement(c, 1, Parameter::a);
  EXPECT_TRUE(contains(s, "for every a in [0.4375, 0.4376]")) << s;
  EXPECT_TRUE(contains(s, "a* <= 0.4375")) << s;  // a low end: the branch lies above
  CertifiedBranchEnds ends;
  ends.low = c;
  const ContinueRequest r = continue_request_for_test();
  const Model<double> m = make_model<double>(r.model, 53);
  const json j = json::parse(branch_json(r, m, branch(), ends, sample_provenance("continue")));
  EXPECT_EQ(j["summary"]["low"]["certified"]["certified_to"], "0.4375");
  EXPECT_EQ(j["summary"]["low"]["certified"]["pieces"], 3);
  EXPECT_EQ(j["summary"]["low"]["certified"]["statement"], s);
  // No two-sided enclosure here: nothing to check the error estimate against.
  EXPECT_TRUE(j["summary"]["low"]["certified"]["two_sided"]["estimate_contains"].is_null());
  EXPECT_TRUE(contains(branch_text(r, branch(), ends, sample_provenance("continue")), "low end " + s + "\n"));
  c.certificate.certified = false;
  EXPECT_EQ(certified_end_statement(c, 1, Parameter::a), "nothing certified next to a*");
}

TEST(ContinueReport, TextSummaryHasBothEndsAndTheBifurcations) {
  const ContinueRequest r = continue_request_for_test();
  const Branch<double> b = branch();
  const std::vector<std::string> lines = data_lines(branch_text(r, b, {}, sample_provenance("continue")));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_TRUE(contains(lines[0], "2 points"));
  EXPECT_EQ(lines[1], "low end:  " + branch_end_sentence(b, b.low, Parameter::a));
  EXPECT_EQ(lines[2], "high end: " + branch_end_sentence(b, b.high, Parameter::a));
  EXPECT_EQ(lines[3], std::string(name(SmoothKind::period_doubling)) + " at a* = 0.55 (accuracy not estimated)");
}

TEST(ContinueReport, FigureSeparatesStableFromUnstablePoints) {
  const ContinueRequest r = continue_request_for_test();
  const Model<double> m = make_model<double>(r.model, 53);
  const Figure f = branch_figure(r, m, branch(), false, sample_provenance("continue"));
  ASSERT_GE(f.series.size(), 2u);
  EXPECT_EQ(f.series[0].label, "stable");
  EXPECT_EQ(f.series[0].x, (std::vector<double>{0.5}));
  EXPECT_EQ(f.series[0].y, (std::vector<double>{1.0}));
  EXPECT_EQ(f.series[1].label, "unstable");
  EXPECT_DOUBLE_EQ(f.x_min, 0.4);  // the range, from its exact decimals
  EXPECT_DOUBLE_EQ(f.x_max, 0.6);
  // The grazing's line and the period doubling's: two more series.
  ASSERT_EQ(f.series.size(), 4u);
  EXPECT_TRUE(contains(f.series[2].label, "grazing")) << f.series[2].label;
  EXPECT_EQ(f.series[2].x, (std::vector<double>{0.4375, 0.4375}));
  // The label prints 8 digits at most, and no more than the error estimate backs:
  // 0.437512345 -+ 3.5e-4 backs 0.4375 (by hand: the 1e-4 place).
  Branch<double> b = branch();
  b.low.param = 0.437512345;
  b.low.estimate.center = mpq_class(b.low.param);
  const Figure g = branch_figure(r, m, b, false, sample_provenance("continue"));
  ASSERT_EQ(g.series.size(), 4u);
  EXPECT_EQ(g.series[2].label.rfind("a* = 0.4375: grazing", 0), 0u) << g.series[2].label;
  b.low.estimate = EndEstimate{};  // not estimated: short_num's 8 digits
  const std::string plain = branch_figure(r, m, b, false, sample_provenance("continue")).series[2].label;
  EXPECT_EQ(plain.rfind("a* = 0.4375123", 0), 0u) << plain;
}

// A branch that fills less than 1/20 of the range, both ends inside it, is drawn in a window
// around it: its hull (by hand: the low end 0.4375 and the points 0.5, 0.6, with the high end
// at 0.6 a fold: [0.4375, 0.6], spread 0.1625) and a tenth of the spread beyond each
// side, [0.42125, 0.61625], inside the range [0, 10]. The range 0.4:0.6 itself (the branch
// fills 81% of it) keeps its axis, as does a branch one of whose ends is the range's end.
TEST(ContinueReport, FigureZoomsOnABranchMuchNarrowerThanTheRange) {
  ContinueRequest r = continue_request_for_test();
  r.lo = parse_decimal("range", "0");
  r.hi = parse_decimal("range", "10");
  const Model<double> m = make_model<double>(r.model, 53);
  Branch<double> b = branch();
  b.high.reason = EndReason::fold;  // inside the range (the fixture's ends at its end)
  const Figure f = branch_figure(r, m, b, false, sample_provenance("continue"));
  EXPECT_DOUBLE_EQ(f.x_min, 0.42125);
  EXPECT_DOUBLE_EQ(f.x_max, 0.61625);
  EXPECT_TRUE(contains(f.subtitle, "the branch's part of the range 0:10")) << f.subtitle;
  // One more point at 2.5: the spread is 0.2 of the range, the whole range is drawn.
  b.points.push_back(b.points.back());
  b.points.back().param = 2.5;
  const Figure wide = branch_figure(r, m, b, false, sample_provenance("continue"));
  EXPECT_DOUBLE_EQ(wide.x_min, 0);
  EXPECT_DOUBLE_EQ(wide.x_max, 10);
  EXPECT_FALSE(contains(wide.subtitle, "part of the range")) << wide.subtitle;
  // A branch that runs into the range's end is drawn over the whole range.
  b.points.pop_back();
  b.high.reason = EndReason::range_end;
  const Figure open = branch_figure(r, m, b, false, sample_provenance("continue"));
  EXPECT_DOUBLE_EQ(open.x_max, 10);
}

// ---- certify-periodic and certify-sticking ----------------------------------------------

CertifyPeriodicRequest periodic_request() {
  CertifyPeriodicRequest r;
  r.question.model = test_support::spec(Law::constant, "0.5", "0.7");
  r.question.period = 2;
  return r;
}

PeriodicCertificate periodic_certificate() {
  PeriodicCertificate c;
  c.outcome = PeriodicOutcome::isolated;
  c.certified = true;
  c.period = 2;
  c.minimal_period = 2;
  c.minimal_period_certified = true;
  c.bits = 128;
  c.points = {{{"0.1", "0.2", 0.15, 0.1}, {"1.5", "1.75", 1.6, 0.25}}, {{"0.6", "0.7", 0.65, 0.1}, {"2", "2.5", 2.2, 0.5}}};
  c.events = {"impact(seg 0)", "impact(seg 1)"};
  c.wall_periods = {1, 0};
  c.multipliers.kind = "real";
  c.stability = "stable";
  c.statement = "a period-2 orbit exists";
  Attempt a;
  a.bits = 128;
  a.decided = true;
  a.seconds = 0.5;
  c.attempts = {a};
  c.seconds = 0.75;
  return c;
}

TEST(CertifyPeriodicReport, JsonHoldsTheEnclosures) {
  std::ostringstream out;
  write_certify_periodic(out, true, sample_provenance("certify-periodic"), periodic_request(), periodic_certificate());
  const json j = json::parse(out.str());
  EXPECT_EQ(j.begin().key(), "provenance");
  EXPECT_EQ(j["inputs"]["a"], "0.5");
  EXPECT_EQ(j["inputs"]["eps"], "0.7");
  EXPECT_FALSE(j["inputs"].contains("c"));  // not a parameter of the constant law
  EXPECT_EQ(j["inputs"]["period"], 2);
  EXPECT_TRUE(j["certified"].get<bool>());
  EXPECT_EQ(j["outcome"], name(PeriodicOutcome::isolated));
  EXPECT_EQ(j["minimal_period"], 2);
  ASSERT_EQ(j["points"].size(), 2u);
  EXPECT_EQ(j["points"][1]["v"], (json{"2", "2.5"}));
  EXPECT_EQ(j["wall_periods"], (json{1, 0}));
  EXPECT_TRUE(j.contains("krawczyk"));
  EXPECT_EQ(j["seconds"].get<double>(), 0.75);
}

TEST(CertifyPeriodicReport, KeyValuesFlattenTheFieldsAndSetTimesApart) {
  std::ostringstream out;
  write_certify_periodic(out, false, sample_provenance("certify-periodic"), periodic_request(), periodic_certificate());
  const std::string text = out.str();
  EXPECT_EQ(text.rfind(sample_provenance("certify-periodic").as_comment_lines(), 0), 0u);
  EXPECT_TRUE(contains(text, "\ninputs.a: 0.5\n"));
  EXPECT_TRUE(contains(text, "\ncertified: true\n"));
  EXPECT_TRUE(contains(text, "\npoints[1].v: [\"2\",\"2.5\"]\n"));
  EXPECT_TRUE(contains(text, "\n# time: seconds = 0.75\n"));
  EXPECT_TRUE(contains(text, "\n# time: attempts[0].seconds = 0.5\n"));
  EXPECT_FALSE(contains(text, "\nseconds:"));
}

TEST(CertifyPeriodicReport, ARangeListsItsPiecesAndTheMostBits) {
  PeriodicRangeReport rep;
  PeriodicCertificate low = periodic_certificate(), high = periodic_certificate();
  high.bits = 256;
  rep.pieces = {{mpq_class(1, 2), mpq_class(3, 4), low}, {mpq_class(3, 4), mpq_class(1), high}};
  rep.uncertified_length = 0;
  rep.theorem = "For every a in [1/2, 1] ...";
  EXPECT_EQ(bits_used(rep), 256);
  std::ostringstream out;
  write_certify_periodic(out, true, sample_provenance("certify-periodic"), periodic_request(), rep);
  const json j = json::parse(out.str());
  EXPECT_TRUE(j["certified"].get<bool>());
  EXPECT_EQ(j["uncertified_length"], "0");
  ASSERT_EQ(j["pieces"].size(), 2u);
  EXPECT_EQ(j["pieces"][0]["lo"], "0.5");
  EXPECT_EQ(j["pieces"][1]["lo"], "0.75");
  EXPECT_EQ(j["pieces"][1]["bits"], 256);
  EXPECT_FALSE(j["pieces"][0].contains("attempts"));
  EXPECT_EQ(j["theorem"], "Theorem (computer-assisted). For every a in [1/2, 1] ...");
}

TEST(CertifyPeriodicReport, ALadderStatesItsExactGain) {
  CertifyPeriodicRequest r = periodic_request();
  r.lift = parse_decimal("lift", "2");
  LadderCertificate c;
  c.certified = true;
  c.D = mpq_class(2);
  c.m0 = mpq_class(3);
  c.J = mpq_class(1, 4);
  c.min_gap = mpq_class(1, 8);
  c.statement = "an accelerator mode";
  std::ostringstream out;
  write_certify_periodic(out, true, sample_provenance("certify-periodic"), r, c);
  const json j = json::parse(out.str());
  EXPECT_EQ(j["inputs"]["lift"], "2");
  EXPECT_EQ(j["outcome"], "accelerator_mode");
  EXPECT_EQ(j["periods_added_per_impact"], "0.25");
  EXPECT_EQ(j["first_flight_least_gap"], "0.125");
}

StickingCertificate sticks_at(long long period) {
  StickingCertificate c;
  c.outcome = StickingOutcome::sticks;
  c.certified = true;
  c.period = period;
  c.bits = 64;
  c.scalar = "interval:64";
  c.steps_checked = period - 1;
  c.seconds = 0.5;
  return c;
}

TEST(CertifyStickingReport, ADoubleRunAgreesOnlyWithTheSamePeriod) {
  StickingQuestion q;
  q.model = test_support::spec(Law::constant, "0.5", "0.7");
  PlainSticking same, other;
  same.period = 7;
  other.period = 8;
  EXPECT_TRUE(plain_agrees(sticks_at(7), same));
  EXPECT_FALSE(plain_agrees(sticks_at(7), other));
  std::ostringstream out;
  write_certify_sticking(out, true, sample_provenance("certify-sticking"), q, sticks_at(7), other);
  const json j = json::parse(out.str());
  EXPECT_EQ(j["inputs"]["a"], "0.5");
  EXPECT_EQ(j["inputs"]["theta"], "0.5");  // the release state
  EXPECT_EQ(j["period"], 7);
  EXPECT_EQ(j["double_period"], 8);
  EXPECT_FALSE(j["agrees"].get<bool>());
  EXPECT_TRUE(j["attractor"].is_null());
  EXPECT_EQ(j["statement"], describe(sticks_at(7), q.max_steps));
}

TEST(CertifyStickingReport, ARangeComparesEachPieceAtItsMidpoint) {
  StickingQuestion q;
  q.model = test_support::spec(Law::constant, "0.5", "0.7");
  q.a_range = std::make_pair(mpq_class(1, 2), mpq_class(1));
  RangeReport rep;
  rep.lo = mpq_class(1, 2);
  rep.hi = mpq_class(1);
  StickingCertificate high = sticks_at(5);
  high.bits = 128;
  rep.pieces = {{mpq_class(1, 2), mpq_class(3, 4), sticks_at(7)}, {mpq_class(3, 4), mpq_class(1), high}};
  rep.uncertified_length = 0;
  rep.theorem = "For every a in [0.5, 1] ...";
  PlainSticking seven, five;
  seven.period = 7;
  five.period = 5;
  EXPECT_EQ(bits_used(rep), 128);
  std::ostringstream out;
  write_certify_sticking(out, true, sample_provenance("certify-sticking"), q, rep, {seven, five});
  json j = json::parse(out.str());
  EXPECT_EQ(j["inputs"]["a_range"], (json{"0.5", "1"}));
  EXPECT_FALSE(j["inputs"].contains("a"));
  EXPECT_TRUE(j["agrees"].get<bool>());
  ASSERT_EQ(j["pieces"].size(), 2u);
  EXPECT_EQ(j["pieces"][0]["a_lo"], "0.5");
  EXPECT_EQ(j["pieces"][0]["double_period_at"], "0.625");  // (1/2 + 3/4) / 2
  EXPECT_EQ(j["pieces"][1]["double_period_at"], "0.875");
  EXPECT_FALSE(j["pieces"][0].contains("attempts"));
  std::ostringstream differs;
  write_certify_sticking(differs, true, sample_provenance("certify-sticking"), q, rep, {seven, seven});
  j = json::parse(differs.str());
  EXPECT_FALSE(j["agrees"].get<bool>());
  EXPECT_FALSE(j["pieces"][1]["agrees"].get<bool>());
}

// ---- a certified map's CSV (basin --certify, scan --certify; io/grid_figures.hpp) ----------

TEST(CertifiedMapCsv, OneRowPerCellAtItsCoordinates) {
  CertifiedMap m;
  m.x_name = "theta";
  m.y_name = "v";
  m.nx = 2;
  m.ny = 2;
  const std::vector<Number> xs{{0.25, "0.25"}, {0.75, "0.75"}}, ys{{1, "1"}, {2, "2"}};
  std::vector<CertifiedCell> cells(4, CertifiedCell::outside());
  cells[3] = {CertifiedClass::sticking, 7, 6, "interval:double", OrbitClass::sticking, 7, Agreement::agrees};
  const std::vector<std::string> lines = data_lines(certified_map_csv(m, xs, ys, cells));
  ASSERT_EQ(lines.size(), 1 + cells.size());
  EXPECT_EQ(lines[0], "theta,v,class,period,certified_steps,scalar,double_class,double_period,agreement");
  for (size_t i = 0; i < cells.size(); ++i) {
    const std::vector<std::string> f = csv_fields(lines[i + 1]);
    ASSERT_EQ(f.size(), 9u) << lines[i + 1];
    EXPECT_EQ(f[0], xs[i % 2].digits);  // columns first, the bottom row first
    EXPECT_EQ(f[1], ys[i / 2].digits);
    EXPECT_EQ(f[2], name(cells[i].cls));
    EXPECT_EQ(f[8], name(cells[i].agreement));
  }
  const std::vector<std::string> last = csv_fields(lines[4]);
  EXPECT_EQ(last[3], "7");
  EXPECT_EQ(last[4], "6");
  EXPECT_EQ(last[5], "interval:double");
  EXPECT_EQ(last[7], "7");
}

}  // namespace
}  // namespace bouncer
