// Periodic orbits: the paper's analytic families (as printed, to be checked against the
// map: see tests/test_periodic.cpp and the report there) and a damped Newton solver for
// period-q orbits of the impact map, with stability multipliers from the AD Jacobian.
// The solver is implemented in lib/src/analysis/periodic.cpp for double and Mpfr.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bouncer/analysis/jacobian.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

// ---------------------------------------------------------------------------------------
// The paper's formulas, transcribed as printed (Langer & Miller 2014, sec. II.B). S is any
// point scalar with + - * / and sqrt/log (double, Mpfr). `one` fixes the precision.
namespace paper {

// Eq. 5: fixed points theta* in (0, 1/2), v* = 4(1+eps)/(1-eps), for a = 8(1+eps)/(p(1-eps)).
template <class S>
S fixed_point_v(const S& eps) {
  return 4 * (eps + 1) / (1 - eps);
}
template <class S>
S fixed_point_a(const S& eps, long p) {
  return 8 * (eps + 1) / (p * (1 - eps));
}
// The same curve solved for eps: eps = (ap - 8)/(ap + 8).
template <class S>
S fixed_point_eps(const S& a, long p) {
  return (a * p - 8) / (a * p + 8);
}

// Elastic period-2 up/up families (eq. 33 and the formula before it):
//   a = (22p - 64k +- 2 sqrt(169p^2 - 608kp + 256k^2)) / (3p^2),  v = ap/4 + 4 - 8k/p,
//   lambda2 = (ap^2 - 32k)^2 / ((ap^2 + 32k) sqrt(a^2p^4 + 128ap^3 - 64akp^2 + 1024k^2)).
template <class S>
S elastic_p2_a(const S& one, long p, long k, int sign) {
  using std::sqrt;
  const S disc = one * (169 * p * p - 608 * k * p + 256 * k * k);
  const S root = sqrt(disc);
  return (one * (22 * p - 64 * k) + (sign >= 0 ? 2 * root : -2 * root)) / (3 * p * p);
}
template <class S>
S elastic_p2_v(const S& a, long p, long k) {
  return a * p / 4 + 4 - (a / a) * (8 * k) / p;
}
template <class S>
S elastic_p2_lambda2(const S& a, long p, long k) {
  using std::sqrt;
  const S ap2 = a * (p * p);
  const S num = (ap2 - 32 * k) * (ap2 - 32 * k);
  const S rad = a * a * (p * p * p * p) + a * (128 * p * p * p) - a * (64 * k * p * p) + (a / a) * (1024 * k * k);
  return num / ((ap2 + 32 * k) * sqrt(rad));
}

// Eq. 10: inelastic period-2 up/up family, p = 1, k = 0:
//   a = 32/(1-eps) - 16/(1+eps^2) - 8,
//   v = 4(eps-3)(eps^3-eps^2-3eps-3) / ((eps-1)^2 (eps^2+1)),
//   and the intermediate v = a(eps^2-4)/((eps-1)(eps+1)^2) + 4 printed before it;
//   lambda2 = 2[eps^2 - sqrt(2) eps^5 / sqrt(8 eps^4 + a (eps-1)^2)]
//           = 2 eps^2 - eps^5 sqrt(eps^2+1) / sqrt(eps^6 - 2 eps^3 + 2 eps + 1).
template <class S>
S eq10_a(const S& eps) {
  return 32 / (1 - eps) - 16 / (eps * eps + 1) - 8;
}
template <class S>
S eq10_v(const S& eps) {
  const S e2 = eps * eps, e3 = e2 * eps;
  return 4 * (eps - 3) * (e3 - e2 - 3 * eps - 3) / ((eps - 1) * (eps - 1) * (e2 + 1));
}
template <class S>
S eq10_v_intermediate(const S& a, const S& eps) {
  return a * (eps * eps - 4) / ((eps - 1) * (eps + 1) * (eps + 1)) + 4;
}
template <class S>
S eq10_lambda2_first(const S& a, const S& eps) {
  using std::sqrt;
  const S e2 = eps * eps, e4 = e2 * e2, e5 = e4 * eps;
  return 2 * (e2 - sqrt(2 * (eps / eps)) * e5 / sqrt(8 * e4 + a * (eps - 1) * (eps - 1)));
}
template <class S>
S eq10_lambda2_second(const S& eps) {
  using std::sqrt;
  const S e2 = eps * eps, e3 = e2 * eps, e5 = e3 * e2, e6 = e3 * e3;
  return 2 * e2 - e5 * sqrt(e2 + 1) / sqrt(e6 - 2 * e3 + 2 * eps + 1);
}

// Velocity-dependent fixed points (sec. II.B.5): v* = 2^(5/3) c [arccoth(ap/8)]^(5/3) - 4,
// claimed for every a > 8/p. arccoth(x) = log((x+1)/(x-1))/2.
template <class S>
S veldep_fixed_v(const S& a, const S& c, long p) {
  using std::exp;
  using std::log;
  const S x = a * p / 8;
  const S acoth = log((x + 1) / (x - 1)) / 2;
  // 2^(5/3) [acoth]^(5/3) = (2 acoth)^(5/3) = exp((5/3) log(2 acoth))
  return c * exp(5 * log(2 * acoth) / 3) - 4;
}

}  // namespace paper

