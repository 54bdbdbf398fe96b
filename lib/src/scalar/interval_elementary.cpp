// exp and log of a DoubleInterval: the fast path in double arithmetic and the MPFR fallback
// (the argument: scalar/interval_elementary.hpp).
#include "bouncer/scalar/interval_elementary.hpp"

#include <mpfr.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "bouncer/scalar/error_free.hpp"

namespace bouncer {

namespace interval_elementary {

namespace {

using I = DoubleInterval;
using interval_double_detail::add_down;
using interval_double_detail::add_up;
using interval_double_detail::mul_up;

constexpr int kExpN = 256;        // exp's table: 2^(j/256), j = 0..255
constexpr int kLogLow = -75;      // log's table: c_j = 1 + j/256, j = -75..106
constexpr int kLogHigh = 106;
constexpr int kLogN = kLogHigh - kLogLow + 1;
constexpr long kTableBits = 200;  // MPFR's precision for the tables' enclosures

I point(double x) { return {x, x}; }

// A double cut to its leading `bits` significant bits (toward 0): exact products with small
// integers.
double cut(double x, int bits) {
  const auto b = std::bit_cast<std::uint64_t>(x);
  const std::uint64_t mask = ~((std::uint64_t{1} << (52 - (bits - 1))) - 1);
  return std::bit_cast<double>(b & mask);
}

struct Tables {
  double exp_hi[kExpN];  // RN(2^(j/256))
  I exp_lo[kExpN];       // encloses 2^(j/256) - exp_hi[j]
  double log_inv[kLogN];  // RN(1 / c_j)
  double log_hi[kLogN];   // RN(-log(log_inv[j]))
  I log_lo[kLogN];        // encloses -log(log_inv[j]) - log_hi[j]
  double c1 = 0;          // ln2/256 cut to 33 bits
  I c2;                   // encloses ln2/256 - c1
  double l1 = 0;          // ln2 cut to 41 bits
  I l2;                   // encloses ln2 - l1
  double inv_ln2_256 = 0;  // about 256/ln2 (any value: only picks M)
  I exp_coef[6];           // encloses 1/k! (k = 2..5)
  I log_coef[9];           // encloses (-1)^(k+1)/k (k = 2..8)
  double exp_rem = 0;      // RU(1/700)
  double log_rem = 0;      // 1/8

