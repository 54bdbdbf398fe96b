// bouncer audit as library calls (workflow/audit.hpp, workflow/compare_results.hpp): the
// comparison of two results, the provenance read from both forms, the trust boundary
// (plan_rerun's refusals and where its rerun may write), and audit() itself: refusals before
// anything runs, reruns that fail, and real reruns of a small orbit with the built bouncer
// (BOUNCER_CLI), identical and edited. The expected values follow from the rules the headers
// state (which fields are volatile, how numbers compare, how the rerun is built), applied by
// hand to hand-written texts.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bouncer/base/error.hpp"
#include "bouncer/workflow/audit.hpp"
#include "bouncer/workflow/compare_results.hpp"
#include "test_support.hpp"

namespace {

using namespace bouncer;
using bouncer::test_support::contains;
using bouncer::test_support::expect_input_error;
using bouncer::test_support::put;
using bouncer::test_support::slurp;
using bouncer::test_support::TempDir;

// ---------------------------------------------------------------------------------------
// The comparison

TEST(AuditCompare, AnEditOfThe17thOf20DigitsIsADifference) {
  const std::string a = "9.8765432109876543210", b = "9.8765432109876544210";  // 17th digit: 3 -> 4
  // Both texts round to the same double: compared as parsed numbers they would be equal.
  ASSERT_EQ(std::strtod(a.c_str(), nullptr), std::strtod(b.c_str(), nullptr));
  const Comparison c = compare_json_results("{\"rows\": [{\"x\": " + a + "}]}", "{\"rows\": [{\"x\": " + b + "}]}");
  EXPECT_FALSE(c.identical);
  EXPECT_EQ(c.path, "rows[0].x");
  EXPECT_EQ(c.detail, a + " vs " + b);
  // The same digits written the same way are the same.
  EXPECT_TRUE(compare_json_results("{\"x\": " + a + "}", "{\"x\": " + a + "}").identical);
  // Numbers are their text: 1.0 is not 1, and a number is not the string of its digits.
  EXPECT_EQ(compare_json_results("{\"x\": 1.0}", "{\"x\": 1}").path, "x");
  EXPECT_EQ(compare_json_results("{\"x\": 1}", "{\"x\": \"1\"}").path, "x");
}

TEST(AuditCompare, TimingsInvocationAndOutputPathsAreVolatile) {
  const std::string file =
      R"({"provenance": {"command": "sweep", "version": "0.1.0", "invocation": "/home/a/bouncer sweep --out /home/a/s",
          "inputs": {"a": "24", "out": "/home/a/s"}},
          "files": {"json": "/home/a/s.json"}, "seconds": 1.5, "rows": [{"seconds": 0.25, "v": 3}]})";
  const std::string rerun =
      R"({"provenance": {"command": "sweep", "version": "0.1.0", "invocation": "/tmp/x/bouncer sweep --out /tmp/r",
          "inputs": {"a": "24", "out": "/tmp/r"}},
          "files": {"json": "/tmp/r.json", "csv": "/tmp/r.csv"}, "seconds": 99, "rows": [{"seconds": 7, "v": 3}]})";
  const Comparison c = compare_json_results(file, rerun);
  EXPECT_TRUE(c.identical) << c.path << ": " << c.detail;
  EXPECT_TRUE(c.path.empty());
  // What is not volatile is compared: another input, another build, "files" below the top.
  std::string other = rerun;
  other.replace(other.find("\"a\": \"24\""), 9, "\"a\": \"25\"");
  EXPECT_EQ(compare_json_results(file, other).path, "provenance.inputs.a");
  other = rerun;
  other.replace(other.find("0.1.0"), 5, "0.0.9");
  EXPECT_EQ(compare_json_results(file, other).path, "provenance.version");
  EXPECT_EQ(compare_json_results(R"({"rows": [{"files": 1}]})", R"({"rows": [{"files": 2}]})").path, "rows[0].files");
}

