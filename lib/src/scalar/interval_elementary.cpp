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

using interval_double_detail::add_down;
using interval_double_detail::add_up;

constexpr int kExpN = 256;        // exp's table: 2^(j/256), j = 0..255
constexpr int kLogLow = -75;      // log's table: c_j = 1 + j/256, j = -75..106
constexpr int kLogHigh = 106;
constexpr int kLogN = kLogHigh - kLogLow + 1;
constexpr long kTableBits = 300;  // MPFR's precision for the tables' values (the header's eta)
constexpr double kK = 0x1p-47;    // the bound's factor on the sum of magnitudes (the header)
constexpr double kEta = 0x1p-190;  // the bound's allowance for the tables and underflow (the header)

// A double cut to its leading `bits` significant bits (toward 0): exact products with small
// integers.
double cut(double x, int bits) {
  const auto b = std::bit_cast<std::uint64_t>(x);
  const std::uint64_t mask = ~((std::uint64_t{1} << (52 - (bits - 1))) - 1);
  return std::bit_cast<double>(b & mask);
}

struct Tables {
  double exp_hi[kExpN];   // RN(2^(j/256))
  double exp_lo[kExpN];   // RN(2^(j/256) - exp_hi[j])
  double log_inv[kLogN];  // RN(1 / c_j)
  double log_hi[kLogN];   // RN(-log(log_inv[j]))
  double log_lo[kLogN];   // RN(-log(log_inv[j]) - log_hi[j])
  double c1 = 0;          // ln2/256 cut to 33 bits
  double c2 = 0;          // RN(ln2/256 - c1)
  double l1 = 0;          // ln2 cut to 41 bits
  double l2 = 0;          // RN(ln2 - l1)
  double inv_ln2_256 = 0;  // about 256/ln2 (any value: only picks M)
  double exp_coef[7];      // RN(1/k!), k = 2..6
  double log_coef[9];      // RN((-1)^(k+1)/k), k = 2..8

  Tables() {
    mpfr_t v, t;
    mpfr_inits2(kTableBits, v, t, static_cast<mpfr_ptr>(nullptr));
    // RN(v - h) for the 300-bit v (the header's eta bounds what v's own rounding adds).
    auto low_part = [&](double h) {
      mpfr_sub_d(t, v, h, MPFR_RNDN);
      return mpfr_get_d(t, MPFR_RNDN);
    };
    mpfr_const_log2(v, MPFR_RNDN);
    l1 = cut(mpfr_get_d(v, MPFR_RNDN), 41);
    l2 = low_part(l1);
    mpfr_div_2ui(v, v, 8, MPFR_RNDN);  // exact
    c1 = cut(mpfr_get_d(v, MPFR_RNDN), 33);
    c2 = low_part(c1);
    inv_ln2_256 = 256 / std::log(2.0);
    for (int j = 0; j < kExpN; ++j) {
      mpfr_set_si(t, j, MPFR_RNDN);
      mpfr_div_2ui(t, t, 8, MPFR_RNDN);  // exact
      mpfr_exp2(v, t, MPFR_RNDN);
      exp_hi[j] = mpfr_get_d(v, MPFR_RNDN);
      exp_lo[j] = low_part(exp_hi[j]);
    }
    for (int j = kLogLow; j <= kLogHigh; ++j) {
      const int i = j - kLogLow;
      log_inv[i] = 1.0 / (1.0 + j / 256.0);  // 1 + j/256 exact; one division, RN
      mpfr_set_d(t, log_inv[i], MPFR_RNDN);   // exact
      mpfr_log(v, t, MPFR_RNDN);
      mpfr_neg(v, v, MPFR_RNDN);
      log_hi[i] = mpfr_get_d(v, MPFR_RNDN);
      log_lo[i] = low_part(log_hi[i]);
    }
    mpfr_clears(v, t, static_cast<mpfr_ptr>(nullptr));
    double fact = 1;
    for (int k = 2; k <= 6; ++k) {
      fact *= k;                   // exact
      exp_coef[k] = 1.0 / fact;  // RN
    }
    for (int k = 2; k <= 8; ++k) log_coef[k] = (k % 2 == 0 ? -1.0 : 1.0) / k;  // RN
  }
};

const Tables& tables() {
  static const Tables t;
  return t;
}

// The directed rounding of s + w + [-eps, eps] when both ends round to the same double.
template <bool Up>
bool decide(const Sum& f, double& out) {
  const double lo = add_down(f.w, -f.eps), hi = add_up(f.w, f.eps);
  const double a = Up ? add_up(f.s, lo) : add_down(f.s, lo);
  const double b = Up ? add_up(f.s, hi) : add_down(f.s, hi);
  if (a != b || std::isnan(a)) return false;
  // Times 2^k, exact: the result is a normal double (the header); -1022 <= k <= 1023, so 2^k is
  // a normal double too, built from its bits (std::ldexp is a library call per end).
  out = a * std::bit_cast<double>(static_cast<std::uint64_t>(f.k + 1023) << 52);
  return true;
}

}  // namespace

