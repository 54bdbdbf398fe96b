// Jacobians of the impact map by forward-mode automatic differentiation through the same
// templated step (ImpactMap<Dual<S>>), and stability multipliers of periodic orbits.
// Implemented in lib/src/analysis/jacobian.cpp for the analysis scalars S
// (scalar/scalar_set.hpp).
//
// Seeding: theta0 -> (1, 0), v0 -> (0, 1). The result's derivative components are the rows
//     J = [ d theta1/d theta0   d theta1/d v0 ]
//         [ d v1/d theta0       d v1/d v0     ].
// theta1 is taken modulo 1 (the integer part has zero derivative), so J is the Jacobian
// of the map on the cylinder.
//
// Non-smooth steps:
//   * a sticking step (constant restitution: collapse, ride, release) ends at the release
//     state, a constant of the wall (the triangle's (1/2, 4)): it does not depend on the
//     input, so J = 0 exactly. The same holds for a ride step (start with zero relative
//     velocity) and for the downward-sticking "impact" convention's corner collision.
//     `contracted` is set for these steps.
//   * at a branch point (impact exactly at a corner, grazing) J is the one-sided
//     derivative of the branch the step took.
#pragma once

#include <vector>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/dual.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

// The step in Dual<S> for the analysis scalars (scalar/scalar_set.hpp), instantiated in
// lib/src/model/map_instances.cpp.
#define BOUNCER_X(S, kind)                          \
  extern template class ImpactMap<Dual<S>>;         \
  extern template Model<Dual<S>> make_model<Dual<S>>(const ModelSpec&, long);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

// A 2x2 matrix, row major.
template <class S>
struct Mat2 {
  S a11{}, a12{}, a21{}, a22{};  // zero until set (a PeriodicOrbit that never converged)
};

template <class S>
Mat2<S> operator*(const Mat2<S>& x, const Mat2<S>& y) {
  return {x.a11 * y.a11 + x.a12 * y.a21, x.a11 * y.a12 + x.a12 * y.a22,
          x.a21 * y.a11 + x.a22 * y.a21, x.a21 * y.a12 + x.a22 * y.a22};
}

template <class S>
Mat2<S> identity2(long bits) {
  using Tr = ScalarTraits<S>;
  return {Tr::from_int(1, bits), Tr::from_int(0, bits), Tr::from_int(0, bits), Tr::from_int(1, bits)};
}

// The model with every parameter lifted to a constant dual number.
template <class S>
Model<Dual<S>> dual_model(const Model<S>& m);

// One step with its Jacobian.
template <class S>
struct LinearStep {
  State<S> next;
  S tau;
  long long periods = 0;
  EventKind kind = EventKind::impact;
  int segment = 0;
  bool contracted = false;  // sticking / ride: J == 0 (release state independent of input)
  Mat2<S> J;
};

// q steps with the composed Jacobian J_{q-1} ... J_1 J_0.
template <class S>
struct LinearOrbit {
  std::vector<State<S>> points;     // points[0] = start, ..., points[q] = end
  std::vector<long long> periods;   // periods[i]: wall periods begun in step i
  std::vector<EventKind> kinds;     // kinds[i]: what step i was
  bool contracted = false;          // some step had J == 0
  Mat2<S> J;
};

template <class S>
class TangentMap {
 public:
  explicit TangentMap(const Model<S>& m);
  const ImpactMap<Dual<S>>& dual_map() const { return map_; }
  long bits() const { return bits_; }

  // Throws Undecided like ImpactMap::step.
  LinearStep<S> step(const State<S>& s) const;
  LinearOrbit<S> steps(const State<S>& s, long q) const;

 private:
  ImpactMap<Dual<S>> map_;
  long bits_;
};

// Eigenvalues of a 2x2 matrix (closed form, cancellation-free): a real pair or a complex
// conjugate pair re +- i im. Ordered by decreasing modulus.
template <class S>
struct Eigen2 {
  S re[2], im[2];
  bool complex = false;
  double modulus(int i) const;
};

template <class S>
Eigen2<S> eigenvalues(const Mat2<S>& m);

// Instantiated in lib/src/analysis/jacobian.cpp for the analysis scalars.
#define BOUNCER_X(S, kind)                                              \
  extern template Model<Dual<S>> dual_model<S>(const Model<S>&);        \
  extern template class TangentMap<S>;                                  \
  extern template Eigen2<S> eigenvalues<S>(const Mat2<S>&);             \
  extern template struct Eigen2<S>;
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
