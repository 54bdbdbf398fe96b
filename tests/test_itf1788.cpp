// ITF1788, the IEEE Std 1788-2015 interval test suite (https://github.com/oheim/ITF1788),
// run on both interval types: DoubleInterval (interval:double) and Mpfi at 53 bits.
//
// The vectors (tests/data/itf1788/vectors.txt, converted by tools/itf1788_convert.py; its
// header names the source commit, the files and their licences) are the suite's cases for
// the operations these types provide: add sub mul div neg recip (1 / x) sqrt exp log abs
// convexHull (hull) intersection (intersect), and the predicates subset (contains),
// isMember (contains a number), precedes / strictPrecedes (ScalarTraits::le / lt, read both
// ways: le(x, y) certainly true iff lt(y, x) certainly false) and isCommonInterval
// (ScalarTraits::is_finite). Every literal of ITF1788 is a double (the nearest one), and an
// expected interval is the tightest interval of doubles holding the exact result.
//
// Truth independent of the code: the expected results of ITF1788 (written for the reference
// implementations libieeep1788, MPFI, FI_LIB and C-XSC, and checked against them there).
// Checks, per case and type:
//   * soundness: the result encloses the expected interval. For Mpfi, whose 53-bit ends have
//     MPFR's exponent range (finer than the doubles among the subnormals, finite beyond
//     DBL_MAX), the ends are first rounded outward to double (mpfr_get_d RNDD / RNDU), which
//     maps every 53-bit enclosure of the exact result onto a double enclosure of it;
//   * tightness: the result (its outward double ends for Mpfi) equals the expected interval.
//     Asserted for every case of both types (DoubleInterval's header claims each end is the
//     directed rounding of the exact result; MPFI's functions round each end correctly);
//     counted and printed per operation;
//   * the types' conventions where IEEE 1788 has an empty interval (the types have none): an
//     empty operand is the NaN interval, and the result must then be NaN (invalid stays
//     invalid, the hull included); an expected empty result must be NaN (an empty
//     intersection, sqrt or log of an interval below 0, a quotient by [0, 0]), never an
//     inverted pair; the predicates of a NaN interval are false (contains) or
//     Truth::invalid (lt, le);
//   * a NaN result where IEEE 1788 has a non-empty one is a failure unless the type
//     documents it ("declined", counted by reason): a divisor holding 0 (DoubleInterval), a
//     corner 0 * inf (DoubleInterval), log of an interval reaching below 0 (both), sqrt of one
//     reaching below 0 (Mpfi).
// Skipped, counted and printed: isMember of +-inf or NaN (not real numbers; the types'
// contains compares the ends, so [entire] "contains" -inf).
// The test fails if fewer than kMinCases cases are checked per type or an operation has
// fewer than kMinPerOperation, so that a broken converter or parser cannot pass silently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "bouncer/scalar/traits.hpp"

#ifndef BOUNCER_ITF1788_VECTORS
#error "BOUNCER_ITF1788_VECTORS (the path of tests/data/itf1788/vectors.txt) is set by tests/CMakeLists.txt"
#endif

