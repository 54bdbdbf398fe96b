// A reproduce manifest is data that may come from a stranger (`reproduce --manifest`, or the
// manifest a reproduce directory names, which `audit DIR` reruns): parse_manifest and
// command_problem (workflow/manifest.hpp) must refuse every manifest that would write outside
// its directory, run anything but a computing command or a proof program, choose where a
// command writes, read a scene that is not built in, or exhaust the parser; and each refusal
// must name the manifest, the item and the field at fault.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "bouncer/base/error.hpp"
#include "bouncer/base/input.hpp"
#include "bouncer/workflow/manifest.hpp"
#include "bouncer/workflow/paper.hpp"
#include "bouncer/workflow/report.hpp"
#include "test_support.hpp"

using namespace bouncer;
using bouncer::test_support::contains;
using bouncer::test_support::expect_input_error;

namespace {

// One ready panel, one claim checked on a proof's certificate, one documentation picture: the
// smallest manifest with every kind of item. Each test changes one line of it.
const std::string kPanel = R"toml(
[[panel]]
label = "fig:a"
figure = "fig:f"
panel = "(a)"
caption = "A caption."
status = "ready"
quick = ["bouncer", "basin", "--a", "24"]
full = ["bouncer", "basin", "--a", "24", "--grid", "400x300"]
)toml";
const std::string kClaim = R"toml(
[[claim]]
id = "c1"
row = "1"
groups = [2, 3]
text = "A claim"
paper = "eq. (1)"
expected = "refuted"
verdict = "**refuted**"
evidence = "A proof."
rerun = "`build/proofs/proof_elastic_period2`"
run = ["proof_elastic_period2", "--json"]
checks = [["verdict", "==", "refuted"], ["bits", ">=", 53], ["ratio", "<", 0.5], ["ok", "==", true]]
)toml";
const std::string kPicture = R"toml(
[[picture]]
name = "pic"
readme = "Pictures"
about = "A picture."
command = ["bouncer", "tongues", "--p-max", "3"]
)toml";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// Expects parse_manifest to refuse `text` with InputError("manifest", ...) whose message
// holds every one of `parts` (the source, the item, the field); returns the message.
std::string refused(const std::string& text, const std::vector<std::string>& parts) {
  const std::string message = expect_input_error([&] { parse_manifest(text, "m.toml"); }, "manifest");
  EXPECT_TRUE(contains(message, "m.toml")) << message;
  for (const std::string& p : parts) EXPECT_TRUE(contains(message, p)) << "'" << p << "' not in: " << message;
  return message;
}

}  // namespace

TEST(Manifest, ParsesEveryKindOfItem) {
  const Manifest m = parse_manifest(kPanel + kClaim + kPicture, "m.toml");
  ASSERT_EQ(m.panels.size(), 1u);
  ASSERT_EQ(m.claims.size(), 1u);
  ASSERT_EQ(m.pictures.size(), 1u);
  const Panel& p = m.panels[0];
  EXPECT_EQ(p.label, "fig:a");
  EXPECT_EQ(p.name(), "a");  // the file name drops "fig:"
  EXPECT_EQ(p.quick, (std::vector<std::string>{"bouncer", "basin", "--a", "24"}));
  EXPECT_EQ(p.full.back(), "400x300");
  const Claim& c = m.claims[0];
  EXPECT_EQ(c.groups, (std::vector<long>{2, 3}));
  EXPECT_TRUE(c.quick);  // settled in --quick unless it says otherwise
  // A proof's full run is its run with --full, when the manifest gives none.
  EXPECT_EQ(c.full_run, (std::vector<std::string>{"proof_elastic_period2", "--json", "--full"}));
  // Each check's VALUE keeps its TOML type: text, integer, float, boolean.
  ASSERT_EQ(c.checks.size(), 4u);
  EXPECT_EQ(std::get<std::string>(c.checks[0].value), "refuted");
  EXPECT_EQ(std::get<std::int64_t>(c.checks[1].value), 53);
  EXPECT_EQ(std::get<double>(c.checks[2].value), 0.5);
  EXPECT_EQ(std::get<bool>(c.checks[3].value), true);
  EXPECT_EQ(m.pictures[0].id(), "picture:pic");
  EXPECT_EQ(m.pictures[0].files, (std::vector<std::string>{"pic.png"}));  // default NAME.png
}

