// Independent truth for scalar tests: floating values as exact GMP rationals, decimals as
// exact rationals (built here, without the library's Decimal), and correct rounding to p
// bits computed with integers.
//
// Every floating value is converted back to a rational exactly (mpq from double; through
// MPFR for long double; a split into two 64-bit integers for __float128).
#pragma once

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <quadmath.h>

#include <cstdlib>
#include <string>

#include "bouncer/scalar/traits.hpp"

namespace bouncer {

// ---------------------------------------------------------------------------------------
// Exact rationals of floating values, and correct rounding computed with integers.

inline mpq_class exact(double x) { return mpq_class(x); }

inline mpq_class exact(const Mpfr& x) {
  mpq_class q;
  mpfr_get_q(q.get_mpq_t(), x.get());
  return q;
}

inline mpq_class exact(long double x) {
  Mpfr m(64);
  EXPECT_EQ(mpfr_set_ld(m.get(), x, MPFR_RNDN), 0);  // exact at 64 bits
  return exact(m);
}

inline mpq_class exact(const Quad& x) {
  // x = m * 2^(e - 113) with an integer m < 2^113, split into two 64-bit halves.
  const __float128 v = x.backend().value();
  if (v == 0) return 0;
  int e = 0;
  const __float128 frac = frexpq(fabsq(v), &e);
  const __float128 m = ldexpq(frac, 113);
  const __float128 hi = floorq(ldexpq(m, -64));
  const __float128 lo = m - ldexpq(hi, 64);
  mpz_class z(static_cast<unsigned long>(hi));
  z <<= 64;
  z += mpz_class(static_cast<unsigned long>(lo));
  mpq_class q(z);
  mpz_class p2(1);
  if (e - 113 >= 0) { p2 <<= static_cast<unsigned>(e - 113); q *= p2; }
  else { p2 <<= static_cast<unsigned>(113 - e); q /= p2; }
  q.canonicalize();
  return v < 0 ? mpq_class(-q) : q;
}

inline mpq_class exact(const DoubleDouble& x) { return mpq_class(x.hi()) + mpq_class(x.lo()); }

inline mpq_class inv_pow2(long k) { return mpq_class(mpz_class(1), mpz_class(1) << static_cast<unsigned>(k)); }

// The exact value of a decimal string, built without Decimal: [-]digits[.digits][e[-]n].
inline mpq_class rational_of(const std::string& s) {
  std::string digits;
  long scale = 0;
  size_t i = 0;
  bool neg = false;
  if (s[i] == '-' || s[i] == '+') neg = s[i++] == '-';
  bool frac = false;
  for (; i < s.size() && s[i] != 'e' && s[i] != 'E'; ++i) {
    if (s[i] == '.') { frac = true; continue; }
    digits += s[i];
    if (frac) --scale;
  }
  if (i < s.size()) scale += std::stol(s.substr(i + 1));
  mpq_class q(mpz_class(digits, 10));
  mpz_class p10;
  mpz_ui_pow_ui(p10.get_mpz_t(), 10, static_cast<unsigned long>(std::labs(scale)));
  if (scale >= 0) q *= p10; else q /= p10;
  q.canonicalize();
  return neg ? mpq_class(-q) : q;
}

// q rounded to the nearest p-bit binary number, ties to even (no exponent range limits).
inline mpq_class round_to_bits(const mpq_class& q, long p) {
  if (q == 0) return q;
  const mpq_class mag = abs(q);
  // e with 2^(e-1) <= mag < 2^e
  long e = static_cast<long>(mpz_sizeinbase(mag.get_num_mpz_t(), 2)) -
           static_cast<long>(mpz_sizeinbase(mag.get_den_mpz_t(), 2));
  auto pow2 = [](long k) {
    mpq_class r(1);
    mpz_class t(1);
    mpz_mul_2exp(t.get_mpz_t(), t.get_mpz_t(), static_cast<unsigned long>(std::labs(k)));
    if (k >= 0) r = mpq_class(t); else r = mpq_class(mpz_class(1), t);
    r.canonicalize();
    return r;
  };
  while (mag >= pow2(e)) ++e;
  while (mag < pow2(e - 1)) --e;
  const mpq_class scaled = mag * pow2(p - e);  // in [2^(p-1), 2^p)
  mpz_class m = scaled.get_num() / scaled.get_den();  // floor
  const mpq_class rest = scaled - mpq_class(m);
  if (rest > mpq_class(1, 2) || (rest == mpq_class(1, 2) && mpz_odd_p(m.get_mpz_t()))) m += 1;
  mpq_class r = mpq_class(m) * pow2(e - p);
  r.canonicalize();
  return q < 0 ? mpq_class(-r) : r;
}

}  // namespace bouncer
