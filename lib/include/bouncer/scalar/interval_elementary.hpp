// exp and log of a DoubleInterval (scalar/interval_double.hpp) in double arithmetic, with MPFR
// only as fallback: the ends are the same doubles MPFR's directed roundings give, bit for bit.
//
// The decision (Ziv's strategy: round if you can, else recompute more precisely). Both
// functions are increasing, so the lower end is RD(f(lo)) and the upper end RU(f(hi)) (RD, RU:
// the directed roundings to double of the exact real value). For one point x the fast path
// computes doubles s, w, eps and an integer k with
//     |f(x) 2^-k - (s + w)| <= eps                                                    (*)
// (s + w a real sum, never rounded). Then [w - eps, w + eps] is widened outward to doubles
// [lo, hi] (add_down, add_up: exact directed sums, interval_double.hpp), and, RD being
// monotone, RD(s + lo) <= RD(f(x) 2^-k) <= RD(s + hi); the outer two are directed sums too, and
// when they are equal they ARE RD(f(x) 2^-k), and 2^k times it is RD(f(x)) (for |x| <= 708
// every result is a normal double and the scaling is exact). Likewise RU. When they differ
// (f(x) lies within eps of a rounding boundary: rarely, tests/test_interval_elementary.cpp counts it) or x lies
// outside the range argued below, MPFR computes the end at 53 bits in the same direction. So
// every end is exactly MPFR's directed result: 0 ulps wider. Everything rests on (*).
//
// How (*) is proved: an a-priori bound of the rounding errors. s is exact (error-free
// transformations, argued at each use); w is computed by some 25 plain round-to-nearest
// operations on doubles, and eps bounds the difference between w and the exact remainder.
// Notation: u = 2^-53; every plain operation returns RN(a op b) = (a op b)(1 + d), |d| <= u,
// when no underflow occurs (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed.,
// (2.4); gamma_n = n u / (1 - n u)); with gradual underflow a product also carries an absolute
// error of at most 2^-1075 (sums of doubles in the subnormal range are exact). The bound is
//     eps = RN(RN(K mag) + eta),   K = 2^-47 (= 64 u),   eta = 2^-190,
// mag = a sum of magnitudes of computed terms (listed below for each function; computed in
// RN, within a factor (1 - u)^8 of its exact value). The derivations below show that the
// rounding errors, the roundings of the coefficients and tables and the series' truncation
// together are at most 21.7 u mag (exp) and 19.2 u mag (log), so K leaves a factor 2.9 for the
// slack of mag's and eps's own roundings and for any constant counted too tightly here. eta
// covers what is not relative to mag: the tables' values come from MPFR at 300 bits (each at
// most 2^-299 relative from the exact constant, so the low parts and c2, l2 below carry
// absolute errors of at most 2^18 2^-300 + 2^-298 < 2^-280), and underflow (at most 8
// products in the subnormal range, only when x or r is below 2^-500: under 2^-1070 in all).
// RN(y + eta) >= y + eta/2 for y < 2^-140, and for larger y the factor 2.9 covers 2^-280 by far.
// tests/test_interval_elementary.cpp measures |f(x) 2^-k - (s + w)| / eps at 300 bits over
// random and extreme arguments and requires it <= 1/2.
//
// exp(x), |x| <= 708 (larger |x|, infinities and NaN go to MPFR). With M = nearbyint(x 256/ln2)
// (|M| < 2^18; any integer would do, only |r| below matters), k = floor(M / 256),
// j = M - 256 k in [0, 255]:  exp(x) = 2^k 2^(j/256) exp(r),  r = x - M ln2/256.
// ln2/256 = c1 + c2* (c1 the double RN(ln2/256) cut to 33 significant bits, so M c1 is a double
// exactly: 18 + 33 bits; c2 = RN(c2*) up to the table error). TwoSum gives x - M c1 = rh + e0
// exactly, so r = rh + e0 - M c2* exactly. Computed: mc = RN(M c2), rl = RN(e0 - mc),
// r' = RN(rh + rl) (the fast path requires |r'| <= 2^-9; |r| < 2^-9.4 by construction).
//   |M c2* - mc| <= 2.01 u |mc|;  |(e0 - M c2*) - rl| <= 3.01 u (|e0| + |mc|) =: d1;
//   |r - r'| <= d1 + u |r'|.
// P(r) = exp(r) - 1 - r, approximated by S(t) = t^2 (c_2 + t (c_3 + ... + t c_6)) at r' by
// Horner's rule (c_i = RN(1/i!)); in units of u r'^2:
//   * truncation |P(r') - S*(r')| <= |r'|^7 e^|r'| / 7! < 0.07 (S* with the exact 1/i!);
//   * the coefficients' roundings |S*(r') - S(r')| <= 0.502;
//   * the inner Horner (4 steps) errs by at most gamma_8 0.5015 < 4.02 (Higham (5.3); the
//     coefficients' absolute sum at |r'| <= 2^-9 is at most 0.5014 (1 + u)), and r'^2 and the
//     outer product add 2.01 x 0.5016 < 1.01;
//   * |P(r) - P(r')| <= |r - r'| max|e^t - 1| <= 1.003 (|r'| + |r - r'|) |r - r'|
//     <= 0.002 d1 + 1.01 u r'^2.
//   Since |p| >= 0.498 r'^2: |P(r) - p| <= 17.7 u |p| + 0.002 d1.
// 2^(j/256) = th + tl* (th = RN(2^(j/256)), tl = RN(tl*), |tl* - tl| <= u |tl|; tl = 0 for
// j = 0). th rh = h + l (TwoProduct: exact; for M != 0 |x| >= 2^-10 and M c1 is a multiple of
// 2^-41, so rh is 0 or a multiple of 2^-62, far from underflow; for M = 0, th = 1 and l = 0) and
// th + h = s + e1 (TwoSum, exact), so
//   2^(j/256) exp(r) = s + [e1 + l + th (e0 - M c2* + P(r)) + tl* (1 + r + P(r))]  exactly,
// and the bracket is computed as w = RN(RN(e1 + l) + RN(RN(th RN(rl + p)) + RN(tl RN(1 + RN(r'
// + p))))). With 1 <= th < 2, |r'| <= 2^-9 and |tl| < 2^-52, term by term:
//   * a1 = RN(rl + p) against e0 - M c2* + P(r): 1.002 d1 + 17.7 u |p| + 1.0001 u (|e0| + |mc| + |p|);
//   * a2 = RN(th a1): th times that plus u th |a1|: th (5.02 u (|e0| + |mc|) + 19.7 u |p|);
//   * a3 = RN(tl z'), z' = RN(1 + RN(r' + p)) against tl* (1 + r + P(r)): |z - z'| <= 1.02 u + d1
//     + 19 u |p|, so |tl| (1.02 u + ...) + u |tl z'| + 1.01 u |tl| <= 3.1 u |tl| (d1 and |p| times
//     |tl| < 2^-52 are far below the other terms' allowance);
//   * the three outer sums: u (|e1| + |l|), then u (|a2| + |a3|) and u (|a4| + |a5|), each term
//     counted at most twice: 2.01 u (|e1| + |l|) + 2.01 u th (|e0| + |mc| + |p|) + 2.05 u |tl|.
// With  mag = |e1| + |l| + th (|e0| + |mc| + |p|) + |tl|  the weights are at most 21.7 u (th |p|),
// 7.03 u (th (|e0| + |mc|)), 5.2 u (|tl|) and 2.01 u (|e1| + |l|): below 21.7 u mag.
//
// log(x), x a normal positive double (0, subnormals, negative, inf and NaN go to MPFR, which
// gives -inf at 0 and NaN below it). x = m 2^E exactly (the bits), m in [1, 2), halved with
// E + 1 when m > sqrt(2) (exact), so m in (sqrt(2)/2, sqrt(2)]. j = nearbyint(256 (m - 1)) in
// [-75, 106], c_j = 1 + j/256, inv_j = RN(1 / c_j) (inv_0 = 1). Then
//   log x = E ln2 - log(inv_j) + log(1 + r),  r = m inv_j - 1.
// m inv_j = h + l exactly (TwoProduct; h near 1), and h - 1 = rh exactly (Sterbenz:
// 1/2 <= h <= 2), so r = rh + l exactly (|r| <= 2^-9/c_j + 2^-52 < 2^-8.4; r is 0 or at least
// 2^-106 in magnitude, a multiple of ulp(m) ulp(inv)), and r' = RN(rh + l) errs by at most
// u |r'| (the fast path requires |r'| <= 2^-8).
// P(r) = log(1 + r) - r, approximated by S(t) = t^2 (c_2 + t (c_3 + ... + t c_8)),
// c_i = RN((-1)^(i+1)/i); in units of u r'^2:
//   * truncation |P(r') - S*(r')| <= |r'|^9 / (9 (1 - |r'|)) < 0.02 (the series of
//     -log(1 - |r'|) bounds every tail, whatever the sign of r');
//   * coefficients <= 0.502; Horner (6 steps) gamma_12 0.5015 < 6.02, the outer products 1.01;
//   * |P(r) - P(r')| <= |r - r'| max|t/(1 + t)| <= 1.005.
//   Since |p| >= 0.4986 r'^2: |P(r) - p| <= 17.2 u |p|.
// ln2 = l1 + l2* (l1 cut to 41 significant bits, so E l1 is exact for |E| <= 1024; l2 = RN(l2*))
// and -log(inv_j) = lh + ll* (lh = RN(-log(inv_j)), ll = RN(ll*); ll = ll* = 0 for j = 0).
// E l1 + lh = s1 + e1 and s1 + rh = s + e2 (TwoSum, exact), so
//   log x = s + [e1 + e2 + l + ll* + E l2* + P(r)]  exactly,
// computed as w = RN(RN(RN(e1 + e2) + RN(l + ll)) + RN(RN(E l2) + p)). Errors: |E l2* - RN(E l2)|
// <= 2.02 u |E l2|; |ll* - ll| <= u |ll|; the polynomial 17.2 u |p|; the sums u times the
// magnitudes, each term counted at most twice more (1 + u each). With
//   mag = |e1| + |e2| + |l| + |ll| + |E l2| + |p|
// every weight is at most 19.2 u (|p|; |E l2| 4.05 u, |ll| 4.01 u, the others 3.01 u). Near
// x = 1 (E = 0, j = 0) everything but rh, l and p vanishes exactly, so eps is relatively as
// small as w (no cancellation against E ln2): log(1 +- ulp) decides like any other point;
// log(1) = 0 and exp(0) = 1 come out exact.
//
// Cost, measured (bench_step, veldep): see docs/guide/benchmarks.md, "The step".
#pragma once

#include "bouncer/scalar/interval_double.hpp"

namespace bouncer::interval_elementary {

// (*) above for one point: f(x) 2^-k within eps of s + w. False (f untouched but for k) when
// x lies outside the argued range. For tests; the fast paths below use them.
struct Sum {
  double s = 0, w = 0, eps = 0;
  int k = 0;
};
bool exp_sum(double x, Sum& f);
bool log_sum(double x, Sum& f);

// The fast path for one point: true and f(x) rounded down (up = false) or up in `out` when it
// decides; false (out untouched) when MPFR must decide. For tests and benchmarks; exp and log
// of a DoubleInterval call these and fall back to the *_mpfr ones.
bool exp_fast(double x, bool up, double& out);
bool log_fast(double x, bool up, double& out);
// MPFR at 53 bits, directed (MPFR_RNDD / MPFR_RNDU), converted to double in the same
// direction: the reference and the fallback.
double exp_mpfr(double x, bool up);
double log_mpfr(double x, bool up);

}  // namespace bouncer::interval_elementary