TEST(AuditCompare, JsonObjectsCompareByKeyNotByOrder) {
  EXPECT_TRUE(compare_json_results(R"({"a": 1, "b": [2, 3]})", R"({"b": [2, 3], "a": 1})").identical);
  Comparison c = compare_json_results(R"({"a": 1, "b": 2})", R"({"a": 1})");
  EXPECT_EQ(c.path, "b");
  EXPECT_EQ(c.detail, "present in the file, missing in the rerun");
  c = compare_json_results(R"({"a": 1})", R"({"c": 0, "a": 1})");
  EXPECT_EQ(c.path, "c");
  EXPECT_EQ(c.detail, "missing in the file, present in the rerun");
  c = compare_json_results(R"({"rows": [1, 2]})", R"({"rows": [1, 2, 3]})");
  EXPECT_EQ(c.path, "rows");
  EXPECT_EQ(c.detail, "2 vs 3 elements");
  c = compare_json_results(R"({"a": 1})", "not json");
  EXPECT_FALSE(c.identical);
  EXPECT_EQ(c.detail, "the rerun's output is not JSON");
}

TEST(AuditCompare, TextSkipsTimeAndInvocationLinesAndTheOutputLocation) {
  const std::string file =
      "# bouncer 0.1.0 (commit abc) sweep\n"
      "# invocation: /home/a/bouncer sweep --out /home/a/s\n"
      "# inputs: a=24 out=/home/a/s label=\"two words\"\n"
      "# time: 1.5 s\n"
      "n,x\n"
      "0,0.25\n"
      "1,0.5\n";
  std::string rerun =
      "# bouncer 0.1.0 (commit abc) sweep\n"
      "# invocation: /tmp/b/bouncer sweep --out /tmp/r\n"
      "# inputs: a=24 out=/tmp/r label=\"two words\"\n"
      "# time: 20.25 s\n"
      "n,x\n"
      "0,0.25\n"
      "1,0.5\n";
  EXPECT_TRUE(compare_text_results(file, rerun).identical);
  // Without the time line at all: still the same lines.
  std::string no_time = rerun;
  no_time.erase(no_time.find("# time:"), std::string("# time: 20.25 s\n").size());
  EXPECT_TRUE(compare_text_results(file, no_time).identical);
  // The kept lines are: the first line, the inputs, the header, row 0, row 1 (line 5).
  rerun.replace(rerun.find("1,0.5"), 5, "1,0.6");
  Comparison c = compare_text_results(file, rerun);
  EXPECT_FALSE(c.identical);
  EXPECT_EQ(c.path, "line 5");
  EXPECT_EQ(c.file_line, "1,0.5");
  EXPECT_EQ(c.rerun_line, "1,0.6");
  // A missing last row; another input; another commit.
  c = compare_text_results(file, file.substr(0, file.size() - std::string("1,0.5\n").size()));
  EXPECT_EQ(c.path, "line 5");
  EXPECT_EQ(c.rerun_line, "<end of output>");
  std::string other = file;
  other.replace(other.find("a=24"), 4, "a=25");
  EXPECT_EQ(compare_text_results(file, other).path, "line 2");
  other = file;
  other.replace(other.find("abc"), 3, "abd");
  EXPECT_EQ(compare_text_results(file, other).path, "line 1");
}

// ---------------------------------------------------------------------------------------
// Provenance and the trust boundary (plan_rerun), on hand-written results

std::string json_result(const std::string& command, const std::string& inputs, const std::string& rest = "") {
  return "{\"provenance\": {\"command\": \"" + command + "\", \"inputs\": {" + inputs + "}, \"invocation\": \"x\"}" + rest +
         "}\n";
}
std::string text_result(const std::string& command, const std::string& inputs) {
  return "# bouncer 0.1.0 (commit abc) " + command + "\n# invocation: bouncer\n# inputs: " + inputs + "\nn,x\n0,1\n";
}

