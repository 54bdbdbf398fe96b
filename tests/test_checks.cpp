// The check language of a manifest's claims (workflow/checks.hpp) on hand-written JSON: each
// operator, "*" paths, missing paths, numbers against texts. The expected outcomes follow
// from the language's rules (checks.hpp), worked out by hand for each document.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bouncer/workflow/checks.hpp"

using namespace bouncer;

namespace {

const std::string kDoc = R"({
  "verdict": "refuted", "n": 3, "x": 2.5, "small": "1e-3", "word": "abc", "numeric_word": "3x",
  "infinite": "inf", "flag": true, "none": null,
  "list": [1, 2, 3], "names": ["a", "b"],
  "orbits": [{"period": 2, "tags": ["x", "y"]}, {"period": 3, "tags": ["z"]}, {"other": 1}],
  "nested": {"a": {"b": [10, 20, {"c": "deep"}]}},
  "long": ")" + std::string(300, 'q') + R"("
})";

CheckResult eval(const std::string& path, const std::string& op, CheckValue value, const std::string& doc = kDoc) {
  const auto r = evaluate_check(Check{path, op, std::move(value)}, doc);
  EXPECT_TRUE(r.has_value()) << "not JSON";
  return r.value_or(CheckResult{});
}
bool holds(const std::string& path, const std::string& op, CheckValue value) { return eval(path, op, std::move(value)).held; }

}  // namespace

TEST(Checks, Operators) {
  for (const char* op : {"==", "!=", "<", "<=", ">", ">=", "has", "lacks"}) EXPECT_TRUE(is_check_operator(op)) << op;
  for (const char* op : {"=", "=~", "", "in", "HAS"}) EXPECT_FALSE(is_check_operator(op)) << op;
}

TEST(Checks, Equality) {
  EXPECT_TRUE(holds("verdict", "==", std::string("refuted")));
  EXPECT_FALSE(holds("verdict", "==", std::string("confirmed")));
  EXPECT_TRUE(holds("verdict", "!=", std::string("confirmed")));
  EXPECT_FALSE(holds("verdict", "!=", std::string("refuted")));
  // numbers by value: the integer 3 is the float 3.0
  EXPECT_TRUE(holds("n", "==", 3.0));
  EXPECT_TRUE(holds("n", "==", std::int64_t{3}));
  EXPECT_TRUE(holds("x", "==", 2.5));
  EXPECT_FALSE(holds("n", "!=", std::int64_t{3}));
  // anything else exactly as JSON: the number 3 is not the text "3", true is not 1
  EXPECT_FALSE(holds("n", "==", std::string("3")));
  EXPECT_TRUE(holds("n", "!=", std::string("3")));
  EXPECT_TRUE(holds("flag", "==", true));
  EXPECT_FALSE(holds("flag", "==", std::int64_t{1}));
  EXPECT_TRUE(holds("none", "==", std::monostate{}));  // null
  EXPECT_FALSE(holds("n", "==", std::monostate{}));
}

TEST(Checks, Order) {
  EXPECT_TRUE(holds("x", "<", std::int64_t{3}));
  EXPECT_FALSE(holds("x", "<", 2.5));
  EXPECT_TRUE(holds("x", "<=", 2.5));
  EXPECT_FALSE(holds("x", ">", 2.5));
  EXPECT_TRUE(holds("x", ">=", 2.5));
  EXPECT_TRUE(holds("n", ">", 2.5));
  EXPECT_FALSE(holds("n", ">=", std::int64_t{4}));
}

TEST(Checks, NumbersAgainstTexts) {
  // A text that is a whole finite number compares as that number, on either side.
  EXPECT_TRUE(holds("small", "<", 0.01));        // "1e-3" < 0.01
  EXPECT_FALSE(holds("small", ">", 0.01));
  EXPECT_TRUE(holds("n", "<", std::string("4")));  // 3 < "4"
  EXPECT_TRUE(holds("n", ">=", std::string("3.0")));
  // Anything else does not compare: neither side of a comparison holds.
  EXPECT_FALSE(holds("word", "<", std::int64_t{1}));
  EXPECT_FALSE(holds("word", ">=", std::int64_t{1}));
  EXPECT_FALSE(holds("numeric_word", "<", std::int64_t{4}));   // "3x": not a whole number
  EXPECT_FALSE(holds("numeric_word", ">=", std::int64_t{4}));
  EXPECT_FALSE(holds("infinite", ">", std::int64_t{0}));       // "inf": not finite
  EXPECT_FALSE(holds("flag", ">", std::int64_t{0}));           // a boolean is not a number
  EXPECT_FALSE(holds("list", ">", std::int64_t{0}));           // nor an array
  EXPECT_FALSE(holds("n", "<", std::string("four")));
  EXPECT_FALSE(holds("n", "<", true));
}

TEST(Checks, HasAndLacks) {
  EXPECT_TRUE(holds("list", "has", std::int64_t{2}));
  EXPECT_TRUE(holds("list", "has", 2.0));  // numbers by value here too
  EXPECT_FALSE(holds("list", "has", std::int64_t{4}));
  EXPECT_TRUE(holds("list", "lacks", std::int64_t{4}));
  EXPECT_FALSE(holds("list", "lacks", std::int64_t{1}));
  EXPECT_TRUE(holds("names", "has", std::string("a")));
  EXPECT_FALSE(holds("names", "has", std::string("A")));
  // Not an array: neither has nor lacks holds (a text is not a list of its characters).
  EXPECT_FALSE(holds("verdict", "has", std::string("r")));
  EXPECT_FALSE(holds("verdict", "lacks", std::string("r")));
}

