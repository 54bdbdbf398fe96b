// Certified orbit enclosures: naive interval iteration and Lohner's QR method.
#include "bouncer/verify/enclosure.hpp"

#include <chrono>
#include <cmath>

#include "bouncer/base/cancel.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/verify/interval_dual.hpp"

namespace bouncer {

// The step for interval duals (Dual<S> over the enclosure scalars) is instantiated in
// model/map_instances.cpp, one type per translation unit.

const char* name(EnclosureMethod m) { return m == EnclosureMethod::naive ? "naive" : "lohner"; }

EnclosureMethod parse_enclosure_method(const std::string& field, const std::string& text) {
  if (text == "naive") return EnclosureMethod::naive;
  if (text == "lohner") return EnclosureMethod::lohner;
  throw InputError(field, "unknown method '" + text + "' (allowed: lohner, naive)");
}

Mpfi enclose(const mpq_class& lo, const mpq_class& hi, long bits) {
  Mpfr l(bits), h(bits);
  mpfr_set_q(l.get(), lo.get_mpq_t(), MPFR_RNDD);
  mpfr_set_q(h.get(), hi.get_mpq_t(), MPFR_RNDU);
  return Mpfi(l, h);
}

template <>
Mpfi enclose_as<Mpfi>(const mpq_class& lo, const mpq_class& hi, long bits) {
  return enclose(lo, hi, bits);
}

template <>
DoubleInterval enclose_as<DoubleInterval>(const mpq_class& lo, const mpq_class& hi, long) {
  const Mpfi x = enclose(lo, hi, 53);  // 53-bit ends are doubles exactly
  return {mpfr_get_d(&x.get()->left, MPFR_RNDD), mpfr_get_d(&x.get()->right, MPFR_RNDU)};
}

template <class S>
Model<S> interval_model_of(const ModelSpec& spec, long bits, const std::optional<std::pair<mpq_class, mpq_class>>& a_range) {
  Model<S> m = make_model<S>(spec, bits);
  if (a_range) m = with_parameter(m, Parameter::a, enclose_as<S>(a_range->first, a_range->second, bits));
  return m;
}

namespace {

// What the enclosure needs of a point type P = PointOfT<S> (Mpfr or double).
double to_double(const Mpfr& x) { return x.to_double(); }
double to_double(double x) { return x; }
template <class P>
P point(long n, long bits) {
  if constexpr (std::is_same_v<P, Mpfr>) return Mpfr(n, bits);
  else return static_cast<P>(n);
}
// A usable pivot: finite and non-zero.
bool usable(const Mpfr& x) { return !mpfr_zero_p(x.get()) && mpfr_number_p(x.get()); }
bool usable(double x) { return x != 0 && std::isfinite(x); }

template <class S>
S thin(const PointOfT<S>& x) { return S(x, x); }

// The interval step result inside a dual one (the values without the derivatives).
template <class S>
StepResult<S> values_of(const StepResult<Dual<S>>& d) {
  StepResult<S> r;
  r.next = State<S>{d.next.theta.v, d.next.v.v, d.next.knot};
  r.tau = d.tau.v;
  r.periods = d.periods;
  r.segment = d.segment;
  r.kind = d.kind;
  r.corner = d.corner;
  r.indirect = d.indirect;
  r.stick_segment = d.stick_segment;
  r.passed_upward_turn = d.passed_upward_turn;
  r.stuck_theta = d.stuck_theta.v;
  r.stuck_v = d.stuck_v.v;
  r.phase_bits_lost = d.phase_bits_lost;
  return r;
}

// The interval model with every parameter a constant (zero derivatives).
template <class S>
Model<Dual<S>> lift(const Model<S>& m) {
  return convert_model<Dual<S>>(m, [](const S& x) { return Dual<S>(x); });
}

// Intersection of two enclosures of the same exact set; if rounding made them disjoint
// (cannot happen for correct enclosures), keep the first.
template <class S>
S meet(const S& x, const S& y) {
  using Tr = ScalarTraits<S>;
  if (Tr::lt(x, y) == Truth::yes || Tr::lt(y, x) == Truth::yes) return x;
  return intersect(x, y);
}

}  // namespace

template <class S>
double box_width(const State<S>& s) {
  return std::max(to_double(s.theta.width()), to_double(s.v.width()));
}

template <class S>
struct OrbitEnclosureOf<S>::Impl {
  using P = PointOfT<S>;
  using D = Dual<S>;
  ImpactMap<S> map;
  std::optional<ImpactMap<D>> dmap;
  EnclosureMethod method;
  long bits;
  State<S> box;
  long long steps = 0, fallbacks = 0;
  // Lohner set c + B r.
  P c[2];
  P B[2][2];
  S r[2];

