#include "bouncer/scalar/decimal.hpp"

#include <cctype>

namespace bouncer {

std::optional<Decimal> Decimal::parse(std::string_view text) {
  size_t i = 0;
  const size_t n = text.size();
  bool negative = false;
  if (i < n && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
  std::string digits;
  long scale = 0;  // value = digits * 10^(scale)
  size_t int_digits = 0, frac_digits = 0;
  while (i < n && std::isdigit(static_cast<unsigned char>(text[i]))) { digits += text[i++]; ++int_digits; }
  if (i < n && text[i] == '.') {
    ++i;
    while (i < n && std::isdigit(static_cast<unsigned char>(text[i]))) { digits += text[i++]; ++frac_digits; }
  }
  if (int_digits + frac_digits == 0) return std::nullopt;
  scale = -static_cast<long>(frac_digits);
  if (i < n && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool eneg = false;
    if (i < n && (text[i] == '+' || text[i] == '-')) eneg = text[i++] == '-';
    std::string ed;
    while (i < n && std::isdigit(static_cast<unsigned char>(text[i]))) ed += text[i++];
    if (ed.empty() || ed.size() > 6) return std::nullopt;  // |exponent| < 10^6
    const long e = std::stol(ed);
    scale += eneg ? -e : e;
  }
  if (i != n) return std::nullopt;
  Decimal d;
  d.text_ = std::string(text);
  mpz_class num(digits, 10);
  if (negative) num = -num;
  mpz_class pow10;
  mpz_ui_pow_ui(pow10.get_mpz_t(), 10, static_cast<unsigned long>(scale < 0 ? -scale : scale));
  if (scale >= 0) {
    d.value_ = mpq_class(num * pow10);
  } else {
    d.value_ = mpq_class(num, pow10);
    d.value_.canonicalize();
  }
  return d;
}

Decimal Decimal::from_int(long n) { return *parse(std::to_string(n)); }

std::string exact_decimal(const mpq_class& x) {
  mpz_class den = x.get_den();
  long twos = 0, fives = 0;
  while (mpz_divisible_ui_p(den.get_mpz_t(), 2)) { den /= 2; ++twos; }
  while (mpz_divisible_ui_p(den.get_mpz_t(), 5)) { den /= 5; ++fives; }
  if (den != 1) return x.get_str();
  const long k = std::max(twos, fives);
  mpz_class scale;
  mpz_ui_pow_ui(scale.get_mpz_t(), 10, static_cast<unsigned long>(k));
  mpz_class n = x.get_num() * scale / x.get_den();  // exact
  std::string sign;
  if (n < 0) { sign = "-"; n = -n; }
  std::string digits = n.get_str();
  if (k == 0) return sign + digits;
  if (static_cast<long>(digits.size()) <= k) digits = std::string(k - digits.size() + 1, '0') + digits;
  std::string out = digits.substr(0, digits.size() - k) + "." + digits.substr(digits.size() - k);
  while (out.back() == '0') out.pop_back();
  if (out.back() == '.') out.pop_back();
  return sign + out;
}

}  // namespace bouncer