TEST(Manifest, BouncerClaimFullRunDefaultsToItsRun) {
  const Manifest m = parse_manifest(replaced(kClaim, R"(run = ["proof_elastic_period2", "--json"])",
                                             R"(run = ["bouncer", "classify", "--a", "18", "--json"])"),
                                    "m.toml");
  EXPECT_EQ(m.claims[0].full_run, m.claims[0].run);
}

TEST(Manifest, TilesFromMustNameAnEarlierPanel) {
  const std::string second = replaced(kPanel, R"(label = "fig:a")", "label = \"fig:b\"\ntiles_from = \"fig:a\"");
  EXPECT_EQ(parse_manifest(kPanel + second, "m.toml").panels[1].tiles_from, "fig:a");
  // the same panel before the one it names: refused, naming the panel and the key
  refused(second + kPanel, {"panel fig:b", "tiles_from 'fig:a'"});
}

TEST(Manifest, UnsafeNamesAreRefused) {
  // Ids, labels and file names become file names in the reproduce directory.
  refused(replaced(kPanel, R"(label = "fig:a")", R"(label = "../../etc/x")"), {"panel ../../etc/x", "label"});
  refused(replaced(kPanel, R"(label = "fig:a")", R"(label = "fig/a")"), {"panel fig/a", "label"});
  refused(replaced(kPanel, R"(label = "fig:a")", "label = \"fig:a\"\ntwin_of = \"..\""), {"panel fig:a", "label"});
  refused(replaced(kClaim, R"(id = "c1")", R"(id = "a/b")"), {"claim a/b", "id"});
  refused(replaced(kClaim, R"(id = "c1")", R"(id = "..")"), {"claim ..", "id"});
  refused(replaced(kClaim, R"(id = "c1")", "id = \"" + std::string(101, 'x') + "\""), {"claim xxx", "id"});
  refused(replaced(kPicture, R"(name = "pic")", R"(name = "/tmp/pic")"), {"picture /tmp/pic", "name"});
  refused(replaced(kPicture, R"(about = "A picture.")", "about = \"A picture.\"\nfiles = [\"../pic.png\"]"),
          {"picture pic", "file '../pic.png'"});
}

TEST(Manifest, MissingAndWrongFieldsAreNamed) {
  refused(replaced(kPanel, "caption = \"A caption.\"\n", ""), {"panel fig:a", "'caption'"});
  refused(replaced(kPanel, R"(status = "ready")", R"(status = "maybe")"), {"panel fig:a", "status"});
  refused(replaced(kPanel, R"(status = "ready")", R"(status = "pending")"), {"panel fig:a", "reason"});
  refused(replaced(kPanel, R"(full = ["bouncer", "basin", "--a", "24", "--grid", "400x300"])", ""),
          {"panel fig:a", "quick and full"});
  refused(replaced(kPanel, R"(quick = ["bouncer", "basin", "--a", "24"])", R"(quick = ["bouncer", 7])"),
          {"panel fig:a", "'quick'"});
  refused(replaced(kClaim, R"(expected = "refuted")", R"(expected = "probably")"), {"claim c1", "expected"});
  refused(replaced(kClaim, "run = [\"proof_elastic_period2\", \"--json\"]\n", ""), {"claim c1", "run command"});
  refused(replaced(kClaim, "checks = [", "unchecked = ["), {"claim c1", "check"});
  refused(replaced(kClaim, R"(["verdict", "==", "refuted"])", R"(["verdict", "=="])"), {"claim c1", "[PATH, OP, VALUE]"});
  refused(replaced(kClaim, R"(["verdict", "==", "refuted"])", R"(["verdict", "=~", "ref"])"),
          {"claim c1", "operator '=~'"});
  refused(replaced(kPicture, "command = [\"bouncer\", \"tongues\", \"--p-max\", \"3\"]\n", ""), {"picture pic", "command"});
  refused("panel = [1, 2]\n", {"[[panel]]"});
  refused("[[claim]]\nrow = \"1\"\n", {"claim", "'id'"});
}