namespace bouncer {
namespace {

constexpr long kMinCases = 1500;       // of 1545 in the committed file
constexpr long kMinPerOperation = 10;

const char* const kOperations[] = {"add", "sub", "mul", "div", "neg", "recip", "sqrt", "exp", "log", "abs",
                                   "convexHull", "intersection", "subset", "isMember", "precedes",
                                   "strictPrecedes", "isCommonInterval"};

std::string vectors_path() {
  const char* env = std::getenv("BOUNCER_ITF1788_VECTORS");
  return env ? env : BOUNCER_ITF1788_VECTORS;
}

// ---------------------------------------------------------------------------------------
// The vectors.

struct Interval {
  bool empty = false;
  double lo = 0, hi = 0;
};

struct Case {
  std::string op;
  std::vector<std::string> args;  // interval tokens, or a number (isMember's first)
  std::string expected;           // an interval token, or true / false
  std::string where;              // file:testcase, line
};

bool parse_double(const std::string& t, double& out) {
  if (t.empty()) return false;
  char* end = nullptr;
  out = std::strtod(t.c_str(), &end);
  return *end == '\0';
}

bool parse_interval(const std::string& t, Interval& out) {
  if (t == "[empty]") {
    out.empty = true;
    return true;
  }
  if (t.size() < 5 || t.front() != '[' || t.back() != ']') return false;
  const auto comma = t.find(',');
  if (comma == std::string::npos) return false;
  return parse_double(t.substr(1, comma - 1), out.lo) && parse_double(t.substr(comma + 1, t.size() - comma - 2), out.hi) &&
         out.lo <= out.hi;
}

bool is_boolean(const std::string& op) {
  return op == "subset" || op == "isMember" || op == "precedes" || op == "strictPrecedes" || op == "isCommonInterval";
}

int arity(const std::string& op) {
  for (const char* one : {"neg", "recip", "sqrt", "exp", "log", "abs", "isCommonInterval"})
    if (op == one) return 1;
  return 2;
}

// Every line must parse: a malformed one is a failure, not a skip.
std::vector<Case> load() {
  std::vector<Case> cases;
  std::ifstream in(vectors_path());
  EXPECT_TRUE(in.good()) << "cannot read " << vectors_path();
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string t; words >> t;) w.push_back(t);
    Case c;
    const auto eq = std::find(w.begin(), w.end(), "=");
    const auto at = std::find(w.begin(), w.end(), "@");
    bool ok = !w.empty() && eq != w.end() && at != w.end() && at == eq + 2 && at + 2 == w.end();
    if (ok) {
      c.op = w[0];
      c.args.assign(w.begin() + 1, eq);
      c.expected = *(eq + 1);
      c.where = *(at + 1) + " (line " + std::to_string(n) + ")";
      ok = std::find(std::begin(kOperations), std::end(kOperations), c.op) != std::end(kOperations) &&
           static_cast<int>(c.args.size()) == arity(c.op);
      for (std::size_t i = 0; ok && i < c.args.size(); ++i) {
        Interval x;
        double d = 0;
        ok = (c.op == "isMember" && i == 0) ? parse_double(c.args[i], d) : parse_interval(c.args[i], x);
      }
      Interval e;
      if (ok) ok = is_boolean(c.op) ? (c.expected == "true" || c.expected == "false") : parse_interval(c.expected, e);
    }
    EXPECT_TRUE(ok) << vectors_path() << ":" << n << ": malformed line: " << line;
    if (ok) cases.push_back(std::move(c));
  }
  return cases;
}

Interval interval(const std::string& t) {
  Interval x;
  parse_interval(t, x);
  return x;
}

// ---------------------------------------------------------------------------------------
// The two types behind one interface.

template <class I>
struct Kind;

template <>
struct Kind<DoubleInterval> {
  using I = DoubleInterval;
  static constexpr const char* name = "interval:double";
  static I make(const Interval& x) { return x.empty ? I::nan_interval() : I(x.lo, x.hi); }
  static bool inverted(const I& r) { return r.lower() > r.upper(); }
  static void ends(const I& r, double& lo, double& hi) {
    lo = r.lower();
    hi = r.upper();
  }
  static bool contains_point(const I& x, double m) { return x.contains(m); }
  static std::string text(const I& r) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "[%a, %a]", r.lower(), r.upper());
    return buf;
  }
};

template <>
struct Kind<Mpfi> {
  using I = Mpfi;
  static constexpr const char* name = "mpfi:53";
  static Mpfr exact(double d) {
    Mpfr r(53);
    mpfr_set_d(r.get(), d, MPFR_RNDN);  // exact
    return r;
  }
  static I make(const Interval& x) {
    if (!x.empty) return I(exact(x.lo), exact(x.hi));
    I r(53);
    mpfr_set_nan(&r.get()->left);
    mpfr_set_nan(&r.get()->right);
    return r;
  }
  static bool inverted(const I& r) { return mpfr_greater_p(&r.get()->left, &r.get()->right); }
  // Outward to double (the tightest double interval around the 53-bit one).
  static void ends(const I& r, double& lo, double& hi) {
    lo = mpfr_get_d(&r.get()->left, MPFR_RNDD);
    hi = mpfr_get_d(&r.get()->right, MPFR_RNDU);
  }
  static bool contains_point(const I& x, double m) { return x.contains(exact(m)); }
  static std::string text(const I& r) {
    char buf[160];
    mpfr_snprintf(buf, sizeof buf, "[%Ra, %Ra]", &r.get()->left, &r.get()->right);
    return buf;
  }
};

