#include "bouncer/analysis/end_estimate.hpp"

#include <cmath>
#include <stdexcept>

namespace bouncer {

const char* name(EndEstimate::Kind k) {
  switch (k) {
    case EndEstimate::Kind::not_estimated: return "not_estimated";
    case EndEstimate::Kind::given: return "given";
    case EndEstimate::Kind::estimate: return "estimate";
  }
  return "?";
}

namespace {

mpq_class pow10q(long e) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(e < 0 ? -e : e));
  return e < 0 ? mpq_class(mpz_class(1), p) : mpq_class(p);
}

// m * 10^k with exactly max(0, -k) decimals (trailing zeros kept: they are backed digits).
std::string fixed_text(const mpz_class& m, long k) {
  std::string s = mpz_class(abs(m)).get_str();
  if (k >= 0) {
    if (m != 0) s.append(static_cast<size_t>(k), '0');
  } else {
    const size_t dec = static_cast<size_t>(-k);
    if (s.size() <= dec) s = std::string(dec + 1 - s.size(), '0') + s;
    s = s.substr(0, s.size() - dec) + "." + s.substr(s.size() - dec);
  }
  return (m < 0 ? "-" : "") + s;
}

mpz_class floor_q(const mpq_class& x) {
  mpz_class r;
  mpz_fdiv_q(r.get_mpz_t(), x.get_num_mpz_t(), x.get_den_mpz_t());
  return r;
}
mpz_class ceil_q(const mpq_class& x) {
  mpz_class r;
  mpz_cdiv_q(r.get_mpz_t(), x.get_num_mpz_t(), x.get_den_mpz_t());
  return r;
}

}  // namespace

BackedDigits backed_digits(const mpq_class& center, double radius) {
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("backed_digits: the radius must be positive and finite");
  const mpq_class r(radius);  // exact
  long k = static_cast<long>(std::floor(std::log10(radius)));
  for (;; ++k) {
    const mpq_class grain = pow10q(k);
    const mpz_class m = floor_q(center / grain + mpq_class(1, 2));  // halves up
    const mpq_class rounding = abs(mpq_class(m) * grain - center);
    const mpz_class u = ceil_q((r + rounding) / grain);
    if (u >= 10) continue;  // one significant digit of the radius: the next place up
    BackedDigits out;
    out.value = fixed_text(m, k);
    out.plus_minus = k == 0 ? u.get_str() : u.get_str() + "e" + std::to_string(k);
    out.digits = m == 0 ? 0 : static_cast<int>(mpz_class(abs(m)).get_str().size());
    out.lo = fixed_text(floor_q((center - r) / grain), k);
    out.hi = fixed_text(ceil_q((center + r) / grain), k);
    return out;
  }
}

std::string end_value_text(const EndEstimate& e, const std::string& computed) {
  switch (e.kind) {
    case EndEstimate::Kind::estimate: {
      const BackedDigits d = backed_digits(e.center, e.radius);
      return d.value + " ± " + d.plus_minus + " (estimate)";
    }
    case EndEstimate::Kind::given: return computed;
    default: return computed + " (accuracy not estimated)";
  }
}

}  // namespace bouncer
