#include "bouncer/analysis/jacobian.hpp"

#include <cmath>
#include <utility>

namespace bouncer {

namespace {

template <class S>
bool all_zero(const Dual<S>& x) {
  using Tr = ScalarTraits<S>;
  return Tr::is_zero(x.d[0]) == Truth::yes && Tr::is_zero(x.d[1]) == Truth::yes;
}

}  // namespace

// The model with every parameter a constant (zero derivatives).
template <class S>
Model<Dual<S>> dual_model(const Model<S>& m) {
  return convert_model<Dual<S>>(m, [](const S& x) { return Dual<S>(x); });
}

template <class S>
TangentMap<S>::TangentMap(const Model<S>& m) : map_(dual_model(m)), bits_(m.bits) {}

template <class S>
LinearStep<S> TangentMap<S>::step(const State<S>& s) const {
  using D = Dual<S>;
  State<D> ds{D::variable(s.theta, 0), D::variable(s.v, 1)};
  ds.knot = s.knot;
  StepResult<D> r = map_.step(ds);
  LinearStep<S> out;
  out.contracted = r.kind != EventKind::impact && all_zero(r.next.theta) && all_zero(r.next.v);
  out.next.theta = std::move(r.next.theta.v);
  out.next.v = std::move(r.next.v.v);
  out.next.knot = r.next.knot;
  out.tau = std::move(r.tau.v);
  out.periods = r.periods;
  out.kind = r.kind;
  out.segment = r.segment;
  out.J = {std::move(r.next.theta.d[0]), std::move(r.next.theta.d[1]), std::move(r.next.v.d[0]), std::move(r.next.v.d[1])};
  return out;
}

template <class S>
LinearOrbit<S> TangentMap<S>::steps(const State<S>& s, long q) const {
  LinearOrbit<S> o;
  o.J = identity2<S>(ScalarTraits<S>::bits(s.v));
  o.points.push_back(s);
  for (long i = 0; i < q; ++i) {
    LinearStep<S> st = step(o.points.back());
    o.J = st.J * o.J;
    o.periods.push_back(st.periods);
    o.kinds.push_back(st.kind);
    o.contracted = o.contracted || st.contracted;
    o.points.push_back(std::move(st.next));
  }
  return o;
}

template <class S>
double Eigen2<S>::modulus(int i) const {
  const double r = ScalarTraits<S>::to_double(re[i]), m = ScalarTraits<S>::to_double(im[i]);
  return std::hypot(r, m);
}

template <class S>
Eigen2<S> eigenvalues(const Mat2<S>& m) {
  using Tr = ScalarTraits<S>;
  using std::sqrt;
  const long bits = Tr::bits(m.a11);
  const S zero = Tr::from_int(0, bits);
  const S h = (m.a11 + m.a22) / 2;
  const S det = m.a11 * m.a22 - m.a12 * m.a21;
  const S half_diff = (m.a11 - m.a22) / 2;
  const S disc = half_diff * half_diff + m.a12 * m.a21;  // (tr/2)^2 - det, better conditioned
  Eigen2<S> e;
  if (Tr::likely_negative(disc)) {
    const S w = sqrt(-disc);
    e.complex = true;
    e.re[0] = h;
    e.im[0] = w;
    e.re[1] = h;
    e.im[1] = -w;
    return e;
  }
  const S w = sqrt(disc);
  S l1 = Tr::likely_negative(h) ? S(h - w) : S(h + w);  // the larger modulus, no cancellation
  S l2 = Tr::is_zero(l1) == Truth::yes ? S(h - w) : S(det / l1);
  e.re[0] = std::move(l1);
  e.re[1] = std::move(l2);
  e.im[0] = zero;
  e.im[1] = zero;
  return e;
}

#define BOUNCER_X(S, kind)                                       \
  template Model<Dual<S>> dual_model<S>(const Model<S>&);        \
  template class TangentMap<S>;                                  \
  template Eigen2<S> eigenvalues<S>(const Mat2<S>&);             \
  template struct Eigen2<S>;
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