TEST(Manifest, ForbiddenCommandsAreRefused) {
  // Workflow commands (they start processes or read prefixes of their own) and non-commands.
  for (const char* command : {"reproduce", "audit", "merge", "rm", ""})
    EXPECT_TRUE(contains(command_problem({"bouncer", command}), "a manifest runs only")) << command;
  EXPECT_TRUE(contains(command_problem({"bouncer"}), "a manifest runs only"));
  EXPECT_TRUE(contains(command_problem({"sh", "-c", "rm -rf /"}), "must start with bouncer or proof_NAME"));
  EXPECT_TRUE(contains(command_problem({"/usr/bin/bouncer", "basin"}), "must start with bouncer"));
  // Options that choose where a command reads tiles or writes, in both spellings.
  for (const char* option : {"--out", "--tiles-from", "--keep-tiles", "--shard", "--manifest"}) {
    EXPECT_TRUE(contains(command_problem({"bouncer", "basin", option, "x"}), std::string("gives ") + option)) << option;
    EXPECT_TRUE(contains(command_problem({"bouncer", "basin", std::string(option) + "=x"}), std::string("gives ") + option))
        << option;
  }
  // Proof programs: a plain name, and only --full, --json, --bits N.
  EXPECT_EQ(command_problem({"proof_elastic_period2", "--full", "--json", "--bits", "200"}), "");
  EXPECT_TRUE(contains(command_problem({"proof_../../bin/sh"}), "not a proof program's name"));
  EXPECT_TRUE(contains(command_problem({"proof_"}), "not a proof program's name"));
  EXPECT_TRUE(contains(command_problem({"proof_X"}), "not a proof program's name"));  // lower case only
  EXPECT_TRUE(contains(command_problem({"proof_a", "--out", "x"}), "got '--out'"));
  EXPECT_TRUE(contains(command_problem({"proof_a", "--bits"}), "got '--bits'"));  // --bits without N
  // Words a command line cannot hold, or too long to be an option.
  EXPECT_TRUE(contains(command_problem({"bouncer", "basin", std::string("a\0b", 3)}), "NUL byte"));
  EXPECT_TRUE(contains(command_problem({"bouncer", "basin", std::string(4097, 'x')}), "4096"));
  EXPECT_EQ(command_problem({"bouncer", "basin", std::string(4096, 'x')}), "");
  // Computing commands with their own options are fine; no command is no problem.
  EXPECT_EQ(command_problem({"bouncer", "basin", "--a", "24", "--output-hint", "x"}), "");
  EXPECT_EQ(command_problem({}), "");
  // and parse_manifest names the item and the command at fault
  refused(replaced(kPanel, R"(quick = ["bouncer", "basin", "--a", "24"])", R"(quick = ["bouncer", "reproduce"])"),
          {"panel fig:a", "command runs 'reproduce'"});
  refused(replaced(kClaim, R"(run = ["proof_elastic_period2", "--json"])", R"(run = ["bouncer", "audit", "x"])"),
          {"claim c1", "command runs 'audit'"});
  refused(replaced(kPicture, R"(command = ["bouncer", "tongues", "--p-max", "3"])",
                   R"(command = ["bouncer", "tongues", "--out", "/tmp/x"])"),
          {"picture pic", "gives --out"});
}

TEST(Manifest, SceneMustBeBuiltIn) {
  // The scenes built in are exactly the files of data/scenes/.
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(BOUNCER_SOURCE_DIR) + "/data/scenes"))
    if (entry.path().extension() == ".toml") {
      ++files;
      const std::string key = "data/scenes/" + entry.path().filename().string();
      ASSERT_TRUE(built_in_scenes().count(key)) << key;
      EXPECT_EQ(built_in_scenes().at(key), test_support::slurp(entry.path().string())) << key;
    }
  EXPECT_EQ(built_in_scenes().size(), files);
  EXPECT_EQ(command_problem({"bouncer", "orbit", "--scene", "data/scenes/default.toml"}), "");
  EXPECT_EQ(command_problem({"bouncer", "orbit", "--scene=data/scenes/default.toml"}), "");
  // a file of the system, a scene not built in, a relative path out, and no value at all
  for (const std::string scene : {"/etc/passwd", "data/scenes/none.toml", "../data/scenes/default.toml"}) {
    EXPECT_TRUE(contains(command_problem({"bouncer", "orbit", "--scene", scene}), "--scene '" + scene + "' is not a scene"))
        << scene;
    EXPECT_TRUE(contains(command_problem({"bouncer", "orbit", "--scene=" + scene}), "is not a scene")) << scene;
  }
  EXPECT_TRUE(contains(command_problem({"bouncer", "orbit", "--scene"}), "--scene '' is not a scene"));
  refused(replaced(kPicture, R"(command = ["bouncer", "tongues", "--p-max", "3"])",
                   R"(command = ["bouncer", "tongues", "--scene", "/etc/passwd"])"),
          {"picture pic", "--scene '/etc/passwd'"});
}

