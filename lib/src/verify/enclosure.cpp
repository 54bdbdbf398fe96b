// Certified orbit enclosures: naive interval iteration and Lohner's QR method.
#include "bouncer/verify/enclosure.hpp"

#include <chrono>
#include <cmath>

#include "bouncer/model/spec.hpp"
#include "bouncer/verify/interval_dual.hpp"
// Instantiate the step for interval duals (Dual<S> over the enclosure scalars).
#include "bouncer/model/impact_map_impl.hpp"

namespace bouncer {

#define BOUNCER_X(S, kind) template class ImpactMap<Dual<S>>;
BOUNCER_FOR_EACH_ENCLOSURE_SCALAR(BOUNCER_X)
#undef BOUNCER_X

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

Model<Mpfi> interval_model(const ModelSpec& spec, long bits, const std::optional<std::pair<mpq_class, mpq_class>>& a_range) {
  Model<Mpfi> m = make_model<Mpfi>(spec, bits);
  if (a_range) {
    m = with_parameter(m, Parameter::a, enclose(a_range->first, a_range->second, bits));
  }
  return m;
}

double box_width(const State<Mpfi>& s) {
  return std::max(s.theta.width().to_double(), s.v.width().to_double());
}

namespace {

// The interval model with every parameter a constant (zero derivatives).
// The interval step result inside a dual one (the values without the derivatives).
StepResult<Mpfi> values_of(const StepResult<IDual>& d) {
  StepResult<Mpfi> r;
  r.next = State<Mpfi>{d.next.theta.v, d.next.v.v, d.next.knot};
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

Model<IDual> lift(const Model<Mpfi>& m) {
  return convert_model<IDual>(m, [](const Mpfi& x) { return IDual(x); });
}

Mpfi thin(const Mpfr& x) { return Mpfi(x, x); }

// Intersection of two enclosures of the same exact set; if rounding made them disjoint
// (cannot happen for correct enclosures), keep the first.
Mpfi meet(const Mpfi& x, const Mpfi& y) {
  using Tr = ScalarTraits<Mpfi>;
  if (Tr::lt(x, y) == Truth::yes || Tr::lt(y, x) == Truth::yes) return x;
  return intersect(x, y);
}

}  // namespace

struct OrbitEnclosure::Impl {
  ImpactMap<Mpfi> map;
  std::optional<ImpactMap<IDual>> dmap;
  EnclosureMethod method;
  long bits;
  State<Mpfi> box;
  long long steps = 0, fallbacks = 0;
  // Lohner set c + B r.
  Mpfr c[2];
  Mpfr B[2][2];
  Mpfi r[2];

  Impl(const Model<Mpfi>& m, const State<Mpfi>& start, EnclosureMethod meth)
      : map(m), method(meth), bits(m.bits), box(start) {
    if (method == EnclosureMethod::lohner) {
      dmap.emplace(lift(m));
      reset_frame();
    }
  }

  Impl(const Model<Mpfi>& m, const Parallelogram& start)
      : map(m), method(EnclosureMethod::lohner), bits(m.bits) {
    dmap.emplace(lift(m));
    for (int i = 0; i < 2; ++i) {
      c[i] = start.c[i];
      r[i] = start.r[i];
      for (int k = 0; k < 2; ++k) B[i][k] = start.B[i][k];
    }
    box = {thin(c[0]) + thin(B[0][0]) * r[0] + thin(B[0][1]) * r[1],
           thin(c[1]) + thin(B[1][0]) * r[0] + thin(B[1][1]) * r[1]};
  }

  // c = mid(box), B = I, r = box - c.
  void reset_frame() {
    c[0] = box.theta.mid();
    c[1] = box.v.mid();
    B[0][0] = Mpfr(1, bits);
    B[0][1] = Mpfr(0, bits);
    B[1][0] = Mpfr(0, bits);
    B[1][1] = Mpfr(1, bits);
    r[0] = box.theta - thin(c[0]);
    r[1] = box.v - thin(c[1]);
  }

