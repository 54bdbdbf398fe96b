// Error-free transformations of IEEE doubles: the exact rounding error of one operation,
// itself a double. Exact in round-to-nearest without FMA contraction (-ffp-contract=off,
// which the build sets) within the ranges stated for each; used by DoubleInterval (the
// directed ends of each operation, scalar/interval_double.hpp) and DoubleDouble (double-word
// arithmetic, scalar/double_double.hpp).
#pragma once

#include <cmath>

namespace bouncer::error_free {

// Knuth's TwoSum: s = RN(a + b), e = (a + b) - s exactly for finite a, b unless an
// intermediate overflows. That can happen while s is finite, near the top of the range
// (s - a overflows for a = 0x1.0000000000003p+1022, b = -DBL_MAX: issue 21). Only + and - are used, so an overflow reaches e as +-inf or NaN,
// never as a wrong finite value, and an infinite or NaN s makes e NaN: e is exact whenever it
// is finite (DoubleInterval tests exactly that). Underflow never disturbs it: a sum or
// difference of doubles in the subnormal range is exact. (DoubleDouble, a point type, lets a
// non-finite e through to its own is_finite check.)
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

// Dekker's FastTwoSum: the same when |a| >= |b| (or a == 0); then s - a = b - e exactly, so no
// intermediate overflows when s is finite.
inline void fast_two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  e = b - (s - a);
}

// TwoProduct: h = RN(a b), l = a b - h exactly when h is finite and l does not underflow
// (a b - h is a multiple of ulp(a) ulp(b): |h| >= 2^-960, DoubleInterval's range, or a or b
// zero suffices). l = RN(a b - h) by one fused multiply-add: std::fma is the IEEE 754
// fusedMultiplyAdd, correctly rounded (glibc's fma: the processor's FMA instruction where it
// has one, an exact software emulation otherwise), and a b - h is a double, so l is exact and
// the same bits on every machine. The FMA forms a b exactly inside, so nothing overflows
// while h is finite (Dekker's splitting with Veltkamp's constant gives the same l in 17
// operations, but overflows for |a| or |b| above about 2^996; the FMA made the Lohner step
// 10-15% cheaper and the double-double step about 8%). This is an explicit call, not a
// contraction: -ffp-contract=off still forbids the compiler to fuse any a * b + c of its own.
inline void two_product(double a, double b, double& h, double& l) {
  h = a * b;
  l = std::fma(a, b, -h);
}

}  // namespace bouncer::error_free
