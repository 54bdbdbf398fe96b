// Decimal: the exact rational value of a decimal string such as "28.82" or "1e-9".
//
// Parameters are exact decimals. Range checks (eps <= 1, v0 >= wall velocity, ...) are
// made on the exact rational, so "1.0000000000000000000000001" is rejected for eps even
// though it rounds to 1 in double. Conversion to a scalar type goes through the original
// text (correct rounding per type; an enclosure for intervals), never through a double.
#pragma once

#include <gmpxx.h>

#include <optional>
#include <string>
#include <string_view>

namespace bouncer {

class Decimal {
 public:
  // Accepts [+-]digits[.digits][(e|E)[+-]digits] (digits before or after the point may be
  // empty, not both). Anything else (inf, nan, hex, spaces) gives nullopt.
  static std::optional<Decimal> parse(std::string_view text);
  static Decimal from_int(long n);

  const std::string& text() const { return text_; }
  const mpq_class& value() const { return value_; }
  double approx() const { return value_.get_d(); }

  friend bool operator<(const Decimal& x, const Decimal& y) { return x.value_ < y.value_; }
  friend bool operator<=(const Decimal& x, const Decimal& y) { return x.value_ <= y.value_; }
  friend bool operator>(const Decimal& x, const Decimal& y) { return x.value_ > y.value_; }
  friend bool operator>=(const Decimal& x, const Decimal& y) { return x.value_ >= y.value_; }
  friend bool operator==(const Decimal& x, const Decimal& y) { return x.value_ == y.value_; }

 private:
  std::string text_;
  mpq_class value_;
};

// Exact decimal text of a rational whose denominator has only the prime factors 2 and 5
// (every bisection point of a decimal interval), else "num/den".
std::string exact_decimal(const mpq_class& x);

}  // namespace bouncer