TEST(AuditProvenance, ReadFromBothForms) {
  auto j = read_provenance(json_result("orbit", R"("a": "24", "eps": "0.8")"));
  ASSERT_TRUE(j);
  EXPECT_TRUE(j->is_json);
  EXPECT_EQ(j->command, "orbit");
  EXPECT_EQ(j->inputs, (std::vector<std::pair<std::string, std::string>>{{"a", "24"}, {"eps", "0.8"}}));
  auto t = read_provenance(text_result("sweep", R"(a=24 label="two \"quoted\" words" v=4)"));
  ASSERT_TRUE(t);
  EXPECT_FALSE(t->is_json);
  EXPECT_EQ(t->command, "sweep");
  EXPECT_EQ(t->inputs,
            (std::vector<std::pair<std::string, std::string>>{{"a", "24"}, {"label", "two \"quoted\" words"}, {"v", "4"}}));
  EXPECT_FALSE(read_provenance(json_result("orbit", R"("a": 24)")));  // inputs are strings
  EXPECT_FALSE(read_provenance("n,x\n0,1\n"));
  EXPECT_FALSE(read_provenance(text_result("orbit", "a=\"unclosed")));
  EXPECT_FALSE(read_provenance("# bouncer 0.1.0 (commit abc) orbit\nn,x\n"));  // no inputs line
}

TEST(AuditPlan, RefusesPicturesCertificatesAndFilesWithoutProvenance) {
  const std::string dir = "/nonexistent/rerun";
  auto refused = [&](const std::string& text) {
    return expect_input_error([&] { plan_rerun("r.x", text, dir, "/self"); }, "file");
  };
  EXPECT_TRUE(contains(refused(std::string("\x89PNG\r\n\x1a\n", 8) + "IHDR"), "'r.x' is a picture; audit the PREFIX.json"));
  EXPECT_TRUE(contains(refused("%PDF-1.5\n"), "is a picture"));
  EXPECT_TRUE(contains(refused("<?xml version=\"1.0\"?>\n<svg width=\"1\"/>"), "is a picture"));
  EXPECT_TRUE(contains(refused(R"j({"proof": "elastic_period2", "claim": "eq. (33)", "verdict": "proved"})j"),
                       "is a proof certificate; rerun its proof (build/proofs/proof_elastic_period2 --json)"));
  // A proof name that is not a name is not echoed into the advice.
  EXPECT_TRUE(contains(refused(R"({"proof": "../../bin/sh", "claim": "x"})"), "proof_NAME --json"));
  EXPECT_TRUE(contains(refused("n,x\n0,1\n"), "is not a bouncer result (no provenance with command and inputs)"));
  EXPECT_TRUE(contains(refused(R"({"rows": [1, 2]})"), "is not a bouncer result"));
}

TEST(AuditPlan, RefusesWhatNoBouncerResultRecords) {
  const std::string dir = "/nonexistent/rerun";
  auto refused = [&](const std::string& text) {
    return expect_input_error([&] { plan_rerun("r.csv", text, dir, "/self"); }, "file");
  };
  for (const char* command : {"reproduce", "audit", "merge"}) {
    EXPECT_TRUE(contains(refused(text_result(command, "out=x")), std::string("records the command '") + command + "'"));
    EXPECT_TRUE(contains(refused(json_result(command, R"("a": "1")")), "which audit does not rerun"));
  }
  EXPECT_TRUE(contains(refused(text_result("no-such-command", "a=1")), "records the command 'no-such-command'"));
  for (const char* key : {"tiles-from", "scene", "manifest", "keep-tiles", "shard", "trust-manifest"})
    EXPECT_TRUE(contains(refused(text_result("orbit", std::string(key) + "=/etc")),
                         std::string("records the input '") + key + "', which no bouncer result records"));
  EXPECT_TRUE(contains(refused(json_result("orbit", R"("../out": "x")")), "records the input '../out'"));
  EXPECT_TRUE(contains(refused(json_result("orbit", R"("Eps": "1")")), "records the input 'Eps'"));
  EXPECT_TRUE(contains(refused(json_result("orbit", R"("a": "1\u0000")")), "records an input with a NUL byte"));
}

// Every --out of the plan, and the file it compares, are inside `dir`; no word starts an
// option that a recorded value carries.
void expect_inside(const AuditPlan& plan, const std::string& dir) {
  const std::string inside = dir + "/";
  for (size_t i = 2; i < plan.argv.size(); ++i) {
    const std::string& w = plan.argv[i];
    if (w == "--out") {
      ASSERT_LT(i + 1, plan.argv.size());
      EXPECT_EQ(plan.argv[i + 1].rfind(inside, 0), 0u) << plan.argv[i + 1];
    }
    if (w.rfind("--out=", 0) == 0) {
      EXPECT_EQ(w.rfind("--out=" + inside, 0), 0u) << w;
    }
  }
  EXPECT_EQ(plan.compare_path.rfind(inside, 0), 0u) << plan.compare_path;
}

TEST(AuditPlan, TheRerunWritesOnlyIntoItsDirectory) {
  const std::string dir = "/tmp/audit-rerun";
  // A CSV of sweep written to /home/victim/s.csv: rerun into dir, compared with dir/result.csv.
  AuditPlan p = plan_rerun("s.csv", text_result("sweep", "a=24 out=/home/victim/s v=4"), dir, "/self");
  EXPECT_EQ(p.argv, (std::vector<std::string>{"/self", "sweep", "--a=24", "--v=4", "--out", dir + "/result"}));
  EXPECT_EQ(p.compare_path, dir + "/result.csv");
  EXPECT_FALSE(p.is_json);
  expect_inside(p, dir);
  // Its JSON: dir/result.json.
  p = plan_rerun("s.json", json_result("sweep", R"("a": "24", "out": "../../victim")"), dir, "/self");
  EXPECT_EQ(p.compare_path, dir + "/result.json");
  EXPECT_TRUE(p.is_json);
  expect_inside(p, dir);
  // Another command with --out: dir/result itself.
  p = plan_rerun("t", text_result("trajectory", "out=/etc/passwd"), dir, "/self");
  EXPECT_EQ(p.argv, (std::vector<std::string>{"/self", "trajectory", "--out", dir + "/result"}));
  EXPECT_EQ(p.compare_path, dir + "/result");
  // A picture command's PREFIX.json (its "files", no out input): --out dir/result.
  p = plan_rerun("b.json", json_result("basin", R"("a": "24")", R"(, "files": {"png": "/x/b.png"})"), dir, "/self");
  EXPECT_EQ(p.argv, (std::vector<std::string>{"/self", "basin", "--a=24", "--out", dir + "/result"}));
  EXPECT_EQ(p.compare_path, dir + "/result.json");
  // On stdout: orbit chose JSON with --format; other commands get --json; text gets nothing.
  p = plan_rerun("o.json", json_result("orbit", R"("a": "24", "format": "json")"), dir, "/self");
  EXPECT_EQ(p.argv, (std::vector<std::string>{"/self", "orbit", "--a=24", "--format=json"}));
  EXPECT_EQ(p.compare_path, dir + "/stdout");
  p = plan_rerun("c.json", json_result("classify", R"("a": "24")"), dir, "/self");
  EXPECT_EQ(p.argv, (std::vector<std::string>{"/self", "classify", "--a=24", "--json"}));
  p = plan_rerun("o.csv", text_result("orbit", "a=24 eps=0.8"), dir, "/self");
  EXPECT_EQ(p.argv, (std::vector<std::string>{"/self", "orbit", "--a=24", "--eps=0.8"}));
  // A recorded value that looks like an option stays the value of its own option, one word.
  p = plan_rerun("o.csv", text_result("orbit", "eps=--tiles-from=/etc"), dir, "/self");
  EXPECT_EQ(p.argv, (std::vector<std::string>{"/self", "orbit", "--eps=--tiles-from=/etc"}));
}

// An npy orbit: the sidecar PATH.json is compared as JSON and its data PATH byte for byte.
// The data's name comes from the audited file's own path, never from the recorded --out
// (which a stranger could set to any file); the rerun writes both into its directory.
TEST(AuditPlan, AnNpyOrbitComparesItsDataNamedByThePathNotByTheRecord) {
  const std::string dir = "/tmp/audit-rerun";
  AuditPlan p = plan_rerun("runs/o.npy.json", json_result("orbit", R"("a": "24", "format": "npy", "out": "/etc/shadow")"),
                           dir, "/self");
  EXPECT_EQ(p.argv, (std::vector<std::string>{"/self", "orbit", "--a=24", "--format=npy", "--out", dir + "/result"}));
  EXPECT_EQ(p.data_path, "runs/o.npy");
  EXPECT_EQ(p.rerun_data_path, dir + "/result");
  EXPECT_EQ(p.compare_path, dir + "/result.json");
  expect_inside(p, dir);
  // Other orbits have no data file.
  p = plan_rerun("o.json", json_result("orbit", R"("a": "24", "format": "json", "out": "o.json")"), dir, "/self");
  EXPECT_TRUE(p.data_path.empty());
  // The sidecar under a name without .json (its data could not be named) and the data itself
  // (the npy magic) are refused, naming what to audit instead.
  EXPECT_TRUE(contains(
      expect_input_error([&] { plan_rerun("sidecar", json_result("orbit", R"("format": "npy", "out": "o")"), dir, "/self"); }, "file"),
      "ending in .json"));
  EXPECT_TRUE(contains(
      expect_input_error([&] { plan_rerun("o.npy", std::string("\x93NUMPY\x01\x00", 8) + "{'descr': '<f8'}", dir, "/self"); }, "file"),
      "audit its provenance 'o.npy.json'"));
}

// ---------------------------------------------------------------------------------------
// audit(): refusals before anything runs, failed reruns

// A request whose executable does not exist: were anything started, the verdict would be
// rerun_failed (exit status 127), never not_a_result.
AuditRequest request_for(const std::string& file) {
  AuditRequest r;
  r.file = file;
  r.executable = "/nonexistent/bouncer";
  return r;
}

TEST(Audit, NotAResultIsRefusedBeforeAnythingRuns) {
  TempDir t("bouncer-test-audit");
  bool started = false;
  auto audited = [&](const std::string& file) {
    AuditRequest r = request_for(file);
    r.on_rerun = [&](const std::string&) { started = true; };
    return audit(r);
  };
  AuditResult r = audited(put(t / "b.png", std::string("\x89PNG\r\n\x1a\n", 8)));
  EXPECT_EQ(r.verdict, AuditVerdict::not_a_result);
  EXPECT_EQ(r.message.rfind("'" + (t / "b.png") + "' is a picture", 0), 0u) << r.message;
  r = audited(t / "missing.json");
  EXPECT_EQ(r.verdict, AuditVerdict::not_a_result);
  EXPECT_TRUE(contains(r.message, "missing.json")) << r.message;
  r = audited(put(t / "m.csv", text_result("merge", "a=1")));
  EXPECT_EQ(r.verdict, AuditVerdict::not_a_result);
  EXPECT_TRUE(contains(r.message, "records the command 'merge'")) << r.message;
  std::filesystem::create_directory(t / "empty");
  r = audited(t / "empty");
  EXPECT_EQ(r.verdict, AuditVerdict::not_a_result);
  EXPECT_TRUE(contains(r.message, "is a directory without claims.json")) << r.message;
  // A reproduce directory: malformed, or made from another manifest (not trusted).
  std::filesystem::create_directory(t / "mangled");
  put(t / "mangled/claims.json", R"({"reproduce": {"mode": "quick"}, "claims": [{"status": "reproduced"}]})");
  r = audited(t / "mangled");
  EXPECT_EQ(r.verdict, AuditVerdict::not_a_result);
  EXPECT_TRUE(contains(r.message, "is not the claims.json of bouncer reproduce (an entry of 'claims' without a string 'id')"))
      << r.message;
  std::filesystem::create_directory(t / "foreign");
  put(t / "foreign/claims.json", R"({"reproduce": {"mode": "quick", "manifest": "/home/x/m.toml"}, "claims": []})");
  r = audited(t / "foreign/claims.json");  // its claims.json: audited as its directory
  EXPECT_EQ(r.verdict, AuditVerdict::not_a_result);
  EXPECT_TRUE(contains(r.message, "was made from the manifest '/home/x/m.toml'")) << r.message;
  EXPECT_TRUE(contains(r.message, "--trust-manifest")) << r.message;
  std::filesystem::create_directory(t / "odd");
  put(t / "odd/claims.json", R"({"reproduce": {"mode": "../../x"}, "claims": []})");
  r = audited(t / "odd");
  EXPECT_TRUE(contains(r.message, "(mode '../../x')")) << r.message;
  EXPECT_FALSE(started);
}

TEST(Audit, TheCommandLinesCheckRefusesBeforeTheRerunStarts) {
  TempDir t("bouncer-test-audit");
  AuditRequest r = request_for(put(t / "o.csv", text_result("orbit", "a=-1 eps=0.8")));
  std::vector<std::string> checked;
  bool started = false;
  r.check_command = [&](const std::vector<std::string>& words) -> std::optional<std::string> {
    checked = words;
    return "a: must be positive";
  };
  r.on_rerun = [&](const std::string&) { started = true; };
  const AuditResult a = audit(r);
  EXPECT_EQ(a.verdict, AuditVerdict::not_a_result);
  EXPECT_EQ(a.message, "'" + (t / "o.csv") + "' records inputs that bouncer refuses: a: must be positive");
  EXPECT_EQ(checked, (std::vector<std::string>{"bouncer", "orbit", "--a=-1", "--eps=0.8"}));
  EXPECT_FALSE(started);
}

TEST(Audit, AFailedRerunIsReported) {
  TempDir t("bouncer-test-audit");
  AuditRequest r = request_for(put(t / "o.csv", text_result("orbit", "a=24")));
  r.executable = "/bin/false";
  AuditResult a = audit(r);
  EXPECT_EQ(a.verdict, AuditVerdict::rerun_failed);
  EXPECT_EQ(a.rerun_status, 1);
  EXPECT_EQ(a.message, "the rerun failed (exit status 1)");
  EXPECT_EQ(a.rerun, "bouncer orbit --a=24");
  // A rerun that exits 0 and prints nothing: a JSON result's rerun is not JSON; a text one
  // ends at its first line.
  r.executable = "/bin/true";
  a = audit(r);
  EXPECT_EQ(a.verdict, AuditVerdict::different);
  EXPECT_EQ(a.first.path, "line 1");
  EXPECT_EQ(a.first.rerun_line, "<end of output>");
  r.file = put(t / "o.json", json_result("orbit", R"("a": "24", "format": "json")"));
  a = audit(r);
  EXPECT_EQ(a.verdict, AuditVerdict::rerun_failed);
  EXPECT_EQ(a.message, "the rerun's output is not JSON");
}

TEST(Audit, SaysWhereItsTimeWent) {
  // A rerun that takes 0.3 s (a script that sleeps, then prints nothing): rerun_seconds holds
  // at least that, and the rerun and the comparison together fit in the wall time of the call.
  TempDir t("bouncer-test-audit");
  const std::string script = put(t / "slow.sh", "#!/bin/sh\nsleep 0.3\n");
  std::filesystem::permissions(script, std::filesystem::perms::owner_all);
  AuditRequest r = request_for(put(t / "o.csv", text_result("orbit", "a=24")));
  r.executable = script;
  const auto t0 = std::chrono::steady_clock::now();
  const AuditResult a = audit(r);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(a.verdict, AuditVerdict::different);  // its output is empty
  EXPECT_GE(a.rerun_seconds, 0.3);
  EXPECT_GE(a.compare_seconds, 0.0);
  EXPECT_LE(a.rerun_seconds + a.compare_seconds, wall);
}

// ---------------------------------------------------------------------------------------
// Real reruns with the built bouncer

#ifdef BOUNCER_CLI
// The text `bouncer ARGS` prints (exit status 0 expected).
std::string bouncer_output(const std::string& args, const TempDir& t) {
  const std::string out = t / "made.out";
  const int rc = std::system((std::string("'") + BOUNCER_CLI + "' " + args + " >'" + out + "' 2>/dev/null").c_str());
  EXPECT_EQ(rc, 0) << args;
  return slurp(out);
}

// The private directory is made under TMPDIR and removed at the end: with TMPDIR a fresh
// directory, it holds nothing after each audit.
struct AuditRun : ::testing::Test {
  TempDir tmp{"bouncer-test-audit-tmp"};
  TempDir t{"bouncer-test-audit"};
  std::string old_tmpdir;
  void SetUp() override {
    if (const char* v = std::getenv("TMPDIR")) old_tmpdir = v;
    ::setenv("TMPDIR", tmp.path.c_str(), 1);
  }
  void TearDown() override {
    if (old_tmpdir.empty()) ::unsetenv("TMPDIR");
    else ::setenv("TMPDIR", old_tmpdir.c_str(), 1);
  }
  AuditResult audited(const std::string& file, std::string* shown = nullptr) {
    AuditRequest r;
    r.file = file;
    r.executable = BOUNCER_CLI;
    r.on_rerun = [shown](const std::string& s) {
      if (shown) *shown = s;
    };
    AuditResult a = audit(r);
    EXPECT_EQ(tmp.entries(), 0) << "audit left its temporary directory";
    return a;
  }
};

const std::string kOrbit = "orbit --model constant --eps 0.8 --a 24 --theta 0.1 --v 10 --steps 5";

TEST_F(AuditRun, AnOrbitJsonRerunsIdenticalAndAnEditDiffers) {
  const std::string text = bouncer_output(kOrbit + " --format json", t);
  std::string shown;
  AuditResult a = audited(put(t / "orbit.json", text), &shown);
  EXPECT_EQ(a.verdict, AuditVerdict::identical) << a.message << a.first.path << a.first.detail;
  EXPECT_TRUE(a.is_json);
  // The rerun has the recorded inputs as --KEY=VALUE words, nothing else.
  EXPECT_EQ(shown, a.rerun);
  for (const char* w : {"--model=constant", "--eps=0.8", "--a=24", "--theta=0.1", "--v=10", "--steps=5", "--format=json"})
    EXPECT_TRUE(contains(a.rerun, w)) << a.rerun;
  EXPECT_EQ(a.rerun.rfind("bouncer orbit --", 0), 0u) << a.rerun;
  // The invocation is volatile: another binary path is still identical.
  std::string edited = text;
  const size_t inv = edited.find("\"invocation\":\"");
  ASSERT_NE(inv, std::string::npos);
  edited.insert(inv + 14, "/elsewhere/");
  EXPECT_EQ(audited(put(t / "moved.json", edited)).verdict, AuditVerdict::identical);
  // One digit of row 3's theta changed: the first difference is there, at that path.
  edited = text;
  size_t at = edited.find("[\"3\", \"");
  ASSERT_NE(at, std::string::npos);
  at = edited.find_first_of("0123456789", at + 7 + 2);  // past "0." of the theta value
  edited[at] = edited[at] == '9' ? '8' : static_cast<char>(edited[at] + 1);
  a = audited(put(t / "edited.json", edited));
  EXPECT_EQ(a.verdict, AuditVerdict::different);
  EXPECT_EQ(a.first.path, "orbits[0].rows[3][1]");
  EXPECT_TRUE(contains(a.first.detail, " vs ")) << a.first.detail;
  // Another build (its version): different, in that field.
  edited = text;
  at = edited.find("\"version\":\"");
  ASSERT_NE(at, std::string::npos);
  edited.insert(at + 11, "9");
  a = audited(put(t / "version.json", edited));
  EXPECT_EQ(a.verdict, AuditVerdict::different);
  EXPECT_EQ(a.first.path, "provenance.version");
}

TEST_F(AuditRun, AnOrbitCsvRerunsIdenticalAndAnEditedRowDiffers) {
  const std::string text = bouncer_output(kOrbit, t);
  AuditResult a = audited(put(t / "orbit.csv", text));
  EXPECT_EQ(a.verdict, AuditVerdict::identical) << a.message << a.first.path;
  EXPECT_FALSE(a.is_json);
  // Change the last digit of the last data row ("5,..."): its line number counts the lines
  // compared, i.e. all but "# invocation:" and "# time:".
  std::vector<std::string> lines;
  for (size_t from = 0, nl; (nl = text.find('\n', from)) != std::string::npos; from = nl + 1) lines.push_back(text.substr(from, nl - from));
  size_t row = lines.size(), skipped = 0;
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind("5,", 0) == 0) row = i;
  ASSERT_LT(row, lines.size());
  for (size_t i = 0; i < row; ++i) skipped += lines[i].rfind("# invocation:", 0) == 0 || lines[i].rfind("# time:", 0) == 0;
  const std::string original = lines[row];
  const size_t digit = lines[row].find_first_of("12345678", lines[row].find(',') + 1);  // past n
  ASSERT_NE(digit, std::string::npos);
  lines[row][digit] = static_cast<char>(lines[row][digit] + 1);
  std::string edited;
  for (const std::string& l : lines) edited += l + "\n";
  a = audited(put(t / "edited.csv", edited));
  EXPECT_EQ(a.verdict, AuditVerdict::different);
  EXPECT_EQ(a.first.path, "line " + std::to_string(row + 1 - skipped));
  EXPECT_EQ(a.first.file_line, lines[row]);
  EXPECT_EQ(a.first.rerun_line, original);
}
#endif

}  // namespace