  Tables() {
    mpfr_t lo, hi, t;
    mpfr_inits2(kTableBits, lo, hi, t, static_cast<mpfr_ptr>(nullptr));
    // The low part of an enclosure [lo, hi] of a value v relative to the double h near it:
    // [RD(lo - h), RU(hi - h)] (each subtraction and conversion directed).
    auto low_part = [&](double h) {
      mpfr_sub_d(t, lo, h, MPFR_RNDD);
      const double a = mpfr_get_d(t, MPFR_RNDD);
      mpfr_sub_d(t, hi, h, MPFR_RNDU);
      return I(a, mpfr_get_d(t, MPFR_RNDU));
    };
    // ln2 and ln2/256.
    mpfr_const_log2(lo, MPFR_RNDD);
    mpfr_const_log2(hi, MPFR_RNDU);
    l1 = cut(mpfr_get_d(lo, MPFR_RNDN), 41);
    l2 = low_part(l1);
    mpfr_div_2ui(lo, lo, 8, MPFR_RNDD);  // exact
    mpfr_div_2ui(hi, hi, 8, MPFR_RNDU);
    c1 = cut(mpfr_get_d(lo, MPFR_RNDN), 33);
    c2 = low_part(c1);
    inv_ln2_256 = 256 / std::log(2.0);
    // 2^(j/256).
    for (int j = 0; j < kExpN; ++j) {
      mpfr_set_si(t, j, MPFR_RNDN);
      mpfr_div_2ui(t, t, 8, MPFR_RNDN);  // exact
      mpfr_exp2(lo, t, MPFR_RNDD);
      mpfr_exp2(hi, t, MPFR_RNDU);
      exp_hi[j] = mpfr_get_d(lo, MPFR_RNDN);
      exp_lo[j] = low_part(exp_hi[j]);
    }
    // -log(inv_j), inv_j = RN(1 / (1 + j/256)).
    for (int j = kLogLow; j <= kLogHigh; ++j) {
      const int i = j - kLogLow;
      log_inv[i] = 1.0 / (1.0 + j / 256.0);  // 1 + j/256 exact; one division, RN
      mpfr_set_d(t, log_inv[i], MPFR_RNDN);   // exact
      mpfr_log(lo, t, MPFR_RNDU);
      mpfr_neg(lo, lo, MPFR_RNDN);  // -RU(log inv) = RD(-log inv)
      mpfr_log(hi, t, MPFR_RNDD);
      mpfr_neg(hi, hi, MPFR_RNDN);
      log_hi[i] = mpfr_get_d(lo, MPFR_RNDN);
      log_lo[i] = low_part(log_hi[i]);
    }
    mpfr_clears(lo, hi, t, static_cast<mpfr_ptr>(nullptr));
    long fact = 1;
    for (int k = 2; k <= 5; ++k) {
      fact *= k;
      exp_coef[k] = I(1L) / I(fact);
    }
    for (int k = 2; k <= 8; ++k) log_coef[k] = I(k % 2 == 0 ? -1L : 1L) / I(static_cast<long>(k));
    exp_rem = interval_double_detail::div_up(1.0, 700.0);
    log_rem = 0.125;
  }
};

const Tables& tables() {
  static const Tables t;
  return t;
}

// The directed rounding of s + W (W an enclosure of the rest) when W decides it: both ends of
// s + W round to the same double.
template <bool Up>
bool decide(double s, const I& w, double& out) {
  if (w.has_nan()) return false;
  const double a = Up ? add_up(s, w.lower()) : add_down(s, w.lower());
  const double b = Up ? add_up(s, w.upper()) : add_down(s, w.upper());
  if (a != b) return false;
  out = a;
  return true;
}

// exp(x) = 2^k (s + W) for |x| <= 708; false outside that range (or if rho fails its test).
bool exp_sum(double x, double& s, I& w, int& k) {
  if (!(std::fabs(x) <= 708.0)) return false;  // near overflow or underflow, inf, NaN: MPFR
  const Tables& t = tables();
  const double md = std::nearbyint(x * t.inv_ln2_256);  // |md| < 2^18
  const int m = static_cast<int>(md);
  k = m >> 8;  // floor(m / 256) (C++20: arithmetic shift)
  const int j = m - k * kExpN;
  // r = x - m ln2/256 in rh + RL: x - m c1 = rh + e0 exactly (m c1 exact, TwoSum).
  double rh, e0;
  error_free::two_sum(x, -(md * t.c1), rh, e0);
  const I rl = point(e0) - point(md) * t.c2;
  const I r = point(rh) + rl;
  const double rho = std::max(std::fabs(r.lower()), std::fabs(r.upper()));
  if (!(rho <= 0x1p-7)) return false;
  // P(r) = r^2 (1/2 + r (1/6 + r (1/24 + r/120))) + [-rho^6/700, rho^6/700].
  I p = t.exp_coef[5] * r + t.exp_coef[4];
  p = p * r + t.exp_coef[3];
  p = p * r + t.exp_coef[2];
  p = p * (r * r);
  const double rho3 = mul_up(mul_up(rho, rho), rho);
  const double rem = mul_up(mul_up(rho3, rho3), t.exp_rem);
  p = p + I(-rem, rem);
  // 2^(j/256) exp(r) in s + W.
  const double th = t.exp_hi[j];
  double h, l, e1;
  error_free::two_product(th, rh, h, l);
  error_free::two_sum(th, h, s, e1);
  w = (point(e1) + point(l)) + point(th) * (rl + p) + t.exp_lo[j] * ((I(1L) + r) + p);
  return true;
}

template <bool Up>
bool exp_point(double x, double& out) {
  double s, y;
  I w;
  int k = 0;
  if (!exp_sum(x, s, w, k) || !decide<Up>(s, w, y)) return false;
  out = std::ldexp(y, k);  // exact: a normal result (see the header)
  return true;
}

template <bool Up>
bool log_point(double x, double& out) {
  if (!(x >= std::numeric_limits<double>::min() && x <= std::numeric_limits<double>::max())) return false;
  const Tables& t = tables();
  const auto bits = std::bit_cast<std::uint64_t>(x);
  int e = static_cast<int>(bits >> 52) - 1023;
  double m = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);  // [1, 2)
  if (m > 0x1.6a09e667f3bcdp+0) {  // above sqrt(2) (any threshold near it would do)
    m *= 0.5;
    ++e;
  }
  const int j = static_cast<int>(std::nearbyint((m - 1) * 256));
  if (j < kLogLow || j > kLogHigh) return false;  // cannot happen (m in (0.707, 1.415))
  const int i = j - kLogLow;
  // r = m inv - 1 = rh + l exactly.
  double h, l;
  error_free::two_product(m, t.log_inv[i], h, l);
  const double rh = h - 1;
  const I r = point(rh) + point(l);
  const double rho = std::max(std::fabs(r.lower()), std::fabs(r.upper()));
  if (!(rho <= 0x1p-6)) return false;
  // P(r) = r^2 (-1/2 + r (1/3 + ... + r (-1/8))) + [-rho^9/8, rho^9/8].
  I p = t.log_coef[8] * r + t.log_coef[7];
  for (int k = 6; k >= 2; --k) p = p * r + t.log_coef[k];
  p = p * (r * r);
  const double rho2 = mul_up(rho, rho), rho4 = mul_up(rho2, rho2);
  const double rem = mul_up(mul_up(mul_up(rho4, rho4), rho), t.log_rem);
  p = p + I(-rem, rem);
  // log x = e l1 + e l2 + lh + ll + rh + l + P in s + W.
  const double de = e;
  double s1, e1, s, e2;
  error_free::two_sum(de * t.l1, t.log_hi[i], s1, e1);  // de * l1 exact (11 + 41 bits)
  error_free::two_sum(s1, rh, s, e2);
  const I w = ((point(e1) + point(e2)) + (point(l) + t.log_lo[i])) + (point(de) * t.l2 + p);
  return decide<Up>(s, w, out);
}

// The MPFR path (as before this file): one 53-bit temporary per thread.
template <bool Log>
double mpfr_point(double x, bool up) {
  thread_local struct Tmp {
    mpfr_t t;
    Tmp() { mpfr_init2(t, 53); }
    ~Tmp() { mpfr_clear(t); }
  } tmp;
  const mpfr_rnd_t rnd = up ? MPFR_RNDU : MPFR_RNDD;
  mpfr_set_d(tmp.t, x, MPFR_RNDN);  // exact
  if (Log) mpfr_log(tmp.t, tmp.t, rnd);
  else mpfr_exp(tmp.t, tmp.t, rnd);
  return mpfr_get_d(tmp.t, rnd);
}

}  // namespace

bool exp_fast(double x, bool up, double& out) { return up ? exp_point<true>(x, out) : exp_point<false>(x, out); }
bool log_fast(double x, bool up, double& out) { return up ? log_point<true>(x, out) : log_point<false>(x, out); }
double exp_mpfr(double x, bool up) { return mpfr_point<false>(x, up); }
double log_mpfr(double x, bool up) { return mpfr_point<true>(x, up); }

}  // namespace interval_elementary

