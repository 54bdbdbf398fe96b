// Provenance (io/provenance.hpp) against independent truth: the libraries' own version
// queries (mpfr_get_version, gmp_version, MPFI_VERSION_STRING, BOOST_VERSION), the commit
// forms the documentation promises (docs/guide/development.md) (40 hex digits, optionally +dirty-<16 hex>, or
// tree-sha256:<64 hex>), an unquoting reader written here from quote_input's documented rule
// (so every value round-trips through the "# inputs:" line), and an independent JSON parser
// (nlohmann) reading as_json back field by field.
#include <gtest/gtest.h>

#include <gmp.h>
#include <mpfi.h>
#include <mpfr.h>

#include <boost/version.hpp>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "bouncer/io/provenance.hpp"
#include "bouncer/verify/chaos_certificate.hpp"

namespace bouncer {
namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Reads one value of the "# inputs:" line from `pos` (documented form: plain, or "..." with
// \" and \\), returning it and moving pos past it.
std::string read_input(const std::string& line, size_t& pos) {
  std::string out;
  if (line[pos] != '"') {
    while (pos < line.size() && line[pos] != ' ') out += line[pos++];
    return out;
  }
  ++pos;
  while (pos < line.size() && line[pos] != '"') {
    if (line[pos] == '\\') ++pos;
    out += line[pos++];
  }
  ++pos;  // the closing quote
  return out;
}

// The key=value pairs of an "# inputs:" line.
std::vector<std::pair<std::string, std::string>> read_inputs_line(const std::string& line) {
  const std::string head = "# inputs:";
  EXPECT_EQ(line.rfind(head, 0), 0u) << line;
  std::vector<std::pair<std::string, std::string>> out;
  size_t pos = head.size();
  while (pos < line.size()) {
    EXPECT_EQ(line[pos], ' ') << line;
    ++pos;
    const size_t eq = line.find('=', pos);
    const std::string key = line.substr(pos, eq - pos);
    pos = eq + 1;
    out.emplace_back(key, read_input(line, pos));
  }
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream s(text);
  for (std::string l; std::getline(s, l);) out.push_back(l);
  return out;
}

Provenance sample() {
  Provenance p;
  p.command = "orbit";
  p.inputs = {{"a", "24"}, {"eps", "0.5"}, {"out", "my results/o \"1\".csv"}, {"theta", "0.25,0.1"}};
  p.precision = "mpfr:256";
  p.bits = 256;
  p.decimal_note = "each decimal input is rounded";
  p.invocation = "bouncer orbit --a 24";
  return p;
}

TEST(QuoteInput, PlainValuesStayPlain) {
  for (const char* v : {"24", "0.25,0.1", "mpfr:256", "a=b", "/tmp/x.csv", "\xce\xb8\xe2\x82\x80"})
    EXPECT_EQ(quote_input(v), v);
}

TEST(QuoteInput, OthersAreQuotedByTheDocumentedRule) {
  EXPECT_EQ(quote_input(""), "\"\"");
  EXPECT_EQ(quote_input("my file.csv"), "\"my file.csv\"");
  EXPECT_EQ(quote_input("say \"hi\""), "\"say \\\"hi\\\"\"");
  EXPECT_EQ(quote_input("a\\b"), "\"a\\\\b\"");
  EXPECT_EQ(quote_input("tab\there"), "\"tab\there\"");
  EXPECT_EQ(quote_input("del\x7f"), "\"del\x7f\"");
  EXPECT_EQ(quote_input("\""), "\"\\\"\"");
}

TEST(QuoteInput, EveryValueRoundTripsThroughTheInputsLine) {
  std::mt19937 rng(20261126);
  const std::string alphabet = std::string("ab =\"\\,.:\t\x01\x7f") + "\xce\xb8";
  for (int i = 0; i < 2000; ++i) {
    std::string v;
    const int n = static_cast<int>(rng() % 12);
    for (int k = 0; k < n; ++k) v += alphabet[rng() % alphabet.size()];
    Provenance p;
    p.command = "orbit";
    p.inputs = {{"out", v}, {"a", "24"}};
    std::string line;
    for (const std::string& l : lines_of(p.as_comment_lines()))
      if (l.rfind("# inputs:", 0) == 0) line = l;
    const auto back = read_inputs_line(line);
    ASSERT_EQ(back.size(), 2u) << line;
    EXPECT_EQ(back[0].second, v) << line;
    EXPECT_EQ(back[1], (std::pair<std::string, std::string>{"a", "24"})) << line;
  }
}

TEST(BuildInfo, CommitHasOneOfTheTwoDocumentedForms) {
  const BuildInfo& b = build_info();
  const std::regex git("[0-9a-f]{40}(\\+dirty-[0-9a-f]{16})?"), tree("tree-sha256:[0-9a-f]{64}");
  EXPECT_TRUE(std::regex_match(b.commit, git) || std::regex_match(b.commit, tree)) << b.commit;
  EXPECT_FALSE(b.version.empty());
  EXPECT_FALSE(b.compiler.empty());
  EXPECT_FALSE(b.build_type.empty());
  // Reproducible doubles need this flag (docs/guide/development.md).
  EXPECT_TRUE(contains(b.flags, "-ffp-contract=off")) << b.flags;
}

TEST(LibraryVersions, AreTheLinkedLibrariesOwnVersions) {
  const std::string v = library_versions();
  std::ostringstream boost;
  boost << "boost " << BOOST_VERSION / 100000 << "." << BOOST_VERSION / 100 % 1000 << "." << BOOST_VERSION % 100 << ", ";
  EXPECT_EQ(v.rfind(boost.str(), 0), 0u) << v;
  EXPECT_TRUE(contains(v, std::string("mpfr ") + mpfr_get_version() + ", ")) << v;
  EXPECT_TRUE(contains(v, std::string("mpfi ") + MPFI_VERSION_STRING + ", ")) << v;
  EXPECT_TRUE(contains(v, std::string("gmp ") + gmp_version + ", ")) << v;
  EXPECT_TRUE(std::regex_search(v, std::regex(", qd [^,]+, "))) << v;
  EXPECT_TRUE(contains(v, ", arb " + arb_library_version())) << v;  // the chaos replay's library
  EXPECT_TRUE(std::regex_search(v, std::regex(", arb [0-9]+\\.[0-9]+\\.[0-9]+$"))) << v;
}

TEST(Provenance, CommentLinesCarryEveryField) {
  const Provenance p = sample();
  const std::string text = p.as_comment_lines();
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const auto lines = lines_of(text);
  for (const std::string& l : lines) EXPECT_EQ(l.rfind("# ", 0), 0u) << l;  // CSV readers skip them
  const BuildInfo& b = build_info();
  EXPECT_EQ(lines[0], "# bouncer " + b.version + " (commit " + b.commit + ") orbit");
  EXPECT_EQ(lines[1], "# invocation: bouncer orbit --a 24");
  EXPECT_EQ(read_inputs_line(lines[2]), p.inputs);
  EXPECT_EQ(lines[3], "# precision: mpfr:256 (256 significand bits)");
  EXPECT_EQ(lines[4], "# decimals: each decimal input is rounded");
  EXPECT_EQ(lines[5], "# libraries: " + library_versions());
  EXPECT_TRUE(contains(lines[6], b.flags)) << lines[6];
  EXPECT_EQ(lines.size(), 7u);
}

TEST(Provenance, OptionalLinesAreLeftOut) {
  Provenance p;
  p.command = "audit";
  p.precision = "exact";
  p.bits = 0;  // no scalar type: no bits claimed
  const std::string text = p.as_comment_lines();
  EXPECT_FALSE(contains(text, "# invocation:")) << text;
  EXPECT_FALSE(contains(text, "# decimals:")) << text;
  EXPECT_FALSE(contains(text, "significand bits")) << text;
  EXPECT_TRUE(contains(text, "\n# inputs:\n# precision: exact\n")) << text;
}

TEST(Provenance, JsonReadsBackAsTheSameFields) {
  Provenance p = sample();
  p.inputs.emplace_back("label", std::string("ctl \x01 nl\n tab\t quote\" back\\ \xce\xb8"));
  const nlohmann::json j = nlohmann::json::parse(p.as_json());
  const BuildInfo& b = build_info();
  EXPECT_EQ(j.at("tool"), "bouncer");
  EXPECT_EQ(j.at("version"), b.version);
  EXPECT_EQ(j.at("commit"), b.commit);
  EXPECT_EQ(j.at("command"), "orbit");
  EXPECT_EQ(j.at("precision"), "mpfr:256");
  EXPECT_EQ(j.at("bits"), 256);
  EXPECT_EQ(j.at("decimals"), p.decimal_note);
  EXPECT_EQ(j.at("invocation"), p.invocation);
  EXPECT_EQ(j.at("libraries"), library_versions());
  EXPECT_EQ(j.at("compiler"), b.compiler);
  EXPECT_EQ(j.at("build_type"), b.build_type);
  EXPECT_EQ(j.at("flags"), b.flags);
  ASSERT_TRUE(j.at("inputs").is_object());
  EXPECT_EQ(j.at("inputs").size(), p.inputs.size());
  for (const auto& [k, v] : p.inputs) EXPECT_EQ(j.at("inputs").at(k).get<std::string>(), v) << k;
  // Same order as given (ordered_json), so the JSON reads like the comment lines.
  const std::string text = p.as_json();
  EXPECT_LT(text.find("\"a\""), text.find("\"theta\""));
  EXPECT_LT(text.find("\"theta\""), text.find("\"label\""));
  // No inputs: an empty object, not null.
  Provenance none;
  EXPECT_TRUE(nlohmann::json::parse(none.as_json()).at("inputs").is_object());
}

}  // namespace
}  // namespace bouncer