  EnclosedStep naive() {
    EnclosedStep out;
    out.event = map.step(box);
    box = out.event.next;
    out.next = box;
    return out;
  }

  EnclosedStep lohner() {
    using Tr = ScalarTraits<Mpfi>;
    const State<IDual> ds{IDual::variable(box.theta, 0), IDual::variable(box.v, 1)};
    StepResult<IDual> rd = dmap->step(ds);  // decides every branch for the whole box
    EnclosedStep out;
    out.event = values_of(rd);
    const State<Mpfi>& image = out.event.next;
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
    const Mpfi J[2][2] = {{rd.next.theta.d[0], rd.next.theta.d[1]}, {rd.next.v.d[0], rd.next.v.d[1]}};
    for (const auto& row : J)
      for (const Mpfi& x : row)
        if (!Tr::is_finite(x)) return fall_back(true);
    StepResult<Mpfi> yc;
    try {
      yc = map.step(State<Mpfi>{thin(c[0]), thin(c[1])});
    } catch (const Undecided&) {
      return fall_back(true);
    }
    if (yc.kind != rd.kind) return fall_back(true);
    const Mpfi y[2] = {yc.next.theta, yc.next.v};

    // M = J B.
    Mpfi M[2][2];
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < 2; ++k) M[i][k] = J[i][0] * thin(B[0][k]) + J[i][1] * thin(B[1][k]);
    // New frame: Q of mid(M) with column pivoting by the side lengths of the set: the
    // column k of mid(M) scaled by width(r_k) is the image of the set's k-th side, and the
    // longer image side goes first (pivoting by the bare column norms aligns the frame
    // with a short side and brings the wrapping effect back).
    Mpfr m0[2] = {M[0][0].mid(), M[1][0].mid()}, m1[2] = {M[0][1].mid(), M[1][1].mid()};
    Mpfr n0 = sqrt(m0[0] * m0[0] + m0[1] * m0[1]), n1 = sqrt(m1[0] * m1[0] + m1[1] * m1[1]);
    const bool second = n1 * r[1].width() > n0 * r[0].width();
    const Mpfr* lead = second ? m1 : m0;
    const Mpfr& nl = second ? n1 : n0;
    Mpfr Q[2][2];
    if (mpfr_zero_p(nl.get()) || !mpfr_number_p(nl.get())) {
      Q[0][0] = Mpfr(1, bits); Q[0][1] = Mpfr(0, bits); Q[1][0] = Mpfr(0, bits); Q[1][1] = Mpfr(1, bits);
    } else {
      Q[0][0] = lead[0] / nl; Q[1][0] = lead[1] / nl;
      Q[0][1] = -Q[1][0];     Q[1][1] = Q[0][0];
    }
    // Rigorous inverse of the (nearly orthogonal) point matrix Q.
    const Mpfi det = thin(Q[0][0]) * thin(Q[1][1]) - thin(Q[0][1]) * thin(Q[1][0]);
    if (certainly(Tr::is_zero(det)) || Tr::is_zero(det) == Truth::unknown) return fall_back(true);
    const Mpfi Qi[2][2] = {{thin(Q[1][1]) / det, -thin(Q[0][1]) / det}, {-thin(Q[1][0]) / det, thin(Q[0][0]) / det}};
    Mpfr cn[2] = {y[0].mid(), y[1].mid()};
    Mpfi d[2] = {y[0] - thin(cn[0]), y[1] - thin(cn[1])};
    Mpfi rn[2];
    for (int i = 0; i < 2; ++i) {
      Mpfi A0 = Qi[i][0] * M[0][0] + Qi[i][1] * M[1][0];
      Mpfi A1 = Qi[i][0] * M[0][1] + Qi[i][1] * M[1][1];
      rn[i] = A0 * r[0] + A1 * r[1] + (Qi[i][0] * d[0] + Qi[i][1] * d[1]);
    }
    for (int i = 0; i < 2; ++i) {
      c[i] = cn[i];
      r[i] = rn[i];
      for (int k = 0; k < 2; ++k) B[i][k] = Q[i][k];
    }
    const Mpfi th = thin(c[0]) + thin(B[0][0]) * r[0] + thin(B[0][1]) * r[1];
    const Mpfi v = thin(c[1]) + thin(B[1][0]) * r[0] + thin(B[1][1]) * r[1];
    if (!Tr::is_finite(th) || !Tr::is_finite(v)) return fall_back(true);
    box = {meet(image.theta, th), meet(image.v, v)};
    out.next = box;
    return out;
  }
};

OrbitEnclosure::OrbitEnclosure(const Model<Mpfi>& model, const State<Mpfi>& start, EnclosureMethod method)
    : impl_(std::make_unique<Impl>(model, start, method)) {}
OrbitEnclosure::~OrbitEnclosure() = default;
OrbitEnclosure::OrbitEnclosure(OrbitEnclosure&&) noexcept = default;
OrbitEnclosure& OrbitEnclosure::operator=(OrbitEnclosure&&) noexcept = default;

EnclosedStep OrbitEnclosure::step() {
  EnclosedStep s = impl_->method == EnclosureMethod::naive ? impl_->naive() : impl_->lohner();
  ++impl_->steps;
  return s;
}
OrbitEnclosure::OrbitEnclosure(const Model<Mpfi>& model, const Parallelogram& start)
    : impl_(std::make_unique<Impl>(model, start)) {}
const State<Mpfi>& OrbitEnclosure::box() const { return impl_->box; }
Parallelogram OrbitEnclosure::set() const {
  Parallelogram p;
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
    p.r[0] = m.box.theta - thin(p.c[0]);
    p.r[1] = m.box.v - thin(p.c[1]);
    p.B[0][0] = Mpfr(1, m.bits); p.B[0][1] = Mpfr(0, m.bits);
    p.B[1][0] = Mpfr(0, m.bits); p.B[1][1] = Mpfr(1, m.bits);
  }
  return p;
}