template <class I>
I evaluate(const std::string& op, const std::vector<I>& x) {
  if (op == "add") return x[0] + x[1];
  if (op == "sub") return x[0] - x[1];
  if (op == "mul") return x[0] * x[1];
  if (op == "div") return x[0] / x[1];
  if (op == "neg") return -x[0];
  if (op == "recip") return 1L / x[0];
  if (op == "sqrt") return sqrt(x[0]);
  if (op == "exp") return exp(x[0]);
  if (op == "log") return log(x[0]);
  if (op == "abs") return abs(x[0]);
  if (op == "convexHull") return hull(x[0], x[1]);
  if (op == "intersection") return intersect(x[0], x[1]);
  ADD_FAILURE() << "no interval operation " << op;
  return x[0];
}

// Where a type documents that it gives no finite enclosure (NaN, or for Mpfi an unbounded
// interval) for valid operands although IEEE 1788 has a bounded or empty result
// (interval_double.hpp "Invalid intervals", mpfi.hpp); "" when it does not.
template <class I>
std::string documented_decline(const std::string& op, const std::vector<Interval>& x) {
  const bool is_double = std::is_same_v<I, DoubleInterval>;
  auto holds_zero = [](const Interval& y) { return y.lo <= 0 && y.hi >= 0; };
  auto unbounded = [](const Interval& y) { return std::isinf(y.lo) || std::isinf(y.hi); };
  auto zero_end = [](const Interval& y) { return y.lo == 0 || y.hi == 0; };
  if (op == "div" && holds_zero(x[1])) return is_double ? "a divisor holding 0: NaN" : "a divisor holding 0: unbounded";
  if (op == "recip" && holds_zero(x[0])) return is_double ? "a divisor holding 0: NaN" : "a divisor holding 0: unbounded";
  if (is_double && op == "mul" && ((unbounded(x[0]) && zero_end(x[1])) || (unbounded(x[1]) && zero_end(x[0]))))
    return "a corner 0 * inf: NaN";
  if (op == "log" && x[0].lo < 0) return "log of an interval reaching below 0: NaN";
  if (!is_double && op == "sqrt" && x[0].lo < 0) return "mpfi_sqrt of an interval reaching below 0: NaN";
  return "";
}

struct Tally {
  long checked = 0, tight = 0, loose = 0, nan_for_empty = 0, declined = 0, skipped = 0;
};