TEST(Manifest, OversizeDeepAndBrokenTextIsRefused) {
  // more than kMaxManifestBytes: refused before parsing, naming the size
  const std::string big = kPanel + "# " + std::string(kMaxManifestBytes, 'x') + "\n";
  refused(big, {"larger than"});
  // arrays nested deeper than kMaxTomlDepth (toml++'s recursive descent would go as deep)
  const int deep = kMaxTomlDepth + 8;
  refused("a = " + std::string(deep, '[') + std::string(deep, ']') + "\n", {"line 1", "nested"});
  // dotted keys count as nesting too
  std::string dotted = "k";
  for (int i = 0; i < kMaxTomlDepth + 8; ++i) dotted += ".k";
  refused(kPanel + dotted + " = 1\n", {"nested"});
  refused(kPanel + std::string("x = \"a\0b\"\n", 10), {"NUL byte"});
  refused("[[panel]\nlabel = 1\n", {});  // not TOML: toml++'s message, after the source
}

TEST(Manifest, PaperManifestParses) {
  const Manifest m = parse_manifest(std::string(paper_manifest_text()), kPaperManifestSource);
  EXPECT_FALSE(m.panels.empty());
  EXPECT_FALSE(m.claims.empty());
  EXPECT_FALSE(m.pictures.empty());
  for (const Claim& c : m.claims) {
    EXPECT_NE(std::find(verdict_words().begin(), verdict_words().end(), c.expected), verdict_words().end()) << c.id;
    EXPECT_FALSE(c.checks.empty()) << c.id;
  }
}

TEST(Manifest, CommandText) {
  // A proof program where the build puts it; words quoted for a POSIX shell where needed.
  EXPECT_EQ(command_text({"proof_elastic_period2", "--json"}), "build/proofs/proof_elastic_period2 --json");
  EXPECT_EQ(command_text({"bouncer", "basin", "--a=24", "--range", "0:1,2"}), "bouncer basin --a=24 --range 0:1,2");
  EXPECT_EQ(command_text({"bouncer", "a b", ""}), "bouncer 'a b' ''");
  EXPECT_EQ(command_text({"bouncer", "it's"}), "bouncer 'it'\\''s'");
  EXPECT_EQ(command_text({"bouncer", "$(x)"}), "bouncer '$(x)'");
}

TEST(Manifest, ProofPrefixOfAnInstall) {
  // An installed bouncer names its proof programs where it found them: the prefix replaces
  // build/proofs/ in commands and in every place of a claim's rerun text, nothing else.
  EXPECT_EQ(command_text({"proof_elastic_period2", "--json"}, "/opt/b/libexec/bouncer/"),
            "/opt/b/libexec/bouncer/proof_elastic_period2 --json");
  EXPECT_EQ(command_text({"bouncer", "proof_x"}, "/p/"), "bouncer proof_x");  // only the program word
  EXPECT_EQ(command_text({"proof_a"}, "/my dir/"), "'/my dir/proof_a'");
  EXPECT_EQ(rerun_text("`build/proofs/proof_a`; `build/proofs/proof_b [--full]`", "/p/"), "`/p/proof_a`; `/p/proof_b [--full]`");
  EXPECT_EQ(rerun_text("`bouncer basin --scene data/scenes/x.toml`", "/p/"), "`bouncer basin --scene data/scenes/x.toml`");
  EXPECT_EQ(rerun_text("`build/proofs/proof_a`", kBuildProofPrefix), "`build/proofs/proof_a`");
  EXPECT_EQ(rerun_text("", "/p/"), "");
}

