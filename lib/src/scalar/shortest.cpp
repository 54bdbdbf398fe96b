#include "bouncer/scalar/shortest.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <dragonbox/dragonbox.h>

namespace bouncer {

namespace {

constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

[[gnu::always_inline]] inline void two(char* o, unsigned x) { std::memcpy(o, kPairs + 2 * x, 2); }

// The 8 digits of x < 10^8 (leading zeros included) by multiplications, not divisions: y is
// x / 10^6 in 32.32 fixed point, rounded up by less than 2^32 / 10^6, so that its integer
// part is the first two digits and each further pair is the integer part of 100 times the
// fraction. With M = ceil(2^48 / 10^6) = 281474977, x M / 2^16 exceeds x 2^32 / 10^6 by
// x (M - 2^48 / 10^6) / 2^16 < 442 for x < 10^8; flooring it and adding 1 puts y in
// [x 2^32 / 10^6, x 2^32 / 10^6 + 443), inside the window of width 2^32 / 10^6 > 4294 that
// yields the digits of x (checked for every x < 10^8 when this was written).
[[gnu::always_inline]] inline void eight(char* o, unsigned x) {
  std::uint64_t y = ((std::uint64_t{x} * 281474977U) >> 16) + 1;
  two(o, static_cast<unsigned>(y >> 32));
  y = (y & 0xFFFFFFFFU) * 100;
  two(o + 2, static_cast<unsigned>(y >> 32));
  y = (y & 0xFFFFFFFFU) * 100;
  two(o + 4, static_cast<unsigned>(y >> 32));
  y = (y & 0xFFFFFFFFU) * 100;
  two(o + 6, static_cast<unsigned>(y >> 32));
}

// 10^k, k = 0..18.
constexpr std::uint64_t kPowers[] = {
    1ULL, 10ULL, 100ULL, 1000ULL, 10000ULL,
    100000ULL, 1000000ULL, 10000000ULL, 100000000ULL, 1000000000ULL,
    10000000000ULL, 100000000000ULL, 1000000000000ULL, 10000000000000ULL, 100000000000000ULL,
    1000000000000000ULL, 10000000000000000ULL, 100000000000000000ULL, 1000000000000000000ULL};

// x < 10^17 as 17 digits with leading zeros, in two independent chains (Dragonbox's
// significand of a double has at most 17 digits).
[[gnu::always_inline]] inline void seventeen(char* o, std::uint64_t x) {
  const std::uint64_t hi = x / 100000000;
  const auto lo = static_cast<unsigned>(x - hi * 100000000);
  const auto h = static_cast<unsigned>(hi);
  o[0] = static_cast<char>('0' + h / 100000000);
  eight(o + 1, h % 100000000);
  eight(o + 9, lo);
}

// The number of decimal digits of x > 0 (at most 17 here).
int digit_count(std::uint64_t x) {
  // With 2^(bits-1) <= x < 2^bits, x has n or n + 1 digits for n = floor(bits log10 2)
  // (1233 / 2^12 for log10 2), n + 1 where x reaches 10^n.
  const int bits = 64 - __builtin_clzll(x);
  const int n = (bits * 1233) >> 12;
  return n + (x >= kPowers[n] ? 1 : 0);
}

char* standard(char* out, double x) { return std::to_chars(out, out + kShortestChars, x).ptr; }

}  // namespace

char* shortest_chars(char* out, double x) {
  if (!std::isfinite(x) || x == 0) return standard(out, x);
  const auto d = jkj::dragonbox::to_decimal(x);  // x = +-significand * 10^exponent, shortest
  const int e = d.exponent;
  const int n = digit_count(d.significand);
  const int sci_exp = e + n - 1;  // x = d.ddd * 10^sci_exp
  const int abs_exp = sci_exp < 0 ? -sci_exp : sci_exp;
  const int scientific = n + (n > 1 ? 1 : 0) + 2 + (abs_exp >= 100 ? 3 : 2);
  const int fixed = e >= 0 ? n + e : sci_exp >= 0 ? n + 1 : n + 1 - sci_exp;
  // The digits first, then zeros to 17 digits: written in place at their final position
  // (through a buffer, the copies of freshly stored digits stalled on store forwarding).
  const std::uint64_t digits = d.significand * kPowers[17 - n];
  char* p = out;
  if (d.is_negative) *p++ = '-';
  if (fixed <= scientific) {
    if (e > 0) return standard(out, x);  // trailing integer zeros: to_chars' own rule
    if (e == 0) {
      seventeen(p, digits);
      return p + n;
    }
    if (sci_exp >= 0) {  // ddd.ddd: sci_exp + 1 digits before the point
      const int before = sci_exp + 1;
      seventeen(p + 1, digits);
      for (int i = 0; i < before; ++i) p[i] = p[i + 1];
      p[before] = '.';
      return p + n + 1;
    }
    // 0.000ddd: -sci_exp - 1 zeros after the point (at most 3: fixed is chosen only while it
    // is no longer than scientific, n + 5 characters or 5 for one digit)
    std::memcpy(p, "0.000000", 8);
    p += 1 - sci_exp;
    seventeen(p, digits);
    return p + n;
  }
  seventeen(p + 1, digits);
  p[0] = p[1];
  p[1] = '.';
  p += n > 1 ? n + 1 : 1;
  *p++ = 'e';
  *p++ = sci_exp < 0 ? '-' : '+';
  int rest = abs_exp;
  if (rest >= 100) {
    *p++ = static_cast<char>('0' + rest / 100);
    rest %= 100;
  }
  two(p, static_cast<unsigned>(rest));
  return p + 2;
}

}  // namespace bouncer