template <class I>
void run(const char* test_name) {
  using K = Kind<I>;
  using Tr = ScalarTraits<I>;
  const std::vector<Case> cases = load();
  std::map<std::string, Tally> by_op;
  std::map<std::string, long> declined, skipped;
  long failures = 0;
  auto fail = [&](const Case& c, const std::string& what, const std::string& result = "") {
    if (++failures <= 30) {
      std::string args;
      for (const auto& a : c.args) {
        args += ' ';
        args += a;
      }
      ADD_FAILURE() << K::name << ": " << c.op << args << " = " << c.expected << " @ " << c.where << ": " << what << result;
    }
  };
  for (const Case& c : cases) {
    Tally& t = by_op[c.op];
    // Operands.
    std::vector<Interval> xs;
    std::vector<I> ys;
    double member = 0;
    bool any_empty = false;
    for (std::size_t i = 0; i < c.args.size(); ++i) {
      if (c.op == "isMember" && i == 0) {
        parse_double(c.args[0], member);
        continue;
      }
      xs.push_back(interval(c.args[i]));
      any_empty = any_empty || xs.back().empty;
      ys.push_back(K::make(xs.back()));
    }

    if (is_boolean(c.op)) {
      const bool expected = c.expected == "true";
      if (c.op == "isMember" && !std::isfinite(member)) {
        ++t.skipped;
        ++skipped["isMember of +-inf or NaN (not a real number)"];
        continue;
      }
      ++t.checked;
      bool ok = true;
      if (c.op == "isCommonInterval") {
        ok = Tr::is_finite(ys[0]) == expected;
      } else if (any_empty) {
        // Invalid operands: contains is false, the order predicates are invalid.
        if (c.op == "subset") ok = !ys[1].contains(ys[0]);
        if (c.op == "isMember") ok = !K::contains_point(ys[0], member);
        if (c.op == "precedes") ok = Tr::le(ys[0], ys[1]) == Truth::invalid && Tr::lt(ys[1], ys[0]) == Truth::invalid;
        if (c.op == "strictPrecedes") ok = Tr::lt(ys[0], ys[1]) == Truth::invalid && Tr::le(ys[1], ys[0]) == Truth::invalid;
        if (ok) ++t.nan_for_empty;
      } else if (c.op == "subset") {
        ok = ys[1].contains(ys[0]) == expected;
      } else if (c.op == "isMember") {
        ok = K::contains_point(ys[0], member) == expected;
      } else if (c.op == "precedes") {
        ok = (Tr::le(ys[0], ys[1]) == Truth::yes) == expected && (Tr::lt(ys[1], ys[0]) == Truth::no) == expected;
      } else if (c.op == "strictPrecedes") {
        ok = (Tr::lt(ys[0], ys[1]) == Truth::yes) == expected && (Tr::le(ys[1], ys[0]) == Truth::no) == expected;
      }
      if (ok) ++t.tight;
      else fail(c, "wrong answer");
      continue;
    }

    ++t.checked;
    const I r = evaluate(c.op, ys);
    const Interval e = interval(c.expected);
    const bool r_nan = r.has_nan();
    const std::string why = documented_decline<I>(c.op, xs);
    auto decline = [&] {
      ++t.declined;
      ++declined[c.op + ": " + why];
    };
    if (any_empty) {
      if (r_nan) ++t.nan_for_empty, ++t.tight;
      else fail(c, "an invalid (NaN) operand gave the valid ", K::text(r));
      continue;
    }
    if (e.empty) {
      if (r_nan) ++t.nan_for_empty, ++t.tight;
      else if (K::inverted(r)) fail(c, "an empty result not flagged: inverted ", K::text(r));
      else if (!why.empty() && !Tr::is_finite(r)) decline();
      else fail(c, "an empty result given as ", K::text(r) + " (the convention is NaN)");
      continue;
    }
    if (r_nan) {
      if (why.empty()) fail(c, "NaN where an enclosure was due: ", K::text(r));
      else decline();
      continue;
    }
    double lo = 0, hi = 0;
    K::ends(r, lo, hi);
    if (K::inverted(r)) {
      fail(c, "inverted result ", K::text(r));
    } else if (!(lo <= e.lo && hi >= e.hi)) {
      fail(c, "UNSOUND: ", K::text(r) + " does not enclose the expected interval");
    } else if (lo == e.lo && hi == e.hi) {
      ++t.tight;
    } else if (!why.empty() && !Tr::is_finite(r)) {
      decline();  // sound, and no finite enclosure claimed
    } else {
      ++t.loose;
      fail(c, "not tight: ", K::text(r));
    }
  }

  // Report.
  Tally all;
  std::printf("%s, %s: ITF1788 cases from %s\n", test_name, K::name, vectors_path().c_str());
  std::printf("  %-17s %8s %8s %8s %8s %8s %8s\n", "operation", "checked", "tight", "loose", "NaN=empty", "declined", "skipped");
  for (const char* op : kOperations) {
    const Tally& t = by_op[op];
    std::printf("  %-17s %8ld %8ld %8ld %8ld %8ld %8ld\n", op, t.checked, t.tight, t.loose, t.nan_for_empty, t.declined, t.skipped);
    all.checked += t.checked, all.tight += t.tight, all.loose += t.loose, all.nan_for_empty += t.nan_for_empty;
    all.declined += t.declined, all.skipped += t.skipped;
    EXPECT_GE(t.checked, kMinPerOperation) << op << ": too few cases (a broken converter or parser?)";
  }
  std::printf("  %-17s %8ld %8ld %8ld %8ld %8ld %8ld\n", "all", all.checked, all.tight, all.loose, all.nan_for_empty, all.declined, all.skipped);
  for (const auto& [why, n] : declined) std::printf("  declined (documented, no finite enclosure): %ld  %s\n", n, why.c_str());
  for (const auto& [why, n] : skipped) std::printf("  skipped: %ld  %s\n", n, why.c_str());
  if (failures > 30) std::printf("  ... %ld failures in all (the first 30 reported)\n", failures);
  EXPECT_GE(all.checked, kMinCases) << "too few ITF1788 cases checked (a broken converter or parser?)";
  EXPECT_EQ(failures, 0);
}

TEST(ITF1788, DoubleInterval) { run<DoubleInterval>("ITF1788.DoubleInterval"); }
TEST(ITF1788, Mpfi53) { run<Mpfi>("ITF1788.Mpfi53"); }

}  // namespace
}  // namespace bouncer