  Impl(const Model<S>& m, const State<S>& start, EnclosureMethod meth)
      : map(m), method(meth), bits(m.bits), box(start) {
    if (method == EnclosureMethod::lohner) {
      dmap.emplace(lift(m));
      reset_frame();
    }
  }

  Impl(const Model<S>& m, const ParallelogramOf<S>& start)
      : map(m), method(EnclosureMethod::lohner), bits(m.bits) {
    dmap.emplace(lift(m));
    for (int i = 0; i < 2; ++i) {
      c[i] = start.c[i];
      r[i] = start.r[i];
      for (int k = 0; k < 2; ++k) B[i][k] = start.B[i][k];
    }
    box = {thin<S>(c[0]) + thin<S>(B[0][0]) * r[0] + thin<S>(B[0][1]) * r[1],
           thin<S>(c[1]) + thin<S>(B[1][0]) * r[0] + thin<S>(B[1][1]) * r[1]};
  }

  // c = mid(box), B = I, r = box - c.
  void reset_frame() {
    c[0] = box.theta.mid();
    c[1] = box.v.mid();
    B[0][0] = point<P>(1, bits);
    B[0][1] = point<P>(0, bits);
    B[1][0] = point<P>(0, bits);
    B[1][1] = point<P>(1, bits);
    r[0] = box.theta - thin<S>(c[0]);
    r[1] = box.v - thin<S>(c[1]);
  }

  EnclosedStepOf<S> naive() {
    EnclosedStepOf<S> out;
    out.event = map.step(box);
    box = out.event.next;
    out.next = box;
    return out;
  }

