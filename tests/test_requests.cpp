// The request readers of the commands that the CLI and the Python module share
// (lib/include/bouncer/io/requests/): continue, certify-sticking, certify-periodic. For
// each, a default (what the documentation, docs/guide/, and --help promise), a bound (the value just inside is
// read, the value just outside is refused) and errors that name the field the user must fix.
// Truth: the documented defaults (docs/guide/) and ranges, not the program's output.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "bouncer/io/requests/certify_periodic.hpp"
#include "bouncer/io/requests/certify_sticking.hpp"
#include "bouncer/io/requests/continue.hpp"

namespace bouncer {
namespace {

Options opts(const std::vector<std::pair<std::string, std::string>>& kv) {
  Options o;
  for (const auto& [k, v] : kv) {
    if (k == "guess") {
      const auto comma = v.find(',');
      o.set(k, std::vector<std::string>{v.substr(0, comma), v.substr(comma + 1)});
    } else {
      o.set(k, v);
    }
  }
  return o;
}

// Runs f, expects an InputError naming `field`; returns its message.
std::string refused(const std::string& field, const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, field) << e.what();
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError(" << field << "), got " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected InputError(" << field << "), nothing was thrown";
  return "";
}

// The period-2 branch (docs/guide/dynamics.md) of the constant model, eps = 0.9.
Options continue_opts() {
  return opts({{"model", "constant"}, {"eps", "0.9"}, {"a", "19"}, {"period", "2"},
               {"guess", "0.1678819228862684,14.143149884133248"}, {"range", "12:23"}});
}

TEST(ContinueRequest, Defaults) {
  const ContinueRequest r = continue_request(continue_opts());
  EXPECT_EQ(r.vary, Parameter::a);
  EXPECT_EQ(r.lo.text(), "12");
  EXPECT_EQ(r.hi.text(), "23");
  EXPECT_EQ(r.model.a.text(), "19");
  EXPECT_EQ(r.model.eps.text(), "0.9");
  EXPECT_EQ(r.period, 2);
  EXPECT_EQ(r.guess.v.text(), "14.143149884133248");
  EXPECT_EQ(r.precision.text(), "double");
  EXPECT_EQ(r.opt.step, 0);  // (HI - LO)/100, chosen by continue_branch
  EXPECT_EQ(r.opt.max_points, 2000);
  EXPECT_EQ(r.opt.newton.max_iter, 30);
  EXPECT_EQ(r.opt.beyond, 1e-6);
  EXPECT_EQ(r.opt.classify.transient, 5000);
  EXPECT_EQ(r.opt.classify.steps, 500);
  EXPECT_FALSE(r.certify);
}

TEST(ContinueRequest, TheVariedParameterStartsAtTheRangesLowEnd) {
  Options o = continue_opts();
  o.values.erase("a");
  EXPECT_EQ(continue_request(o).model.a.text(), "12");
  o.set("vary", "eps");
  o.set("a", "19");
  o.values.erase("eps");
  o.set("range", "0.85:0.95");
  const ContinueRequest r = continue_request(o);
  EXPECT_EQ(r.vary, Parameter::eps);
  EXPECT_EQ(r.model.eps.text(), "0.85");
}

TEST(ContinueRequest, Bounds) {
  Options o = continue_opts();
  o.set("period", "2000");  // kMaxBranchPeriod
  EXPECT_EQ(continue_request(o).period, 2000);
  o.set("period", "2001");
  refused("period", [&] { continue_request(o); });
  o = continue_opts();
  o.set("max-points", "2");
  EXPECT_EQ(continue_request(o).opt.max_points, 2);
  o.set("max-points", "1");
  refused("max-points", [&] { continue_request(o); });
  o = continue_opts();
  o.set("step", "11");  // HI - LO
  EXPECT_DOUBLE_EQ(continue_request(o).opt.step, 11);
  o.set("step", "11.000001");
  refused("step", [&] { continue_request(o); });
  o = continue_opts();
  o.set("beyond", "0.1");
  EXPECT_DOUBLE_EQ(continue_request(o).opt.beyond, 0.1);
  o.set("beyond", "0.10001");
  refused("beyond", [&] { continue_request(o); });
}

TEST(ContinueRequest, ErrorsNameTheField) {
  Options o = continue_opts();
  o.values.erase("range");
  EXPECT_NE(refused("range", [&] { continue_request(o); }).find("is required"), std::string::npos);
  o = continue_opts();
  o.values.erase("guess");
  refused("guess", [&] { continue_request(o); });
  o = continue_opts();
  o.set("vary", "c");  // c belongs to the veldep law only
  refused("vary", [&] { continue_request(o); });
  o = continue_opts();
  o.set("a", "24");  // outside 12:23
  EXPECT_NE(refused("a", [&] { continue_request(o); }).find("must lie in the range"), std::string::npos);
  o = continue_opts();
  o.set("precision", "interval:128");
  refused("precision", [&] { continue_request(o); });
  o = continue_opts();
  o.set("certify", "maybe");
  refused("certify", [&] { continue_request(o); });
}

Options sticking_opts() { return opts({{"eps", "0.96"}, {"a", "28.82"}}); }

TEST(CertifyStickingRequest, Defaults) {
  // docs/guide/certified.md: --model constant, the release state (1/2, 4), 100000 steps, interval:double
  // first then MPFI up to 4096 bits, Lohner, attractor proof on; ranges depth 10, 400 pieces.
  const CertifyStickingRequest r = certify_sticking_request(sticking_opts());
  const StickingQuestion& q = r.question;
  EXPECT_EQ(q.model.law, Law::constant);
  EXPECT_EQ(q.start.theta.value(), mpq_class(1, 2));
  EXPECT_EQ(q.start.v.value(), mpq_class(4));
  EXPECT_FALSE(q.a_range);
  EXPECT_EQ(q.max_steps, 100000);
  EXPECT_TRUE(q.schedule.double_first);
  EXPECT_EQ(q.schedule.max_bits, 4096);
  EXPECT_EQ(q.method, EnclosureMethod::lohner);
  EXPECT_TRUE(q.prove_attractor);
  EXPECT_EQ(r.range.max_depth, 10);
  EXPECT_EQ(r.range.max_pieces, 400);
  Options o = sticking_opts();
  certify_sticking_defaults(o);
  EXPECT_EQ(o.get("model"), "constant");
  EXPECT_EQ(o.get("theta"), "0.5");
  EXPECT_EQ(o.get("v"), "4");
}

TEST(CertifyStickingRequest, ARange) {
  Options o = sticking_opts();
  o.values.erase("a");
  o.set("a-range", "28.8:28.9");
  o.set("max-depth", "40");
  const CertifyStickingRequest r = certify_sticking_request(o);
  ASSERT_TRUE(r.question.a_range);
  EXPECT_EQ(r.question.a_range->first, mpq_class(144, 5));
  EXPECT_EQ(r.question.a_range->second, mpq_class(289, 10));
  EXPECT_EQ(r.range.max_depth, 40);
  o.set("max-depth", "41");
  refused("max-depth", [&] { certify_sticking_request(o); });
  o.set("max-depth", "3");
  o.set("a", "28.82");
  refused("a-range", [&] { certify_sticking_request(o); });
  o.values.erase("a");
  o.set("a-range", "28.9:28.8");
  refused("a-range", [&] { certify_sticking_request(o); });
}

TEST(CertifyStickingRequest, ErrorsNameTheField) {
  Options o = sticking_opts();
  o.set("max-depth", "3");  // without --a-range
  refused("max-depth", [&] { certify_sticking_request(o); });
  o = sticking_opts();
  o.set("max-steps", "1000000000");
  EXPECT_EQ(certify_sticking_request(o).question.max_steps, 1000000000);
  o.set("max-steps", "1000000001");
  refused("max-steps", [&] { certify_sticking_request(o); });
  o = sticking_opts();
  o.set("start-bits", "128");
  o.set("max-bits", "64");
  refused("start-bits", [&] { certify_sticking_request(o); });
  o = opts({{"model", "veldep"}, {"c", "1000"}, {"a", "28"}});
  EXPECT_NE(refused("model", [&] { certify_sticking_request(o); }).find("--model constant"), std::string::npos);
  o = opts({{"eps", "0.96"}});
  refused("a", [&] { certify_sticking_request(o); });
  o = sticking_opts();
  o.set("prove-attractor", "yes");
  refused("prove-attractor", [&] { certify_sticking_request(o); });
}

Options periodic_opts() { return opts({{"model", "constant"}, {"eps", "0.5"}, {"a", "24"}, {"period", "1"}}); }

TEST(CertifyPeriodicRequest, Defaults) {
  // docs/guide/certified.md (certify-periodic): Newton from a grid (8 per axis, 60 iterations), 64 to 1024 bits, family auto;
  // ranges depth 8, 256 pieces.
  const CertifyPeriodicRequest r = certify_periodic_request(periodic_opts());
  const PeriodicQuestion& q = r.question;
  EXPECT_EQ(q.period, 1);
  EXPECT_FALSE(q.guess);
  EXPECT_EQ(q.vary, Parameter::a);
  EXPECT_FALSE(q.range);
  EXPECT_EQ(q.family, FamilyMode::automatic);
  EXPECT_EQ(q.schedule.start_bits, 64);
  EXPECT_EQ(q.schedule.max_bits, 1024);
  EXPECT_EQ(q.max_depth, 8);
  EXPECT_EQ(q.max_pieces, 256);
  EXPECT_EQ(q.newton.max_iter, 60);
  EXPECT_EQ(q.newton.grid, 8);
  EXPECT_FALSE(r.lift);
}

TEST(CertifyPeriodicRequest, ARangeNamesTheVariedParameter) {
  Options o = periodic_opts();
  o.values.erase("eps");
  o.set("eps-range", "0.4:0.6");
  const CertifyPeriodicRequest r = certify_periodic_request(o);
  EXPECT_EQ(r.question.vary, Parameter::eps);
  ASSERT_TRUE(r.question.range);
  EXPECT_EQ(r.question.range->first, mpq_class(2, 5));
  EXPECT_EQ(r.question.model.eps.text(), "0.4");  // the model at the range's start
  o.set("a-range", "20:30");
  refused("eps-range", [&] { certify_periodic_request(o); });  // at most one range
}

TEST(CertifyPeriodicRequest, Bounds) {
  Options o = periodic_opts();
  o.set("period", "2000");  // kMaxCertifiedPeriod: shooting's dense preconditioner, (2Q)^2 doubles
  EXPECT_EQ(certify_periodic_request(o).question.period, 2000);
  o.set("period", "2001");
  refused("period", [&] { certify_periodic_request(o); });
  o = periodic_opts();
  o.set("grid", "64");
  EXPECT_EQ(certify_periodic_request(o).question.newton.grid, 64);
  o.set("grid", "65");
  refused("grid", [&] { certify_periodic_request(o); });
}

TEST(CertifyPeriodicRequest, ErrorsNameTheField) {
  Options o = periodic_opts();
  o.values.erase("period");
  EXPECT_NE(refused("period", [&] { certify_periodic_request(o); }).find("is required"), std::string::npos);
  o = periodic_opts();
  o.set("vary", "c");
  refused("vary", [&] { certify_periodic_request(o); });
  o = periodic_opts();
  o.set("lift", "1");  // accelerator ladders are elastic
  refused("lift", [&] { certify_periodic_request(o); });
  o = periodic_opts();
  o.set("max-pieces", "3");  // without a range
  refused("max-pieces", [&] { certify_periodic_request(o); });
  o = periodic_opts();
  o.set("guess", std::vector<std::string>{"0.25"});
  refused("guess", [&] { certify_periodic_request(o); });
  o = periodic_opts();
  o.values.erase("a");
  o.set("a-range", "20:30");
  o.set("family", "on");
  refused("family", [&] { certify_periodic_request(o); });
}

}  // namespace
}  // namespace bouncer
