// Error-free transformations of IEEE doubles: the exact rounding error of one operation,
// itself a double. Exact in round-to-nearest without FMA contraction (-ffp-contract=off,
// which the build sets) and without overflow; used by DoubleInterval (the directed ends of
// each operation, scalar/interval_double.hpp) and DoubleDouble (double-word arithmetic,
// scalar/double_double.hpp).
#pragma once

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

// Dekker's TwoProduct with Veltkamp's splitting: h = RN(a b), l = a b - h exactly when
// |a|, |b| < 2^995 (no overflow in the splitting) and l does not underflow.
inline void two_product(double a, double b, double& h, double& l) {
  constexpr double split = 134217729.0;  // 2^27 + 1
  h = a * b;
  const double ta = split * a, ah = ta - (ta - a), al = a - ah;
  const double tb = split * b, bh = tb - (tb - b), bl = b - bh;
  l = ((ah * bh - h) + ah * bl + al * bh) + al * bl;
}

}  // namespace bouncer::error_free
