// Error-free transformations of IEEE doubles: the exact rounding error of one operation,
// itself a double. Exact in round-to-nearest without FMA contraction (-ffp-contract=off,
// which the build sets) and without overflow; used by DoubleInterval (the directed ends of
// each operation, scalar/interval_double.hpp) and DoubleDouble (double-word arithmetic,
// scalar/double_double.hpp).
#pragma once

#include <cmath>

namespace bouncer::error_free {

// Knuth's TwoSum: s = RN(a + b), e = (a + b) - s exactly (any finite a, b).
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

// Dekker's FastTwoSum: the same when |a| >= |b| (or a == 0).
inline void fast_two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  e = b - (s - a);
}

// TwoProduct: h = RN(a b), l = a b - h exactly when h does not overflow and l does not
// underflow (the callers' ranges: |a|, |b| < 2^995, |h| > 2^-960). l = RN(a b - h) by one
// fused multiply-add: std::fma is the IEEE 754 fusedMultiplyAdd, correctly rounded (glibc's
// fma: the processor's FMA instruction where it has one, an exact software emulation
// otherwise), and a b - h is a double, so l is exact and the same bits on every machine.
// (Dekker's splitting with Veltkamp's constant gives the same l in 17 operations; the FMA
// made the Lohner step 10-15% cheaper and the double-double step about 8%.) This is an
// explicit call, not a contraction: -ffp-contract=off still forbids the compiler to fuse
// any a * b + c of its own.
inline void two_product(double a, double b, double& h, double& l) {
  h = a * b;
  l = std::fma(a, b, -h);
}

}  // namespace bouncer::error_free
