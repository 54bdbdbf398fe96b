#include "bouncer/analysis/periodic.hpp"
#include "bouncer/model/trapping.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace bouncer {

double veldep_fixed_point_a(double c, long p) {
  // g(a) = 2^(5/3) c arccoth(ap/8)^(5/3) - 4 - ap/2: +inf as a -> 8/p+, -inf as a -> inf,
  // strictly decreasing (both terms decrease), so one root.
  auto g = [&](double a) { return paper::veldep_fixed_v(a, c, p) - a * p / 2; };
  double lo = 8.0 / p * (1 + 1e-12), hi = 1e9;
  if (!(g(lo) > 0) || !(g(hi) < 0)) return std::nan("");
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (g(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

namespace {

template <class T>
using Tr = ScalarTraits<T>;

template <class T>
T wrap_half(const T& d, long bits) {  // into [-1/2, 1/2)
  const T half = Tr<T>::from_int(1, bits) / 2;
  return d - Tr<T>::floor(d + half);
}

template <class T>
T wrap_unit(const T& x) {  // into [0, 1)
  return x - Tr<T>::floor(x);
}

template <class T>
double residual_norm(const T& ft, const T& fv, const T& v) {
  const double scale = std::max(1.0, std::fabs(Tr<T>::to_double(v)));
  return std::max(std::fabs(Tr<T>::to_double(ft)), std::fabs(Tr<T>::to_double(fv)) / scale);
}

template <class T>
bool valid_state(const Model<T>& m, const State<T>& s) {
  if (!Tr<T>::is_finite(s.theta) || !Tr<T>::is_finite(s.v)) return false;
  return !(s.v < m.wall.velocity_at(s.theta));
}

template <class T>
struct Eval {
  LinearOrbit<T> orbit;
  T ft, fv;
  double norm = 0;
};

template <class T>
std::optional<Eval<T>> evaluate(const TangentMap<T>& tm, const State<T>& x, long q, long bits) {
  try {
    Eval<T> e{tm.steps(x, q), {}, {}, 0};
    const State<T>& end = e.orbit.points.back();
    e.ft = wrap_half<T>(end.theta - x.theta, bits);
    e.fv = end.v - x.v;
    e.norm = residual_norm(e.ft, e.fv, x.v);
    if (!std::isfinite(e.norm)) return std::nullopt;
    return e;
  } catch (const Undecided&) {
    return std::nullopt;
  }
}

// The residual norm of evaluate() from the plain map, without the Jacobian: the dual map is
// the plain map on values bit for bit (tests/test_jacobian.cpp), so this is evaluate()'s
// norm, and nullopt exactly where evaluate() gives nullopt. The line search tries
// steps with it and differentiates only the step it accepts: a Newton run that creeps along
// a discontinuity (a trial parameter past a border collision, where the corrector fails)
// halves its steps ~20 times per iteration, and the tangent step costs 2-3x the plain one.
template <class T>
std::optional<double> residual_only(const ImpactMap<T>& map, const State<T>& x, long q, long bits) {
  try {
    State<T> y = x;
    for (long i = 0; i < q; ++i) y = map.step(y).next;
    const double norm = residual_norm(wrap_half<T>(y.theta - x.theta, bits), T(y.v - x.v), x.v);
    if (!std::isfinite(norm)) return std::nullopt;
    return norm;
  } catch (const Undecided&) {
    return std::nullopt;
  }
}

// Truncated pseudo-inverse solve of A dx = b for a 2x2 A (closed-form SVD via A^T A).
template <class T>
void pinv_solve(const Mat2<T>& A, const T& b0, const T& b1, double rcond, T& x0, T& x1, bool& dropped) {
  using std::sqrt;
  const long bits = Tr<T>::bits(A.a11);
  // M = A^T A = [[p, r], [r, s]]; g = A^T b
  const T p = A.a11 * A.a11 + A.a21 * A.a21;
  const T s = A.a12 * A.a12 + A.a22 * A.a22;
  const T r = A.a11 * A.a12 + A.a21 * A.a22;
  const T g0 = A.a11 * b0 + A.a21 * b1;
  const T g1 = A.a12 * b0 + A.a22 * b1;
  const T m = (p + s) / 2;
  const T hd = (p - s) / 2;
  const T d = sqrt(hd * hd + r * r);
  const T l1 = m + d;                       // largest eigenvalue of M (>= 0)
  const T det = p * s - r * r;
  const T l2 = Tr<T>::is_zero(l1) == Truth::yes ? l1 : det / l1;
  // eigenvector of l1: (r, l1 - p) or (l1 - s, r), the longer one
  T e0 = r, e1 = l1 - p;
  T f0 = l1 - s, f1 = r;
  if (Tr<T>::to_double(e0 * e0 + e1 * e1) < Tr<T>::to_double(f0 * f0 + f1 * f1)) {
    e0 = f0;
    e1 = f1;
  }
  T en = sqrt(e0 * e0 + e1 * e1);
  if (Tr<T>::is_zero(en) == Truth::yes) {  // M is a multiple of the identity
    e0 = Tr<T>::from_int(1, bits);
    e1 = Tr<T>::from_int(0, bits);
  } else {
    e0 = e0 / en;
    e1 = e1 / en;
  }
  const T o0 = -e1, o1 = e0;  // eigenvector of l2
  const double s1 = std::sqrt(std::max(0.0, Tr<T>::to_double(l1)));
  const double s2 = std::sqrt(std::max(0.0, Tr<T>::to_double(l2)));
  x0 = Tr<T>::from_int(0, bits);
  x1 = Tr<T>::from_int(0, bits);
  dropped = false;
  if (!(s1 > 0)) { dropped = true; return; }
  const T c1 = (e0 * g0 + e1 * g1) / l1;
  x0 = c1 * e0;
  x1 = c1 * e1;
  if (s2 > rcond * s1) {
    const T c2 = (o0 * g0 + o1 * g1) / l2;
    x0 = x0 + c2 * o0;
    x1 = x1 + c2 * o1;
  } else {
    dropped = true;
  }
}

// The state after the orbit's last sticking or ride step: its release state.
template <class T>
const State<T>& release_point(const LinearOrbit<T>& orbit, long q) {
  long last = -1;
  for (long i = 0; i < q; ++i)
    if (orbit.kinds[i] != EventKind::impact) last = i;
  return orbit.points[last + 1];
}

template <class T>
double mat_norm(const Mat2<T>& J) {
  double m = 0;
  for (const T* x : {&J.a11, &J.a12, &J.a21, &J.a22}) m = std::max(m, std::fabs(Tr<T>::to_double(*x)));
  return m;
}

}  // namespace

template <class T>
PeriodicOrbit<T> find_periodic(const Model<T>& m, long q, const State<T>& guess, const NewtonOptions& opt) {
  PeriodicOrbit<T> out;
  out.period = q;
  const long bits = m.bits;
  const double ulp = std::ldexp(1.0, -static_cast<int>(std::min(bits, 1000L)));
  const double rcond = bits > 53 ? std::pow(opt.rcond, static_cast<double>(std::min(bits, 1000L)) / 53) : opt.rcond;
  TangentMap<T> tm(m);
  const ImpactMap<T> map(m);
  State<T> x{wrap_unit(guess.theta), guess.v};
  // A guess a rounding error inside the wall starts at rest on it: a state on the wall
  // printed in decimal (a smooth wall's release state is irrational) rounds to either side,
  // by up to a double's rounding when it was computed in double (2^-48 relative allows 16
  // ulps of a double, or 1024 of T where T is wider).
  if (Tr<T>::is_finite(x.theta) && Tr<T>::is_finite(x.v)) {
    const T u = m.wall.velocity_at(x.theta);
    const double deficit = Tr<T>::to_double(T(u - x.v));
    if (deficit > 0 && deficit <= std::max(1024 * ulp, std::ldexp(1.0, -48)) * std::max(1.0, std::fabs(Tr<T>::to_double(u)))) x.v = u;
  }
  if (!valid_state(m, x)) {
    out.note = "the guess is not a valid state (v below the wall velocity)";
    return out;
  }
  std::optional<Eval<T>> e = evaluate(tm, x, q, bits);
  if (!e) {
    out.note = "the map could not be iterated from the guess";
    return out;
  }
  bool dropped_any = false;
  for (long it = 0; it < opt.max_iter; ++it) {
    out.iterations = it;
    const double scale = std::max(1.0, std::fabs(Tr<T>::to_double(x.v)));
    out.tolerance = 256 * ulp * std::max(1.0, mat_norm(e->orbit.J)) * scale;
    if (e->norm <= out.tolerance) {
      out.converged = true;
      break;
    }
    // Through a sticking or ride step the orbit reaches the release state R, where P^q is
    // locally constant: if R returns to itself exactly, R is the orbit (no Newton step lands
    // on a release bit for bit, and beside a smooth wall's release the step is rounding noise).
    if (e->orbit.contracted) {
      State<T> R = release_point(e->orbit, q);
      std::optional<Eval<T>> er = evaluate(tm, R, q, bits);
      if (er && er->norm == 0) {
        x = std::move(R);
        e = std::move(er);
        out.converged = true;
        break;
      }
    }
    Mat2<T> A = e->orbit.J;
    A.a11 = A.a11 - 1;
    A.a22 = A.a22 - 1;
    T dt, dv;
    bool dropped = false;
    pinv_solve(A, T(-e->ft), T(-e->fv), rcond, dt, dv, dropped);
    dropped_any = dropped_any || dropped;
    double t = 1;
    bool accepted = false;
    for (int h = 0; h < 40; ++h, t /= 2) {
      const T tt = Tr<T>::from_int(1, bits) / (1L << h);  // t = 2^-h
      State<T> y{wrap_unit<T>(x.theta + tt * dt), x.v + tt * dv};
      if (!valid_state(m, y)) continue;
      const std::optional<double> norm = residual_only(map, y, q, bits);
      if (!norm) continue;
      if (*norm < e->norm * (1 - 1e-4 * t) || *norm <= out.tolerance) {
        std::optional<Eval<T>> ey = evaluate(tm, y, q, bits);  // the same norm, with J
        if (!ey) continue;
        x = std::move(y);
        e = std::move(ey);
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      out.iterations = it + 1;
      const double scale2 = std::max(1.0, std::fabs(Tr<T>::to_double(x.v)));
      out.tolerance = 256 * ulp * std::max(1.0, mat_norm(e->orbit.J)) * scale2;
      out.converged = e->norm <= out.tolerance;
      if (!out.converged) out.note = "line search failed: no step decreases the residual";
      break;
    }
    out.iterations = it + 1;
  }
  if (!out.converged && out.note.empty()) {
    const double scale = std::max(1.0, std::fabs(Tr<T>::to_double(x.v)));
    out.tolerance = 256 * ulp * std::max(1.0, mat_norm(e->orbit.J)) * scale;
    out.converged = e->norm <= out.tolerance;
    if (!out.converged) out.note = "no convergence in " + std::to_string(opt.max_iter) + " iterations";
  }
  // An orbit through a sticking or ride step passes through the release state, where P^q
  // is locally constant: the true orbit starts there exactly (P^q(R) == R bit for bit).
  // Otherwise the residual only vanished in the limit at a discontinuity (e.g. creeping up
  // to a corner from the ride side): not an orbit.
  if (out.converged && e->orbit.contracted) {
    const State<T> R = release_point(e->orbit, q);
    std::optional<Eval<T>> er = evaluate(tm, R, q, bits);
    if (er && er->norm == 0) {
      e = std::move(er);
    } else {
      out.converged = false;
      out.note = "spurious: the residual vanishes only in the limit at a discontinuity (release of a sticking/ride step)";
    }
  }
  out.residual = e->norm;
  const LinearOrbit<T>& lo = e->orbit;
  out.points.assign(lo.points.begin(), lo.points.end() - 1);
  out.wall_periods = lo.periods;
  out.kinds = lo.kinds;
  out.J = lo.J;
  out.multipliers = eigenvalues(lo.J);
  out.marginal = std::fabs(out.multipliers.modulus(0) - 1) < 1e-6 || std::fabs(out.multipliers.modulus(1) - 1) < 1e-6;
  if (dropped_any && out.converged && out.marginal)
    out.note = "J^q - I was singular (a multiplier 1): solved across the family, theta of the family member is free";
  if (out.converged) {
    // Minimal period: the smallest divisor d of q with P^d(x) = x.
    out.minimal_period = q;
    const double tol = std::max(1e3 * out.tolerance, 1e-10);
    for (long d = 1; d < q; ++d) {
      if (q % d) continue;
      const T ft = wrap_half<T>(out.points[d % q].theta - out.points[0].theta, bits);
      const T fv = out.points[d % q].v - out.points[0].v;
      if (residual_norm(ft, fv, out.points[0].v) <= tol) {
        out.minimal_period = d;
        break;
      }
    }
  }
  return out;
}

template <class T>
PeriodicOrbit<T> search_periodic(const Model<T>& m, long q, const NewtonOptions& opt) {
  const long bits = m.bits;
  const double a = Tr<T>::to_double(m.a);
  double vmax = a * q / 2 + 16;
  // Constant eps < 1: no further than 1 above the trapping region (model/trapping.hpp). (The
  // velocity-dependent law keeps a q/2 + 16, the guesses its certified orbits were found from.)
  if (m.law == Law::constant)
    if (const auto top = trapping_top(m)) vmax = std::min(vmax, Tr<T>::to_double(*top) + 1);
  const int G = std::max(2, opt.grid);
  std::optional<PeriodicOrbit<T>> first, best, sticking;
  for (int i = 0; i < G; ++i) {
    for (int k = 0; k < G; ++k) {
      const double th = (k + 0.5) / G;
      State<T> g{Tr<T>::from_decimal(std::to_string(th), bits), Tr<T>::from_int(0, bits)};
      const double u = Tr<T>::to_double(m.wall.velocity_at(g.theta));
      const double v = u + 0.25 + (vmax - u - 0.25) * (i + 0.5) / G;
      g.v = Tr<T>::from_decimal(std::to_string(v), bits);
      PeriodicOrbit<T> o = find_periodic(m, q, g, opt);
      const bool contracted = std::any_of(o.kinds.begin(), o.kinds.end(), [](EventKind k) { return k != EventKind::impact; });
      if (o.converged && o.minimal_period == q && !contracted) return o;
      if (o.converged && o.minimal_period == q && !sticking) sticking = o;
      if (o.converged && !first) first = o;
      if (!best || o.residual < best->residual) best = std::move(o);
    }
  }
  if (sticking) {
    sticking->note += (sticking->note.empty() ? "" : "; ") + std::string("through a sticking/ride release (no other orbit found)");
    return *sticking;
  }
  if (first) {
    first->note += (first->note.empty() ? "" : "; ") + std::string("only orbits of smaller minimal period found");
    return *first;
  }
  best->note += (best->note.empty() ? "" : "; ") + std::string("no guess of the grid converged");
  return *best;
}

#define BOUNCER_X(T, kind)                                                                                 \
  template PeriodicOrbit<T> find_periodic<T>(const Model<T>&, long, const State<T>&, const NewtonOptions&); \
  template PeriodicOrbit<T> search_periodic<T>(const Model<T>&, long, const NewtonOptions&);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
