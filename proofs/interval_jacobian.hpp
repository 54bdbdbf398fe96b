// Rigorous Jacobian enclosures of the impact map for the proofs: forward-mode derivatives
// in interval arithmetic (Dual<Mpfi>, verify/interval_dual.hpp) through the library's own
// templated step. Every branch is decided for the whole input set, so the step is one
// smooth formula there and the derivative enclosures contain the exact Jacobian of that
// branch at every point of the input box. Used as an independent check of the Jacobians
// derived by hand in each proof.
//
// ImpactMap<Dual<Mpfi>> is instantiated in the library (lib/src/verify/enclosure.cpp, declared extern
// in verify/interval_dual.hpp); impact_map_impl.hpp is included so that this header still
// works if that instantiation moves.
#pragma once

#include <optional>
#include <string>

#include "bouncer/verify/interval_dual.hpp"
#include "bouncer/model/impact_map_impl.hpp"
#include "proof_util.hpp"

namespace proofs {

using bouncer::IDual;

// Model<Mpfi> -> Model<Dual<Mpfi>>: every parameter a constant (zero derivatives).
inline bouncer::Model<IDual> lift(const bouncer::Model<Mpfi>& m) {
  return bouncer::convert_model<IDual>(m, [](const Mpfi& x) { return IDual(x); });
}

struct IMat2 {
  Mpfi a11, a12, a21, a22;
};

struct LinearizedSteps {
  bouncer::State<Mpfi> end;
  IMat2 J;  // d(theta_q, v_q)/d(theta_0, v_0), rows (theta, v)
  std::vector<bouncer::EventKind> kinds;
  std::vector<long long> periods;
  std::vector<int> segments;
};

// q steps from the box (theta, v) with the Jacobian of the composition. Throws Undecided.
inline LinearizedSteps linearize(const bouncer::ImpactMap<IDual>& map, const Mpfi& theta,
                                 const Mpfi& v, int q) {
  bouncer::State<IDual> s{IDual::variable(theta, 0), IDual::variable(v, 1)};
  LinearizedSteps out;
  for (int i = 0; i < q; ++i) {
    bouncer::StepResult<IDual> r = map.step(s);
    out.kinds.push_back(r.kind);
    out.periods.push_back(r.periods);
    out.segments.push_back(r.segment);
    s = r.next;
  }
  out.end = {s.theta.v, s.v.v};
  out.J = {s.theta.d[0], s.theta.d[1], s.v.d[0], s.v.d[1]};
  return out;
}

// Enclosures of the two (real) eigenvalues of every matrix in the interval matrix J, when
// the discriminant is certainly positive: (tr +- sqrt(tr^2 - 4 det)) / 2.
struct Eigen2 {
  Mpfi hi, lo;
};
inline std::optional<Eigen2> eigenvalues(const IMat2& J) {
  const Mpfi tr = J.a11 + J.a22;
  const Mpfi det = J.a11 * J.a22 - J.a12 * J.a21;
  const Mpfi disc = tr * tr - 4 * det;
  if (!lt(Mpfi(0, disc.bits()), disc)) return std::nullopt;
  const Mpfi r = sqrt(disc);
  return Eigen2{(tr + r) / 2, (tr - r) / 2};
}

inline std::string describe(const IMat2& J) {
  return "[[" + s(J.a11) + ", " + s(J.a12) + "], [" + s(J.a21) + ", " + s(J.a22) + "]]";
}

}  // namespace proofs