TEST(Manifest, RerunTextNamesNoCheckoutPath) {
  // A built-in scene by name (found from any directory and from an install; picture- dropped
  // as --scene accepts it), an unknown scene path kept as written, ctest run in build/ and,
  // for an install, said to need a build tree.
  EXPECT_EQ(rerun_text("`bouncer basin --scene data/scenes/picture-basin-eps05-a24.toml --out b`", "/p/"),
            "`bouncer basin --scene basin-eps05-a24 --out b`");
  EXPECT_EQ(rerun_text("`bouncer continue --scene data/scenes/continue-veldep-period7.toml --certify`", kBuildProofPrefix),
            "`bouncer continue --scene continue-veldep-period7 --certify`");
  EXPECT_EQ(rerun_text("`bouncer scan --scene data/scenes/nope.toml`", "/p/"), "`bouncer scan --scene data/scenes/nope.toml`");
  EXPECT_EQ(rerun_text("`ctest -R Sticking`; `bouncer certify-sticking --a 24`", kBuildProofPrefix),
            "`ctest --test-dir build -R Sticking`; `bouncer certify-sticking --a 24`");
  EXPECT_EQ(rerun_text("`ctest -R Sticking`; `x`", "/p/"), "`ctest --test-dir build -R Sticking` (in a build tree of the sources); `x`");
  // Every rerun of the built-in manifest, as an install shows it: no path into a checkout
  // except the ctest line that says it needs one.
  for (const Claim& c : parse_manifest(std::string(paper_manifest_text()), kPaperManifestSource).claims) {
    const std::string r = rerun_text(c.rerun, "/usr/libexec/bouncer/");
    EXPECT_EQ(r.find("data/scenes/"), std::string::npos) << c.id << ": " << r;
    EXPECT_EQ(r.find("build/"), std::string::npos) << c.id << ": " << r;
    for (size_t k = 0; (k = r.find("--test-dir build", k)) != std::string::npos; ++k)
      EXPECT_NE(r.find("(in a build tree of the sources)", k), std::string::npos) << c.id << ": " << r;
  }
}

// The report shows the paper's captions as text, not LaTeX (issue 24): hand-converted cases
// of every construct the captions use, and every caption of the built-in manifest free of
// math delimiters, commands and braces.
TEST(Report, CaptionsAreTextNotLatex) {
  EXPECT_EQ(latex_text("Branched Fermi acceleration for $a=19.0$;"), "Branched Fermi acceleration for a = 19.0;");
  EXPECT_EQ(latex_text("the model with $c\\sim 1000$ (cf. Fig.~\\ref{fig:bifurc_three})"),
            "the model with c ∼ 1000 (cf. Fig. bifurc_three)");
  EXPECT_EQ(latex_text("$(\\theta_*,v_*)=(\\theta_*,12)$"), "(θ*,v*) = (θ*,12)");
  EXPECT_EQ(latex_text("as $\\theta_n=1/2$, $\\sigma<0$"), "as θₙ = 1/2, σ < 0");
  EXPECT_EQ(latex_text("in parameter $a,\\epsilon$-space, $k>1000$"), "in parameter a,ε-space, k > 1000");
  EXPECT_EQ(latex_text("$x^2$ and $v_{n+1}$ and $a_{xy}$"), "x² and vₙ₊₁ and a_xy");
  EXPECT_EQ(latex_text("Sec.~\\ref{sec:5.1}, 50\\% and \\emph{typical}"), "Sec. 5.1, 50% and typical");
  const Manifest m = parse_manifest(std::string(paper_manifest_text()), kPaperManifestSource);
  ASSERT_FALSE(m.panels.empty());
  for (const Panel& p : m.panels) {
    const std::string t = latex_text(p.caption);
    EXPECT_EQ(t.find_first_of("$\\{}~"), std::string::npos) << p.label << ": " << t;
    EXPECT_EQ(t.find("  "), std::string::npos) << p.label << ": " << t;
  }
}