bool jacobian_of_iterate(const Model<Mpfi>& model, const State<Mpfi>& x, long q, double J[2][2]) {
  // Approximate (only a frame is built from it): each step is linearized at the midpoint of
  // the previous image and the point is re-centred, so no interval width accumulates.
  const ImpactMap<IDual> map(lift(model));
  double P[2][2] = {{1, 0}, {0, 1}};
  Mpfr c[2] = {x.theta.mid(), x.v.mid()};
  try {
    for (long i = 0; i < q; ++i) {
      const State<IDual> s{IDual::variable(thin(c[0]), 0), IDual::variable(thin(c[1]), 1)};
      const StepResult<IDual> r = map.step(s);
      const IDual* row[2] = {&r.next.theta, &r.next.v};
      double S[2][2];
      for (int a = 0; a < 2; ++a)
        for (int k = 0; k < 2; ++k) {
          if (!ScalarTraits<Mpfi>::is_finite(row[a]->d[k])) return false;
          S[a][k] = row[a]->d[k].mid().to_double();
        }
      const double N[2][2] = {{S[0][0] * P[0][0] + S[0][1] * P[1][0], S[0][0] * P[0][1] + S[0][1] * P[1][1]},
                              {S[1][0] * P[0][0] + S[1][1] * P[1][0], S[1][0] * P[0][1] + S[1][1] * P[1][1]}};
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

long long OrbitEnclosure::steps() const { return impl_->steps; }
long long OrbitEnclosure::fallbacks() const { return impl_->fallbacks; }
EnclosureMethod OrbitEnclosure::method() const { return impl_->method; }

Horizon certified_horizon(const ModelSpec& spec, const InitialCondition& start, long bits, EnclosureMethod method,
                          long long max_steps) {
  const auto t0 = std::chrono::steady_clock::now();
  Horizon h;
  OrbitEnclosure orbit(interval_model(spec, bits), make_state<Mpfi>(start, bits), method);
  try {
    while (h.steps < max_steps) {
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

}  // namespace bouncer
