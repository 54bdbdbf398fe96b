// exp and log of a DoubleInterval (scalar/interval_double.hpp) in double arithmetic, with MPFR
// only as fallback: the ends are the same doubles MPFR's directed roundings give, bit for bit.
//
// Why the ends are exact directed roundings (the argument). Both functions are increasing, so
// the lower end is RD(f(lo)) and the upper end RU(f(hi)) (RD, RU: the directed roundings to
// double of the exact real value). For one point x the fast path computes a double s and a
// DoubleInterval W with f(x) in s + W (a real sum, never rounded), using only the operations
// whose rounding interval_double.hpp proves (DoubleInterval + - * /: each end the directed
// rounding of its exact result) and error-free transformations whose exactness is argued at
// each use. Then, RD being monotone, RD(s + W.lo) <= RD(f(x)) <= RD(s + W.hi); the two outer
// values are add_down(s, W.lo) and add_down(s, W.hi) (exact directed sums, interval_double.hpp),
// and when they are equal they ARE RD(f(x)). Likewise RU. When they differ (f(x) lies within
// W's width of a double: measured once in 2-4 10^4 random ends), or when x lies outside the
// range argued below, the end is computed by MPFR at 53 bits in the same direction, as before.
// So every end is exactly MPFR's directed result: 0 ulps wider (tests/test_interval_elementary.cpp
// checks that bit for bit over random and extreme arguments). The fast path is Ziv's strategy
// ("round if you can, else recompute more precisely") with an interval in place of an error
// estimate, so that no error bound of a floating-point polynomial has to be derived by hand:
// only the truncation bounds of two series (below) and the tables' enclosures, which MPFR
// computes when the tables are first used (at 200 bits, each rounded outward).
//
// exp(x), |x| <= 708 (so the result and every scaled intermediate is a normal double; larger
// |x|, infinities and NaN go to MPFR). With M = nearbyint(x 256/ln2) (|M| < 2^18; any integer
// would do, only |r| below matters), k = floor(M / 256), j = M - 256 k in [0, 255]:
//   exp(x) = 2^k 2^(j/256) exp(r),  r = x - M ln2/256.
// ln2/256 = C1 + c2 with C1 the double RN(ln2/256) cut to 33 significant bits, so M C1 is a
// double exactly (18 + 33 bits), and c2 is enclosed by MPFR. TwoSum gives x - M C1 = rh + e0
// exactly (finite operands), so r lies in rh + RL, RL = e0 - M [c2] (interval arithmetic), and
// R = rh + RL encloses r. The check rho = max|R| <= 2^-7 holds by construction
// (|r| <= ln2/512 plus rounding) and is tested anyway; failing it means MPFR.
// Taylor at 0 to degree 5: exp(r) = 1 + r + P(r) with
//   P(r) = r^2 (1/2 + r (1/6 + r (1/24 + r/120))) + L,  |L| <= rho^6 e^rho / 720 <= rho^6 / 700
// (Lagrange's remainder; e^rho <= e^(2^-7) < 720/700). P is evaluated in DoubleInterval
// arithmetic over R with the coefficients enclosed ([1]/[6] etc.) and [-rho^6/700, rho^6/700]
// added, rho^6 / 700 rounded up: an enclosure of P(r) for the unknown r in R.
// The table T_j = 2^(j/256) = th_j + tl_j: th_j the double nearest, tl_j an MPFR enclosure.
//   T_j exp(r) = th + th rh + th RL + th P + tl (1 + R + P).
// th rh = h + l exactly (TwoProduct by FMA: for M != 0, |x| >= 2^-10 and M C1 is a multiple
// of 2^-41, so rh is 0 or a multiple of 2^-62, far from underflow; for M = 0, th = 1 and the
// product is exact), th + h = s + e1 exactly (TwoSum), so
//   T_j exp(r) in s + W,  W = e1 + l + th (RL + P) + tl (1 + R + P)   (interval arithmetic),
// and the two directed sums s + W.lo, s + W.hi decide as above. W is about 2^-68 wide (the
// rounding of th P, |P| <= 2^-19, dominates; the remainder is below 2^-66). The scaling by
// 2^k (ldexp) is exact: for |x| <= 708, 2^k T_j exp(r) lies in [2^-1022, 2^1022) (k = -1022
// forces j >= 143), so RD and RU commute with it.
//
// log(x), x a normal positive double (0, subnormals, negative, inf and NaN go to MPFR, which
// gives -inf at 0 and NaN below it, as before). x = m 2^E exactly (the bits), m in [1, 2),
// halved with E + 1 when m > sqrt(2) (exact), so m in (sqrt(2)/2, sqrt(2)]. j = nearbyint(256
// (m - 1)) in [-75, 106], c_j = 1 + j/256, inv_j = RN(1 / c_j) (inv_0 = 1). Then
//   log x = E ln2 - log(inv_j) + log(1 + r),  r = m inv_j - 1.
// m inv_j = h + l exactly (TwoProduct; h near 1), and h - 1 = rh exactly (Sterbenz:
// 1/2 <= h <= 2), so r = rh + l exactly (for j = 0, r = m - 1 with l = 0); |r| <= 2^-9/c_j +
// 2^-52 < 2^-8.4, and rho = max|R| <= 2^-6 is tested (else MPFR). Taylor to degree 8:
//   log(1 + r) = r + P(r),  P(r) = r^2 (-1/2 + r (1/3 + r (-1/4 + ... + r (-1/8)))) + L,
//   |L| <= sum_{i>=9} rho^i / i <= rho^9 / (9 (1 - rho)) <= rho^9 / 8
// (the series of -log(1 - rho) bounds every tail, whatever the sign of r).
// ln2 = L1 + l2 with L1 cut to 41 significant bits (E L1 exact for |E| <= 1024), l2 and
// -log(inv_j) = lh_j + ll_j enclosed by MPFR. Then E L1 + lh = s1 + e1 and s1 + rh = s + e2
// exactly (TwoSum), and
//   log x in s + W,  W = e1 + e2 + l + ll + E [l2] + P   (interval arithmetic).
// Near x = 1 (E = 0, j = 0) everything but rh and P vanishes exactly, so W is relatively
// as tight as r (no cancellation against E ln2): log(1 +- ulp) decides like any other point;
// log(1) = 0 and exp(0) = 1 come out exact (W = [0, 0]).
//
// Cost, measured (bench_step, veldep): see docs/guide/benchmarks.md, "The step".
#pragma once

#include "bouncer/scalar/interval_double.hpp"

namespace bouncer::interval_elementary {

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