TEST(Checks, Paths) {
  EXPECT_TRUE(holds("nested.a.b.1", "==", std::int64_t{20}));
  EXPECT_TRUE(holds("nested.a.b.2.c", "==", std::string("deep")));
  const CheckResult found = eval("nested.a.b.0", "==", std::int64_t{10});
  EXPECT_TRUE(found.found);
  EXPECT_EQ(found.got, "10");
  EXPECT_EQ(eval("verdict", "==", std::string("x")).got, "\"refuted\"");  // what was found, as JSON
  EXPECT_EQ(eval("list", "==", std::int64_t{0}).got, "[1,2,3]");
}

TEST(Checks, StarPaths) {
  // "*" maps over an array; elements without the rest of the path are left out.
  const CheckResult periods = eval("orbits.*.period", "has", std::int64_t{3});
  EXPECT_TRUE(periods.held);
  EXPECT_EQ(periods.got, "[2,3]");
  EXPECT_TRUE(holds("orbits.*.period", "lacks", std::int64_t{1}));
  EXPECT_FALSE(holds("orbits.*.period", "has", std::int64_t{1}));
  // A later "*" flattens: every tag of every orbit, in order.
  const CheckResult tags = eval("orbits.*.tags.*", "has", std::string("z"));
  EXPECT_TRUE(tags.held);
  EXPECT_EQ(tags.got, R"(["x","y","z"])");
  // Without it, the lists stay lists: no element is the text "x".
  const CheckResult lists = eval("orbits.*.tags", "has", std::string("x"));
  EXPECT_FALSE(lists.held);
  EXPECT_EQ(lists.got, R"([["x","y"],["z"]])");
  // "*" over something that is not an array finds nothing.
  EXPECT_FALSE(eval("verdict.*", "==", std::string("r")).found);
  EXPECT_FALSE(eval("nested.*", "has", std::int64_t{10}).found);
  // Over an array where no element has the rest: an empty list, found.
  const CheckResult none = eval("list.*.x", "lacks", std::int64_t{1});
  EXPECT_TRUE(none.found);
  EXPECT_EQ(none.got, "[]");
  EXPECT_TRUE(none.held);
}

TEST(Checks, MissingPathsNeverHold) {
  for (const char* op : {"==", "!=", "<", "<=", ">", ">=", "has", "lacks"}) {
    const CheckResult r = eval("absent.key", op, std::int64_t{1});
    EXPECT_FALSE(r.held) << op;
    EXPECT_FALSE(r.found) << op;
    EXPECT_EQ(r.got, "missing") << op;
  }
  EXPECT_FALSE(eval("nested.a.b.3", "==", std::int64_t{1}).found);  // index past the end
  EXPECT_FALSE(eval("nested.a.b.-1", "==", std::int64_t{1}).found);  // not an index
  EXPECT_FALSE(eval("nested.a.b.99999999999999999999999999", "==", std::int64_t{1}).found);  // past any end
  EXPECT_FALSE(eval("n.x", "==", std::int64_t{1}).found);  // a number has no keys
  EXPECT_FALSE(eval("list.x", "==", std::int64_t{1}).found);
}

TEST(Checks, ResultsAndTexts) {
  // A long value is cut at 200 characters.
  const CheckResult r = eval("long", "==", std::string("q"));
  EXPECT_EQ(r.got, "\"" + std::string(199, 'q') + "...");
  // How a check is named: PATH OP VALUE, VALUE as JSON.
  EXPECT_EQ((Check{"verdict", "==", std::string("refuted")}).text(), "verdict == \"refuted\"");
  EXPECT_EQ((Check{"n", ">=", std::int64_t{3}}).text(), "n >= 3");
  EXPECT_EQ((Check{"x", "<", 0.5}).text(), "x < 0.5");
  EXPECT_EQ((Check{"flag", "==", true}).text(), "flag == true");
  EXPECT_EQ((Check{"none", "==", std::monostate{}}).text(), "none == null");
  EXPECT_EQ(eval("n", "==", std::int64_t{3}).check, "n == 3");
  // An operator the language does not know (a Check built by hand) never holds.
  EXPECT_FALSE(holds("n", "=~", std::int64_t{3}));
}

TEST(Checks, NotJson) {
  const std::vector<Check> checks{{"a", "==", std::int64_t{1}}};
  EXPECT_FALSE(evaluate_checks(checks, "").has_value());
  EXPECT_FALSE(evaluate_checks(checks, "verdict: refuted").has_value());
  EXPECT_FALSE(evaluate_checks(checks, "{\"a\": 1").has_value());
  const auto r = evaluate_checks(checks, "{\"a\": 1}");
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(r->size(), 1u);
  EXPECT_TRUE(r->front().held);
  // Every check of a list is evaluated, in order.
  const auto two = evaluate_checks({{"a", "==", std::int64_t{1}}, {"a", "==", std::int64_t{2}}}, "{\"a\": 1}");
  ASSERT_EQ(two->size(), 2u);
  EXPECT_TRUE((*two)[0].held);
  EXPECT_FALSE((*two)[1].held);
}