// Not as printed: the family of eq. 5 is theta* in (fixed_point_theta_min, 1/2), where
// fixed_point_theta_min = max(0, 1/2 - 2p eps/(1 + eps)) (proofs/fixed_point_family: for
// smaller theta* the flight leaves the wall's collision zone; all of (0, 1/2) iff
// eps >= 1/(4p - 1)). Exact in mpq_class.
template <class S>
S fixed_point_theta_min(const S& eps, long p) {
  const S t = (1 - eps * (4 * p - 1)) / (2 * (eps + 1));
  return t > 0 ? t : S(0);
}

// ---------------------------------------------------------------------------------------
// Derived here (see tests/test_periodic.cpp): a velocity-dependent fixed point needs BOTH
// v = ap/2 (flight time p) AND v = 4 coth((1/2)((v+4)/c)^(3/5)) (restitution), so for given
// c and p it exists only at the one a solving ap/2 = 2^(5/3) c arccoth(ap/8)^(5/3) - 4.
// Returns that a (bisection in double; NaN if none in (8/p, 1e9)).
double veldep_fixed_point_a(double c, long p);

// ---------------------------------------------------------------------------------------
// Newton solver for period-q orbits.
//
// Unknown x = (theta, v); F(x) = P^q(x) - x with the theta component wrapped into
// (-1/2, 1/2] (theta lives on the circle). Damped Newton: the step solves
// (J_q - I) dx = -F in the least-squares sense with a truncated pseudo-inverse (closed-form
// 2x2 SVD; singular values below `rcond` times the largest are dropped), then backtracks
// (halving) until the residual decreases and the new point is a valid state. Families with
// a free theta (a multiplier exactly 1, e.g. eq. 5) make J_q - I singular: the dropped
// direction is the family's tangent, so the solver moves only across the family and
// converges to the nearest member (it does not choose theta).
struct NewtonOptions {
  long max_iter = 60;
  // Relative cutoff of singular values at 53 bits; at b > 53 bits rcond^(b/53), the same
  // fraction of the significand. A fixed cutoff would stop Newton next to a fold (where
  // the smallest singular value of J_q - I vanishes like the square root of the distance)
  // at the same distance, ~rcond^2 relative, at every precision: a fold located at
  // mpfr:128 was 1e-18 from the true one, whatever the precision.
  double rcond = 1e-9;
  int grid = 8;          // guesses per axis when no guess is given
};

template <class T>
struct PeriodicOrbit {
  bool converged = false;
  long period = 0;            // q asked for
  long minimal_period = 0;    // smallest d | q with P^d(x) = x (within tolerance), when converged
  std::vector<State<T>> points;      // the q points in orbit order (points[0] = solution)
  std::vector<long long> wall_periods;  // wall periods begun in each step
  std::vector<EventKind> kinds;      // what each step was
  Mat2<T> J;                  // Jacobian of P^q at points[0]
  Eigen2<T> multipliers;      // eigenvalues of J
  bool marginal = false;      // a multiplier within 1e-6 of 1 (a family)
  double residual = 0;        // max(|d theta|, |d v|/max(1,|v|)) at the end
  double tolerance = 0;
  long iterations = 0;
  std::string note;           // why not converged, or remarks
};

// The orbit's stability from its multipliers: "stable" (largest modulus below 1),
// "unstable", "marginal" (a multiplier within 1e-6 of 1, none beyond 1 + 1e-6: a family), or
// "unknown" where Newton did not converge. `periodic`, `continue` and Python print it.
template <class T>
std::string stability_of(const PeriodicOrbit<T>& o) {
  if (!o.converged) return "unknown";
  const double m0 = o.multipliers.modulus(0);
  return o.marginal ? (m0 > 1 + 1e-6 ? "unstable" : "marginal") : m0 < 1 ? "stable" : "unstable";
}

// Newton from one guess.
template <class T>
PeriodicOrbit<T> find_periodic(const Model<T>& m, long q, const State<T>& guess, const NewtonOptions& opt = {});

// Newton from a grid of guesses in the trapping region (theta in (0, 1), v from the wall
// velocity to a bound from the model); returns the first orbit of minimal period q, else
// the first converged one, else the best attempt.
template <class T>
PeriodicOrbit<T> search_periodic(const Model<T>& m, long q, const NewtonOptions& opt = {});

// Instantiated in lib/src/analysis/periodic.cpp for the analysis scalars (scalar/scalar_set.hpp).
#define BOUNCER_X(T, kind)                                                                                        \
  extern template PeriodicOrbit<T> find_periodic<T>(const Model<T>&, long, const State<T>&, const NewtonOptions&); \
  extern template PeriodicOrbit<T> search_periodic<T>(const Model<T>&, long, const NewtonOptions&);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