// report.html's navigation (issue 24) for items in every state, built by hand: a drawn panel
// and a pending one, a reproduced claim and one whose check failed. The contents link each;
// the contact sheet shows the drawn panel's thumbnail and says the other is pending; each
// claim is one row whose summary is its text cut at a word (hand-cut below), its details
// holding the whole text, the rerun and each check with its outcome.
TEST(Report, HtmlLinksEveryItemInEveryState) {
  const std::string long_text =
      "A claim long enough to be cut: the fixed points attract most of the trapping region at every a we tried";
  const Manifest m = parse_manifest(
      kPanel + replaced(replaced(kPanel, "fig:a", "fig:b"), "status = \"ready\"", "status = \"pending\"\nreason = \"needs a week\"") +
          kClaim + replaced(replaced(replaced(kClaim, "\"c1\"", "\"c2\""), "row = \"1\"", "row = \"2\""), "A claim", long_text),
      "m.toml");
  ReproduceResult r;
  r.manifest = m;
  r.build = "0.0.0 (commit x)";
  r.proof_prefix = "/opt/b/libexec/bouncer/";
  auto item = [](const std::string& id, ItemKind kind, size_t index, ItemState state) {
    ItemResult it;
    it.id = id;
    it.kind = kind;
    it.index = index;
    it.state = state;
    return it;
  };
  r.items.push_back(item("fig:a", ItemKind::panel, 0, ItemState::done));
  r.items.back().argv = m.panels[0].quick;
  r.items.push_back(item("fig:b", ItemKind::panel, 1, ItemState::skipped));
  r.items.push_back(item("c1", ItemKind::claim, 0, ItemState::done));
  r.items.back().status = ClaimStatus::reproduced;
  r.items.back().verdict = "refuted";
  r.items.back().argv = m.claims[0].run;
  r.items.back().outputs = {"claims/c1.json"};
  r.items.back().checks = {{"verdict == \"refuted\"", "\"refuted\"", true, true}};
  r.items.push_back(item("c2", ItemKind::claim, 1, ItemState::done));
  r.items.back().status = ClaimStatus::not_reproduced;
  r.items.back().verdict = "not reproduced: check bits >= 53 failed";
  r.items.back().argv = m.claims[1].run;
  r.items.back().checks = {{"bits >= 53", "24", true, false}};
  const std::string h = report_html(r);
  for (const char* link : {"href=\"#claim-c1\"", "href=\"#claim-c2\"", "href=\"#fig:a\"", "href=\"#fig:b\"", "href=\"#figure-fig:f\"",
                           "href=\"#contact-sheet\"", "href=\"#times\""})
    EXPECT_TRUE(contains(h, link)) << link;
  for (const char* id : {"id=\"claim-c1\"", "id=\"claim-c2\"", "id=\"fig:a\"", "id=\"fig:b\"", "id=\"figure-fig:f\"", "id=\"contact-sheet\""})
    EXPECT_TRUE(contains(h, id)) << id;
  EXPECT_TRUE(contains(h, "<a href=\"#fig:a\"><img src=\"panels/a.png\""));
  EXPECT_TRUE(contains(h, "<a href=\"#fig:b\"><span class=\"bad\">(pending)</span>"));
  EXPECT_FALSE(contains(h, "src=\"panels/b.png\""));
  // The summary: the first 80 characters end inside "region"; cut at the space before it.
  EXPECT_TRUE(contains(h, "<summary>A claim long enough to be cut: the fixed points attract most of the trapping …</summary>")) << h;
  EXPECT_TRUE(contains(h, long_text));  // whole, in the details
  EXPECT_TRUE(contains(h, "<summary>A claim</summary>"));
  EXPECT_TRUE(contains(h, "<li class=\"ok\">held: <code>verdict == &quot;refuted&quot;</code>"));
  EXPECT_TRUE(contains(h, "<li class=\"bad\">FAILED: <code>bits &gt;= 53</code> (got <code>24</code>)"));
  EXPECT_TRUE(contains(h, "<code>/opt/b/libexec/bouncer/proof_elastic_period2</code>"));  // the rerun, for this install
  EXPECT_TRUE(contains(h, "<a href=\"claims/c1.json\">claims/c1.json</a>"));
  EXPECT_EQ(h.find("build/proofs"), std::string::npos);
}