bool exp_sum(double x, Sum& f) {
  if (!(std::fabs(x) <= 708.0)) return false;  // near overflow or underflow, inf, NaN: MPFR
  const Tables& t = tables();
  const double md = std::nearbyint(x * t.inv_ln2_256);  // |md| < 2^18
  const int m = static_cast<int>(md);
  f.k = m >> 8;  // floor(m / 256) (C++20: arithmetic shift)
  const int j = m - f.k * kExpN;
  // x - md c1 = rh + e0 exactly (md c1 exact, TwoSum); r = rh + e0 - md (ln2/256 - c1).
  double rh, e0;
  error_free::two_sum(x, -(md * t.c1), rh, e0);
  const double mc = md * t.c2;
  const double rl = e0 - mc;
  const double r = rh + rl;
  if (!(std::fabs(r) <= 0x1p-9)) return false;  // cannot happen (|r| < 2^-9.4): checked anyway
  const double* c = t.exp_coef;
  const double p = (r * r) * (c[2] + r * (c[3] + r * (c[4] + r * (c[5] + r * c[6]))));
  // 2^(j/256) exp(r) = th + th rh + th (rl + P) + tl (1 + r + P), th rh = h + l, th + h = s + e1.
  const double th = t.exp_hi[j], tl = t.exp_lo[j];
  double h, l, e1;
  error_free::two_product(th, rh, h, l);
  error_free::two_sum(th, h, f.s, e1);
  f.w = (e1 + l) + (th * (rl + p) + tl * (1 + (r + p)));
  const double mag = (std::fabs(e1) + std::fabs(l)) + (th * ((std::fabs(e0) + std::fabs(mc)) + std::fabs(p)) + std::fabs(tl));
  f.eps = kK * mag + kEta;
  return true;
}

bool log_sum(double x, Sum& f) {
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
  const double r = rh + l;
  if (!(std::fabs(r) <= 0x1p-8)) return false;  // cannot happen (|r| < 2^-8.4): checked anyway
  const double* c = t.log_coef;
  const double p =
      (r * r) * (c[2] + r * (c[3] + r * (c[4] + r * (c[5] + r * (c[6] + r * (c[7] + r * c[8]))))));
  // log x = e l1 + lh + rh + (e l2 + ll + l + P); e l1 + lh = s1 + e1, s1 + rh = s + e2.
  const double de = e;
  const double el2 = de * t.l2, ll = t.log_lo[i];
  double s1, e1, e2;
  error_free::two_sum(de * t.l1, t.log_hi[i], s1, e1);  // de * l1 exact (11 + 41 bits)
  error_free::two_sum(s1, rh, f.s, e2);
  f.k = 0;
  f.w = ((e1 + e2) + (l + ll)) + (el2 + p);
  const double mag = ((std::fabs(e1) + std::fabs(e2)) + (std::fabs(l) + std::fabs(ll))) + (std::fabs(el2) + std::fabs(p));
  f.eps = kK * mag + kEta;
  return true;
}

namespace {

// The fast path of one end: the sum of f at x, then the decision in the direction asked.
bool fast_point(bool (*sum)(double, Sum&), double x, bool up, double& out) {
  Sum f;
  return sum(x, f) && (up ? decide<true>(f, out) : decide<false>(f, out));
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

bool exp_fast(double x, bool up, double& out) { return fast_point(exp_sum, x, up, out); }
bool log_fast(double x, bool up, double& out) { return fast_point(log_sum, x, up, out); }
double exp_mpfr(double x, bool up) { return mpfr_point<false>(x, up); }
double log_mpfr(double x, bool up) { return mpfr_point<true>(x, up); }

}  // namespace interval_elementary

namespace {

// Both functions are increasing: the lower end from the lower end rounded down, the upper from
// the upper rounded up; a point interval takes one sum for both ends.
DoubleInterval increasing(const DoubleInterval& x, bool (*sum)(double, interval_elementary::Sum&),
                          double (*mpfr)(double, bool)) {
  using namespace interval_elementary;
  Sum f;
  const bool lo_ok = sum(x.lower(), f);
  double lo, hi;
  if (!lo_ok || !decide<false>(f, lo)) lo = mpfr(x.lower(), false);
  const bool hi_ok = x.lower() == x.upper() ? lo_ok : sum(x.upper(), f);
  if (!hi_ok || !decide<true>(f, hi)) hi = mpfr(x.upper(), true);
  return {lo, hi};
}

}  // namespace

DoubleInterval exp(const DoubleInterval& x) {
  if (x.has_nan()) return DoubleInterval::nan_interval();
  return increasing(x, interval_elementary::exp_sum, interval_elementary::exp_mpfr);
}

DoubleInterval log(const DoubleInterval& x) {
  // As mpfi_log: defined for x > 0 only (an end <= 0 gives -inf or NaN from MPFR: never finite).
  if (x.has_nan() || x.upper() < 0) return DoubleInterval::nan_interval();
  return increasing(x, interval_elementary::log_sum, interval_elementary::log_mpfr);
}

}  // namespace bouncer