// Both functions are increasing: the lower end from the lower end, the upper from the upper.
DoubleInterval exp(const DoubleInterval& x) {
  using namespace interval_elementary;
  if (x.has_nan()) return DoubleInterval::nan_interval();
  double lo, hi;
  if (x.lower() == x.upper()) {  // a point: one sum for both ends
    double s;
    DoubleInterval w;
    int k = 0;
    const bool ok = exp_sum(x.lower(), s, w, k);
    if (ok && decide<false>(s, w, lo)) lo = std::ldexp(lo, k);
    else lo = exp_mpfr(x.lower(), false);
    if (ok && decide<true>(s, w, hi)) hi = std::ldexp(hi, k);
    else hi = exp_mpfr(x.upper(), true);
    return {lo, hi};
  }
  if (!exp_point<false>(x.lower(), lo)) lo = exp_mpfr(x.lower(), false);
  if (!exp_point<true>(x.upper(), hi)) hi = exp_mpfr(x.upper(), true);
  return {lo, hi};
}

DoubleInterval log(const DoubleInterval& x) {
  using namespace interval_elementary;
  // As mpfi_log: defined for x > 0 only (an end <= 0 gives -inf or NaN from MPFR: never finite).
  if (x.has_nan() || x.upper() < 0) return DoubleInterval::nan_interval();
  double lo, hi;
  if (!log_point<false>(x.lower(), lo)) lo = log_mpfr(x.lower(), false);
  if (!log_point<true>(x.upper(), hi)) hi = log_mpfr(x.upper(), true);
  return {lo, hi};
}

}  // namespace bouncer