  EnclosedStepOf<S> lohner() {
    using Tr = ScalarTraits<S>;
    using std::sqrt;
    // The knot mark travels with the box (the sine wall's release phase needs it to start).
    const State<D> ds{D::variable(box.theta, 0), D::variable(box.v, 1), box.knot};
    StepResult<D> rd = dmap->step(ds);  // decides every branch for the whole box
    EnclosedStepOf<S> out;
    out.event = values_of(rd);
    const State<S>& image = out.event.next;
    auto fall_back = [&](bool count) {
      box = image;
      reset_frame();
      if (count) ++fallbacks;
      out.next = box;
      out.fallback = count;
      return out;
    };
    // Sticking and ride steps end at a constant state (the release): nothing to transport.
    if (rd.kind != EventKind::impact) return fall_back(false);
    const S J[2][2] = {{rd.next.theta.d[0], rd.next.theta.d[1]}, {rd.next.v.d[0], rd.next.v.d[1]}};
    for (const auto& row : J)
      for (const S& x : row)
        if (!Tr::is_finite(x)) return fall_back(true);
    StepResult<S> yc;
    try {
      yc = map.step(State<S>{thin<S>(c[0]), thin<S>(c[1]), box.knot});
    } catch (const Undecided&) {
      return fall_back(true);
    }
    if (yc.kind != rd.kind) return fall_back(true);
    const S y[2] = {yc.next.theta, yc.next.v};

    // M = J B.
    S M[2][2];
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < 2; ++k) M[i][k] = J[i][0] * thin<S>(B[0][k]) + J[i][1] * thin<S>(B[1][k]);
    // New frame: Q of mid(M) with column pivoting by the side lengths of the set: the
    // column k of mid(M) scaled by width(r_k) is the image of the set's k-th side, and the
    // longer image side goes first (pivoting by the bare column norms aligns the frame
    // with a short side and brings the wrapping effect back).
    P m0[2] = {M[0][0].mid(), M[1][0].mid()}, m1[2] = {M[0][1].mid(), M[1][1].mid()};
    P n0 = sqrt(m0[0] * m0[0] + m0[1] * m0[1]), n1 = sqrt(m1[0] * m1[0] + m1[1] * m1[1]);
    const bool second = n1 * r[1].width() > n0 * r[0].width();
    const P* lead = second ? m1 : m0;
    const P& nl = second ? n1 : n0;
    P Q[2][2];
    if (!usable(nl)) {
      Q[0][0] = point<P>(1, bits); Q[0][1] = point<P>(0, bits); Q[1][0] = point<P>(0, bits); Q[1][1] = point<P>(1, bits);
    } else {
      Q[0][0] = lead[0] / nl; Q[1][0] = lead[1] / nl;
      Q[0][1] = -Q[1][0];     Q[1][1] = Q[0][0];
    }
    // Rigorous inverse of the (nearly orthogonal) point matrix Q.
    const S det = thin<S>(Q[0][0]) * thin<S>(Q[1][1]) - thin<S>(Q[0][1]) * thin<S>(Q[1][0]);
    if (Tr::is_zero(det) != Truth::no) return fall_back(true);
    const S Qi[2][2] = {{thin<S>(Q[1][1]) / det, -thin<S>(Q[0][1]) / det},
                        {-thin<S>(Q[1][0]) / det, thin<S>(Q[0][0]) / det}};
    P cn[2] = {y[0].mid(), y[1].mid()};
    S d[2] = {y[0] - thin<S>(cn[0]), y[1] - thin<S>(cn[1])};
    S rn[2];
    for (int i = 0; i < 2; ++i) {
      S A0 = Qi[i][0] * M[0][0] + Qi[i][1] * M[1][0];
      S A1 = Qi[i][0] * M[0][1] + Qi[i][1] * M[1][1];
      rn[i] = A0 * r[0] + A1 * r[1] + (Qi[i][0] * d[0] + Qi[i][1] * d[1]);
    }
    for (int i = 0; i < 2; ++i) {
      c[i] = cn[i];
      r[i] = rn[i];
      for (int k = 0; k < 2; ++k) B[i][k] = Q[i][k];
    }
    const S th = thin<S>(c[0]) + thin<S>(B[0][0]) * r[0] + thin<S>(B[0][1]) * r[1];
    const S v = thin<S>(c[1]) + thin<S>(B[1][0]) * r[0] + thin<S>(B[1][1]) * r[1];
    if (!Tr::is_finite(th) || !Tr::is_finite(v)) return fall_back(true);
    box = {meet(image.theta, th), meet(image.v, v)};
    out.next = box;
    return out;
  }
};

template <class S>
OrbitEnclosureOf<S>::OrbitEnclosureOf(const Model<S>& model, const State<S>& start, EnclosureMethod method)
    : impl_(std::make_unique<Impl>(model, start, method)) {}
template <class S>
OrbitEnclosureOf<S>::OrbitEnclosureOf(const Model<S>& model, const ParallelogramOf<S>& start)
    : impl_(std::make_unique<Impl>(model, start)) {}
template <class S>
OrbitEnclosureOf<S>::~OrbitEnclosureOf() = default;
template <class S>
OrbitEnclosureOf<S>::OrbitEnclosureOf(OrbitEnclosureOf&&) noexcept = default;
template <class S>
OrbitEnclosureOf<S>& OrbitEnclosureOf<S>::operator=(OrbitEnclosureOf&&) noexcept = default;

template <class S>
EnclosedStepOf<S> OrbitEnclosureOf<S>::step() {
  EnclosedStepOf<S> s = impl_->method == EnclosureMethod::naive ? impl_->naive() : impl_->lohner();
  ++impl_->steps;
  return s;
}
template <class S>
const State<S>& OrbitEnclosureOf<S>::box() const { return impl_->box; }
template <class S>
ParallelogramOf<S> OrbitEnclosureOf<S>::set() const {
  using P = PointOfT<S>;
  ParallelogramOf<S> p;
  const Impl& m = *impl_;
  if (m.method == EnclosureMethod::lohner) {
    for (int i = 0; i < 2; ++i) {
      p.c[i] = m.c[i];
      p.r[i] = m.r[i];
      for (int k = 0; k < 2; ++k) p.B[i][k] = m.B[i][k];
    }
  } else {
    p.c[0] = m.box.theta.mid();
    p.c[1] = m.box.v.mid();
    p.r[0] = m.box.theta - thin<S>(p.c[0]);
    p.r[1] = m.box.v - thin<S>(p.c[1]);
    p.B[0][0] = point<P>(1, m.bits); p.B[0][1] = point<P>(0, m.bits);
    p.B[1][0] = point<P>(0, m.bits); p.B[1][1] = point<P>(1, m.bits);
  }
  return p;
}

