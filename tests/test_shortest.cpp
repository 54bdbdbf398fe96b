// bouncer::shortest_chars against libstdc++'s std::to_chars (Ryu's digits: an independent
// implementation of the same specification), byte for byte, and against strtod (the text
// reads back to the same double).
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "bouncer/scalar/shortest.hpp"
#include "bouncer/scalar/traits.hpp"

namespace {

std::string ours(double x) {
  char buf[bouncer::kShortestChars];
  return std::string(buf, bouncer::shortest_chars(buf, x));
}

std::string standard(double x) {
  char buf[64];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
}

double from_bits(std::uint64_t b) {
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

// Counts mismatches (reporting the first few) so that one test covers many values.
class Checker {
 public:
  void operator()(double x) {
    ++checked_;
    const std::string a = ours(x);
    const std::string b = standard(x);
    if (a != b) {
      if (++mismatches_ <= 5) ADD_FAILURE() << "shortest_chars wrote '" << a << "', std::to_chars '" << b << "'";
      return;
    }
    if (std::isfinite(x)) {
      const double back = std::strtod(a.c_str(), nullptr);
      if (std::memcmp(&back, &x, sizeof x) != 0 && ++mismatches_ <= 5)
        ADD_FAILURE() << "'" << a << "' reads back as another double";
    }
  }
  ~Checker() { EXPECT_EQ(mismatches_, 0) << "of " << checked_ << " values"; }

 private:
  long checked_ = 0;
  long mismatches_ = 0;
};

TEST(Shortest, SpecialValuesAreStdToChars) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ours(0.0), "0");
  EXPECT_EQ(ours(-0.0), "-0");
  EXPECT_EQ(ours(inf), "inf");
  EXPECT_EQ(ours(-inf), "-inf");
  EXPECT_EQ(ours(std::numeric_limits<double>::quiet_NaN()), standard(std::numeric_limits<double>::quiet_NaN()));
}

// Hand-checked texts: each layout (integer, ddd.ddd, 0.0ddd, scientific of both signs and
// three exponent digits) and the shortest digits of a few famous values.
TEST(Shortest, HandCheckedTexts) {
  EXPECT_EQ(ours(1.0), "1");
  EXPECT_EQ(ours(-2.5), "-2.5");
  EXPECT_EQ(ours(0.1), "0.1");
  EXPECT_EQ(ours(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(ours(10.5), "10.5");
  EXPECT_EQ(ours(28.82), "28.82");
  EXPECT_EQ(ours(0.001), "0.001");
  EXPECT_EQ(ours(0.0001), "1e-04");  // shorter than 0.0001; 0.001 ties, and fixed wins
  EXPECT_EQ(ours(0.00001), "1e-05");
  EXPECT_EQ(ours(0.00012), "0.00012");
  EXPECT_EQ(ours(1234.5678), "1234.5678");
  EXPECT_EQ(ours(1e21), "1e+21");
  EXPECT_EQ(ours(123456.0), "123456");
  EXPECT_EQ(ours(1e100), "1e+100");
  EXPECT_EQ(ours(-1.5e-300), "-1.5e-300");
  EXPECT_EQ(ours(5e-324), "5e-324");
  EXPECT_EQ(ours(std::numeric_limits<double>::max()), "1.7976931348623157e+308");
  EXPECT_EQ(ours(std::numeric_limits<double>::min()), "2.2250738585072014e-308");
  EXPECT_EQ(ours(9007199254740993.0), "9007199254740992");  // 2^53 + 1 rounds to 2^53
}

TEST(Shortest, RandomBitPatternsMatchStdToChars) {
  std::mt19937_64 g(20261128);
  Checker check;
  for (int i = 0; i < 1000000; ++i) check(from_bits(g()));
}

// The values an orbit writes: phases in [0, 1), velocities and times of a few units, and
// values with few digits (decimal inputs, rounded grids).
TEST(Shortest, OrbitLikeValuesMatchStdToChars) {
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> u(0, 1);
  Checker check;
  for (int i = 0; i < 300000; ++i) {
    check(u(g));
    check(40 * u(g) - 10);
    check(std::ldexp(u(g), static_cast<int>(g() % 120) - 60));
    check(std::round(u(g) * 1e6) / 1e3);
    check(-std::round(u(g) * 1e4) / 1e8);
  }
}

// Powers of two, decades and their neighbours, integers with trailing zeros (to_chars' own
// rule), around 2^53 and the subnormal range.
TEST(Shortest, BoundariesMatchStdToChars) {
  Checker check;
  for (int k = -1074; k <= 1023; ++k) {
    const double p = std::ldexp(1.0, k);
    for (double x : {p, -p, std::nextafter(p, 0.0), std::nextafter(p, HUGE_VAL), 3 * p, 5 * p}) check(x);
  }
  for (int k = -325; k <= 309; ++k) {
    const double p = std::strtod(("1e" + std::to_string(k)).c_str(), nullptr);  // 0 or inf at the ends
    for (double x : {p, std::nextafter(p, 0.0), std::nextafter(p, HUGE_VAL), 2 * p, 5 * p, 1.5 * p, 0.999 * p}) check(x);
  }
  for (std::int64_t k = 0; k < 20000; ++k) {
    check(static_cast<double>(k));
    check(static_cast<double>(k) * 1000);
    check(static_cast<double>((std::int64_t{1} << 53) - 10000 + k));
    check(static_cast<double>((std::int64_t{1} << 60) + k * 4096));
  }
  for (int digits = 1; digits <= 17; ++digits)
    for (int e = -30; e <= 30; ++e) check(std::strtod((std::string("1234567890123456789").substr(0, digits) + "e" + std::to_string(e)).c_str(), nullptr));
  check(std::numeric_limits<double>::denorm_min());
  check(std::nextafter(std::numeric_limits<double>::min(), 0.0));
}

// ScalarTraits<double>::to_string, which every double bouncer writes goes through, is it.
TEST(Shortest, DoubleToStringIsShortestChars) {
  for (double x : {0.0, 1.0 / 3, 28.82, 1e-7, -6.02214076e23}) EXPECT_EQ(bouncer::ScalarTraits<double>::to_string(x), standard(x));
}

}  // namespace