template <class S>
bool jacobian_of_iterate(const Model<S>& model, const State<S>& x, long q, double J[2][2]) {
  // Approximate (only a frame is built from it): each step is linearized at the midpoint of
  // the previous image and the point is re-centred, so no interval width accumulates.
  using D = Dual<S>;
  const ImpactMap<D> map(lift(model));
  double P[2][2] = {{1, 0}, {0, 1}};
  PointOfT<S> c[2] = {x.theta.mid(), x.v.mid()};
  try {
    for (long i = 0; i < q; ++i) {
      const State<D> s{D::variable(thin<S>(c[0]), 0), D::variable(thin<S>(c[1]), 1)};
      const StepResult<D> r = map.step(s);
      const D* row[2] = {&r.next.theta, &r.next.v};
      double Sm[2][2];
      for (int a = 0; a < 2; ++a)
        for (int k = 0; k < 2; ++k) {
          if (!ScalarTraits<S>::is_finite(row[a]->d[k])) return false;
          Sm[a][k] = to_double(row[a]->d[k].mid());
        }
      const double N[2][2] = {{Sm[0][0] * P[0][0] + Sm[0][1] * P[1][0], Sm[0][0] * P[0][1] + Sm[0][1] * P[1][1]},
                              {Sm[1][0] * P[0][0] + Sm[1][1] * P[1][0], Sm[1][0] * P[0][1] + Sm[1][1] * P[1][1]}};
      for (int a = 0; a < 2; ++a)
        for (int k = 0; k < 2; ++k) P[a][k] = N[a][k];
      c[0] = r.next.theta.v.mid();
      c[1] = r.next.v.v.mid();
    }
  } catch (const Undecided&) {
    return false;
  }
  for (int a = 0; a < 2; ++a)
    for (int k = 0; k < 2; ++k) {
      if (!std::isfinite(P[a][k])) return false;
      J[a][k] = P[a][k];
    }
  return true;
}

template <class S>
long long OrbitEnclosureOf<S>::steps() const { return impl_->steps; }
template <class S>
long long OrbitEnclosureOf<S>::fallbacks() const { return impl_->fallbacks; }
template <class S>
EnclosureMethod OrbitEnclosureOf<S>::method() const { return impl_->method; }

template <class S>
Horizon certified_horizon(const ModelSpec& spec, const InitialCondition& start, long bits, EnclosureMethod method,
                          long long max_steps) {
  const auto t0 = std::chrono::steady_clock::now();
  Horizon h;
  OrbitEnclosureOf<S> orbit(interval_model_of<S>(spec, bits), make_state<S>(start, bits), method);
  try {
    while (h.steps < max_steps) {
      throw_if_cancelled(h.steps);
      orbit.step();
      ++h.steps;
    }
    h.reached_max = true;
  } catch (const Undecided& u) {
    h.reason = u.what();
  }
  h.seconds = detail::seconds_since(t0);
  return h;
}

#define BOUNCER_X(S, kind)                                                                                \
  template Model<S> interval_model_of<S>(const ModelSpec&, long, const std::optional<std::pair<mpq_class, mpq_class>>&); \
  template class OrbitEnclosureOf<S>;                                                                        \
  template bool jacobian_of_iterate<S>(const Model<S>&, const State<S>&, long, double[2][2]);               \
  template double box_width<S>(const State<S>&);                                                             \
  template Horizon certified_horizon<S>(const ModelSpec&, const InitialCondition&, long, EnclosureMethod, long long);
BOUNCER_FOR_EACH_ENCLOSURE_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
