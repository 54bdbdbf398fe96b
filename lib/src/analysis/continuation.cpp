#include "bouncer/analysis/continuation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "bouncer/base/text.hpp"
#include "bouncer/model/impact_map_impl.hpp"  // the sine gap (detail::sine_gap) of the smooth margins
#include "bouncer/scalar/decimal.hpp"

namespace bouncer {

const char* name(Margin m) {
  switch (m) {
    case Margin::knot: return "knot_distance";
    case Margin::clearance: return "clearance";
    case Margin::speed: return "impact_speed";
    case Margin::sticking: return "sticking_margin";
  }
  return "?";
}

const char* name(BeyondRelation r) {
  switch (r) {
    case BeyondRelation::none: return "none";
    case BeyondRelation::continuation: return "continuation";
    case BeyondRelation::other_branch: return "other_branch";
    case BeyondRelation::mother: return "mother";
    case BeyondRelation::unrelated: return "unrelated";
  }
  return "?";
}

const char* name(EndReason r) {
  switch (r) {
    case EndReason::range_end: return "range_end";
    case EndReason::border: return "border";
    case EndReason::fold: return "fold";
    case EndReason::doubling: return "doubling";
    case EndReason::event_change: return "event_change";
    case EndReason::period_collapse: return "period_collapse";
    case EndReason::lost: return "lost";
    case EndReason::max_points: return "max_points";
  }
  return "?";
}

const char* name(SmoothKind k) {
  switch (k) {
    case SmoothKind::fold: return "fold";
    case SmoothKind::period_doubling: return "period_doubling";
    case SmoothKind::neimark_sacker: return "neimark_sacker";
  }
  return "?";
}

std::string event_text(const std::vector<StepEvent>& events) {
  std::string s;
  for (const StepEvent& e : events) {
    if (!s.empty()) s += ' ';
    s += e.kind == EventKind::impact ? 'I' : e.kind == EventKind::sticking ? 'S' : 'R';
    if (!e.smooth_wall) s += std::to_string(e.segment);
    if (e.corner) s += 'c';
    if (e.indirect) s += '^';
  }
  return s;
}

bool same_cycle(const std::vector<StepEvent>& x, const std::vector<StepEvent>& y) {
  if (x.size() != y.size()) return false;
  const size_t n = x.size();
  for (size_t r = 0; r < std::max<size_t>(n, 1); ++r) {
    bool same = true;
    for (size_t i = 0; i < n && same; ++i) same = x[i].same_piece(y[(i + r) % n]);
    if (same) return true;
  }
  return false;
}

namespace {

template <class T>
using Tr = ScalarTraits<T>;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <class T>
T from_double(double x, long bits) {
  if constexpr (std::is_same_v<T, Mpfr>) {
    Mpfr r(static_cast<mpfr_prec_t>(bits));
    mpfr_set_d(r.get(), x, MPFR_RNDN);
    return r;
  } else {
    (void)bits;
    return T(x);
  }
}

template <class T>
T wrap_unit(const T& x) {
  return x - Tr<T>::floor(x);
}

// theta difference on the circle, in [-1/2, 1/2), as a double.
double circle_diff(double d) { return d - std::floor(d + 0.5); }

// The margins on a smooth wall (see Margin). The least local minimum of the gap
// g(s) = f0 + v s - a s^2/2 - f(theta0 + s) inside the flight (0, tau): the sign changes of
// g' from - to + on a grid of 1/128 period (g''' is bounded by 8 pi^3, so a minimum and a
// maximum closer than that are a tangency's unfolding, not missed in practice), located by
// bisection in double; g is then evaluated in T there (g' = 0 there, so the location's error
// enters g only to second order).
template <class T>
ImpactMargins smooth_margins_of_step(const Model<T>& m, const State<T>& from, const StepResult<T>& r) {
  ImpactMargins out;
  out.value.fill(kNaN);
  if (r.kind == EventKind::ride) return out;
  const Wall<T>& w = m.wall;
  const bool stuck = r.kind == EventKind::sticking;
  const T& th = stuck ? r.stuck_theta : r.next.theta;
  const T& vout = stuck ? r.stuck_v : r.next.v;
  // The flight: the step less the ride from the collision to the release (under a period).
  T tau = r.tau;
  if (stuck) tau = tau - wrap_unit<T>(r.next.theta - th);
  const T u = w.velocity_at(th);
  out.value[static_cast<int>(Margin::speed)] = Tr<T>::to_double(T(u - (from.v - m.a * tau)));
  if (m.law == Law::constant) {
    const T rebound = vout - u;
    const T G = m.a - w.two_pi * w.two_pi * Tr<T>::sin_2pi(th);
    T margin = 2 * rebound;
    if (Tr<T>::to_double(G) > 0) {
      const T left = Tr<T>::to_double(T(w.release - th)) >= 0 ? T(w.release - th) : T(w.release + 1 - th);
      margin = margin - (1 - m.eps) * G * left;
    }
    out.value[static_cast<int>(Margin::sticking)] = Tr<T>::to_double(margin);
  }
  // The map's own gap and its rate (model/impact_map_impl.hpp), the rate in double.
  const T f0 = Tr<T>::sin_2pi(from.theta);
  const detail::SineFlight<T> flight{from.theta, f0, from.v};
  const detail::SineFlight<double> flight_d{Tr<T>::to_double(from.theta), Tr<T>::to_double(f0), Tr<T>::to_double(from.v)};
  const double a = Tr<T>::to_double(m.a), tp = Tr<T>::to_double(w.two_pi), th0 = flight_d.phase;
  const auto rate = [&](double s) { return detail::sine_gap_rate(flight_d, a, tp, s); };
  const double tau_d = Tr<T>::to_double(tau), h = 1.0 / 128;
  double best = std::numeric_limits<double>::infinity();
  double prev_s = h, prev_rate = rate(h);
  for (long i = 2; i * h < tau_d && i < 1000000; ++i) {
    const double s = i * h, gs = rate(s);
    if (prev_rate < 0 && gs >= 0) {
      double lo = prev_s, hi = s;
      for (int k = 0; k < 60 && lo < hi; ++k) {
        const double mid = lo + (hi - lo) / 2;
        if (mid <= lo || mid >= hi) break;
        (rate(mid) < 0 ? lo : hi) = mid;
      }
      const T sm = from_double<T>(lo + (hi - lo) / 2, m.bits);
      const double g = Tr<T>::to_double(detail::sine_gap(flight, m.a, sm));
      if (g < best) {
        best = g;
        const double ph = th0 + lo;
        out.graze_theta = ph - std::floor(ph);
      }
    }
    prev_s = s;
    prev_rate = gs;
  }
  out.value[static_cast<int>(Margin::clearance)] = best;
  return out;
}

template <class T>
ImpactMargins margins_of_step(const Model<T>& m, const State<T>& from, const StepResult<T>& r) {
  if (m.wall.smooth()) return smooth_margins_of_step(m, from, r);
  ImpactMargins out;
  out.value.fill(kNaN);
  if (r.kind == EventKind::ride) return out;
  const Wall<T>& w = m.wall;
  const bool stuck = r.kind == EventKind::sticking;
  const int j = stuck ? r.stick_segment : r.segment;
  const T& th = stuck ? r.stuck_theta : r.next.theta;
  const T& vout = stuck ? r.stuck_v : r.next.v;
  // Flight time: the whole step, less the ride from the collision to the release knot
  // (shorter than one period: a ride ends at the next downward turn).
  T tau = r.tau;
  if (stuck) tau = tau - wrap_unit<T>(r.next.theta - th);
  // knot distance: to the nearer end of segment j
  const T d0 = th - w.start[j], d1 = w.end[j] - th;
  const bool near_start = !(d1 < d0);
  out.value[static_cast<int>(Margin::knot)] = Tr<T>::to_double(near_start ? d0 : d1);
  out.knot = near_start ? j : w.next(j);
  // relative impact speed from the flight: v^- = v0 - a tau, speed = u_j - v^-
  const T vminus = from.v - m.a * tau;
  out.value[static_cast<int>(Margin::speed)] = Tr<T>::to_double(T(w.velocity[j] - vminus));
  if (m.law == Law::constant)
    out.value[static_cast<int>(Margin::sticking)] =
        Tr<T>::to_double(T(vout - w.velocity[j] - m.collapse * (w.end[j] - th)));
  // clearance at every knot passed strictly inside the flight
  const int j0 = w.segment_of(from.theta);
  const T f0 = w.height_at(j0, from.theta);
  const double tau_d = Tr<T>::to_double(tau);
  double best = std::numeric_limits<double>::infinity();
  long evaluated = 0;
  for (int k = 0; k < w.segments(); ++k) {
    T t = wrap_unit<T>(w.start[k] - from.theta);
    if (!(Tr<T>::to_double(t) > 0)) t = t + 1;
    for (; Tr<T>::to_double(t) < tau_d && evaluated < 100000; t = t + 1, ++evaluated) {
      const T gap = f0 + from.v * t - m.a * t * t / 2 - w.height[k];
      const double g = Tr<T>::to_double(gap);
      if (g < best) {
        best = g;
        out.graze_knot = k;
      }
    }
  }
  out.value[static_cast<int>(Margin::clearance)] = best;
  return out;
}

// Newton's start for the orbit with these events in m, predicted at `predicted`. An orbit
// through a smooth wall's sticking (or ride) passes through the release state, which moves
// with the parameter along a curve: a prediction (a secant, or a point of another
// precision) lands off it, a hair above the wall, where the particle chatters instead of
// leaving and Newton fails. The release state of m is the orbit's point exactly, if the
// orbit persists.
template <class T>
State<T> newton_start(const Model<T>& m, const std::vector<StepEvent>& events, const State<T>& predicted) {
  const bool through_release =
      m.wall.smooth() && std::any_of(events.begin(), events.end(), [](const StepEvent& e) { return e.kind != EventKind::impact; });
  return through_release ? release_state(m) : predicted;
}

}  // namespace

template <class T>
BranchPoint<T> analyse_orbit(const Model<T>& m, Parameter p, PeriodicOrbit<T> orbit) {
  BranchPoint<T> b;
  b.param = parameter_of(m, p);
  const ImpactMap<T> map(m);
  const long q = static_cast<long>(orbit.points.size());
  b.min_margin.fill(kNaN);
  b.min_impact.fill(-1);
  for (long i = 0; i < q; ++i) {
    const StepResult<T> r = map.step(orbit.points[i]);
    b.events.push_back(step_event(r, m.wall.smooth()));
    b.margins.push_back(margins_of_step(m, orbit.points[i], r));
    for (int k = 0; k < kMargins; ++k) {
      // The sticking margin is signed (negative on a sticking step): its distance to 0.
      const double v = k == static_cast<int>(Margin::sticking) ? std::fabs(b.margins.back().value[k]) : b.margins.back().value[k];
      if (std::isnan(v)) continue;
      if (b.min_impact[k] < 0 || v < b.min_margin[k]) {
        b.min_margin[k] = v;
        b.min_impact[k] = static_cast<int>(i);
      }
    }
  }
  // In T, rounded to double at the end: next to a zero the sums cancel, and in double they
  // would keep only ~1e-16 of absolute accuracy (a bifurcation located by them no closer
  // than that at any precision).
  const Mat2<T>& J = orbit.J;
  const T tr = J.a11 + J.a22, det = J.a11 * J.a22 - J.a12 * J.a21;
  b.test_fold = Tr<T>::to_double(T(1 - tr + det));
  b.test_pd = Tr<T>::to_double(T(1 + tr + det));
  b.test_ns = Tr<T>::to_double(T(det - 1));
  b.stability = stability_of(orbit);
  b.orbit = std::move(orbit);
  return b;
}

namespace {

// What the corrector made of one trial value.
template <class T>
struct Trial {
  bool good = false;
  std::optional<BranchPoint<T>> point;  // good, or converged onto another piece
  enum class Why { none, no_convergence, period, events, jump, undecided } why = Why::none;
};

// How far the orbit is from its own shift by half a period: max_i |x_i - x_{i+q/2}| (the
// metric of state_distance); 0 for an orbit of period q/2 traversed twice.
template <class T>
double half_period_gap(const PeriodicOrbit<T>& o) {
  const size_t q = o.points.size(), h = q / 2;
  double gap = 0;
  for (size_t i = 0; i < q; ++i) gap = std::max(gap, state_distance(o.points[i], o.points[(i + h) % q]));
  return gap;
}

template <class T>
struct Continuer {
  const Model<T>& base;
  Parameter par;
  long q;
  const ContinuationOptions& opt;
  long bits;
  long runs = 0;
  double stop_rel = 0;  // > 0: locate to this relative width instead of the working precision

  Model<T> at(const T& p) const { return with_parameter(base, par, p); }

  // The predicted start point at parameter p from cur (and prev, when the same rotation).
  State<T> predict(const BranchPoint<T>& cur, const BranchPoint<T>* prev, const T& p) const {
    const State<T>& x = cur.orbit.points[0];
    if (!prev) return {x.theta, x.v};
    const State<T>& y = prev->orbit.points[0];
    const double dth = circle_diff(Tr<T>::to_double(T(x.theta - y.theta)));
    const double dv = Tr<T>::to_double(T(x.v - y.v));
    // A secant that moves by more than 0.1 per step is not to be trusted (a rotation of a
    // sticking orbit, or a jump): predict constant instead.
    if (std::fabs(dth) > 0.1 || std::fabs(dv) > 0.1 * std::max(1.0, std::fabs(Tr<T>::to_double(x.v))))
      return {x.theta, x.v};
    const T s = (p - cur.param) / (cur.param - prev->param);
    return {wrap_unit<T>(x.theta + s * from_double<T>(dth, bits)), x.v + s * (x.v - y.v)};
  }

  Trial<T> correct(const T& p, const BranchPoint<T>& ref, const State<T>& predicted) {
    Trial<T> t;
    ++runs;
    const Model<T> m = at(p);
    const State<T> guess = newton_start(m, ref.events, predicted);
    try {
      PeriodicOrbit<T> o = find_periodic(m, q, guess, opt.newton);
      if (!o.converged) {
        t.why = Trial<T>::Why::no_convergence;
        return t;
      }
      // Start the orbit at its point nearest to the prediction, so that points[i] (and
      // impact i) stay the same along the branch: Newton may converge onto another point
      // of the same orbit. (J stays that of the old start: a conjugate, with the same
      // trace, determinant and multipliers.)
      size_t nearest = 0;
      double dmin = std::numeric_limits<double>::infinity();
      for (size_t i = 0; i < o.points.size(); ++i) {
        const double dth = std::fabs(circle_diff(Tr<T>::to_double(T(o.points[i].theta - guess.theta))));
        const double dv = std::fabs(Tr<T>::to_double(T(o.points[i].v - guess.v))) / std::max(1.0, std::fabs(Tr<T>::to_double(guess.v)));
        if (std::max(dth, dv) < dmin) {
          dmin = std::max(dth, dv);
          nearest = i;
        }
      }
      if (nearest != 0 && o.points.size() == o.kinds.size() && o.points.size() == o.wall_periods.size()) {
        std::rotate(o.points.begin(), o.points.begin() + nearest, o.points.end());
        std::rotate(o.kinds.begin(), o.kinds.begin() + nearest, o.kinds.end());
        std::rotate(o.wall_periods.begin(), o.wall_periods.begin() + nearest, o.wall_periods.end());
      }
      BranchPoint<T> b = analyse_orbit(m, par, std::move(o));
      const bool period_ok = b.orbit.minimal_period == q;
      const bool events_ok = same_cycle(b.events, ref.events);
      // Distance of the nearest orbit point to the prediction (the orbit may be rotated).
      double dist = std::numeric_limits<double>::infinity();
      for (const State<T>& s : b.orbit.points) {
        const double dth = std::fabs(circle_diff(Tr<T>::to_double(T(s.theta - guess.theta))));
        const double dv = std::fabs(Tr<T>::to_double(T(s.v - guess.v))) / std::max(1.0, std::fabs(Tr<T>::to_double(guess.v)));
        dist = std::min(dist, std::max(dth, dv));
      }
      t.point = std::move(b);
      if (!period_ok) t.why = Trial<T>::Why::period;
      else if (!events_ok) t.why = Trial<T>::Why::events;
      else if (dist > 0.05) t.why = Trial<T>::Why::jump;
      else t.good = true;
    } catch (const Undecided&) {
      t.why = Trial<T>::Why::undecided;
    }
    return t;
  }

  double tolerance_rel() const {
    if (stop_rel > 0) return stop_rel;
    if constexpr (std::is_same_v<T, double>) return std::ldexp(1.0, -44);
    return std::ldexp(1.0, -static_cast<int>(std::min(bits - 12, 1000L)));
  }
  bool wide(const T& x, const T& y) const {
    const double w = std::fabs(Tr<T>::to_double(T(x - y)));
    return w > tolerance_rel() * std::max(1.0, std::fabs(Tr<T>::to_double(x)));
  }
  long max_bisections() const { return std::min(bits, 1000L) + 80; }

  // Regula falsi (Illinois) on a smooth test function between two accepted points whose
  // values have opposite signs; the corrector runs at every trial value.
  std::optional<Bifurcation<T>> locate_smooth(SmoothKind kind, const BranchPoint<T>& A, const BranchPoint<T>& B) {
    auto g = [kind](const BranchPoint<T>& b) {
      return kind == SmoothKind::fold ? b.test_fold : kind == SmoothKind::period_doubling ? b.test_pd : b.test_ns;
    };
    BranchPoint<T> lo = A, hi = B;
    double glo = g(lo), ghi = g(hi);
    int side = 0;
    Bifurcation<T> out{kind, lo.param, lo.param, hi.param, 0};
    for (long it = 0; it < max_bisections() && wide(lo.param, hi.param); ++it) {
      out.iterations = it + 1;
      double f = glo / (glo - ghi);
      if (!(f > 0.01 && f < 0.99)) f = 0.5;
      T p = lo.param + (hi.param - lo.param) * from_double<T>(f, bits);
      Trial<T> t = correct(p, lo, lo.orbit.points[0]);
      if (!t.good) {
        p = lo.param + (hi.param - lo.param) / 2;
        t = correct(p, lo, lo.orbit.points[0]);
        if (!t.good) break;
      }
      const double gp = g(*t.point);
      if (gp == 0) {
        lo = hi = *t.point;
        break;
      }
      if ((gp < 0) == (glo < 0)) {
        lo = std::move(*t.point);
        glo = gp;
        if (side == -1) ghi /= 2;
        side = -1;
      } else {
        hi = std::move(*t.point);
        ghi = gp;
        if (side == 1) glo /= 2;
        side = 1;
      }
    }
    out.param = lo.param + (hi.param - lo.param) / 2;
    out.bracket_lo = lo.param < hi.param ? lo.param : hi.param;
    out.bracket_hi = lo.param < hi.param ? hi.param : lo.param;
    return out;
  }

  // The tests between two accepted neighbours: a sign change of det(J -+ I) is a real
  // multiplier through +-1; of det J - 1 with a complex pair at both ends, Neimark-Sacker.
  void smooth_events(const BranchPoint<T>& A, const BranchPoint<T>& B, std::vector<Bifurcation<T>>& out) {
    auto flips = [](double x, double y) { return (x < 0 && y > 0) || (x > 0 && y < 0); };
    if (flips(A.test_fold, B.test_fold))
      if (auto b = locate_smooth(SmoothKind::fold, A, B)) out.push_back(*b);
    if (flips(A.test_pd, B.test_pd))
      if (auto b = locate_smooth(SmoothKind::period_doubling, A, B)) out.push_back(*b);
    if (A.orbit.multipliers.complex && B.orbit.multipliers.complex && flips(A.test_ns, B.test_ns))
      if (auto b = locate_smooth(SmoothKind::neimark_sacker, A, B)) out.push_back(*b);
  }

  std::string knot_text(int k) const { return base.wall.knot_exact[k].get_str(); }
  // A doubling end's a* from the period-q/2 orbit, where it is a simple zero of det(DP^{q/2} + I)
  // on an orbit that exists on both sides. Next to a* the period-q corrector cannot tell its
  // orbit from the period-q/2 one traversed twice (the residual there is ~ (mu - 1) x gap, under
  // Newton's tolerance for gaps up to ~1e-3), so the bisection on the period-q branch stops up
  // to ~1e-8 short of a* or past it. Here: the test function on the mother orbit (Newton from
  // the branch's last orbit) at windows around the end, 4x wider each, until its sign
  // changes; then bisection to the working precision. False (e unchanged) where this fails.
  bool locate_mother_doubling(BranchEnd<T>& e, const T& p0, const State<T>& x0) {
    const long h = q / 2;
    State<T> guess = x0;
    const auto test = [&](const T& p) -> std::optional<double> {
      try {
        const Model<T> m = at(p);
        const PeriodicOrbit<T> o = find_periodic(m, h, guess, opt.newton);
        ++runs;
        if (!o.converged || o.minimal_period != h) return std::nullopt;
        guess = o.points[0];
        return analyse_orbit(m, par, o).test_pd;
      } catch (const Undecided&) {
        return std::nullopt;
      }
    };
    const double scale = std::max(1.0, std::fabs(Tr<T>::to_double(p0)));
    const std::optional<double> f0 = test(p0);
    if (!f0 || *f0 == 0) return false;
    std::optional<T> lo, hi;  // lo: the test's sign is f0's; hi: the other sign
    for (double w = 1e-9 * scale; w <= opt.beyond * scale && !hi; w *= 4)
      for (const int side : {-1, 1}) {
        const T p = p0 + from_double<T>(side * w, bits);
        const std::optional<double> f = test(p);
        if (f && (*f > 0) != (*f0 > 0)) {
          hi = p;
          lo = p0;
          break;
        }
      }
    if (!hi) return false;
    for (long it = 0; it < max_bisections() && wide(*lo, *hi); ++it) {
      const T mid = *lo + (*hi - *lo) / 2;
      const std::optional<double> f = test(mid);
      if (!f) return false;
      (*f > 0) == (*f0 > 0) ? lo = mid : hi = mid;
    }
    e.bracket_lo = *lo < *hi ? *lo : *hi;
    e.bracket_hi = *lo < *hi ? *hi : *lo;
    e.param = e.bracket_lo + (e.bracket_hi - e.bracket_lo) / 2;
    return true;
  }

  // At a border a margin reaches 0 at a*, smoothly and linearly on the branch side, so
  // secant steps on it get to the tolerance in a few corrector runs where bisection takes
  // one per bit (~44 in double, ~116 at 128 bits), half of them trials past a*, where Newton
  // creeps along the border for hundreds of evaluations before it gives up (~50x a
  // converging run). The margin is the one that shrank the most since `first`. Its root r
  // is estimated by the secant through the last two accepted points; the step aims short of
  // r by twice the distance to the estimate from the two points before (the older
  // estimate's error, much larger than the newer one's while the secant converges), and
  // halfway to r without such an estimate, so that it lands on the branch side. Once r is
  // within half the tolerance, it aims just past it, to close the bracket. Nothing where the
  // step leaves (good, bad): the caller bisects or halves its step, so the bracket [good, bad]
  // is kept either way, and a margin that is not the cause, or a smooth end such as a fold,
  // costs at most one extra corrector run. `hist`: accepted points, the last one nearest.
  std::optional<T> border_secant(const std::vector<const BranchPoint<T>*>& hist, const T& bad, int dir,
                                 const BranchPoint<T>& first) const {
    const size_t n = hist.size();
    if (n < 2) return std::nullopt;
    const BranchPoint<T>& good = *hist[n - 1];
    for (const BranchPoint<T>* x : hist)
      if (x->margins.size() != first.margins.size()) return std::nullopt;
    int mi = -1, mk = -1;
    double least = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < good.margins.size(); ++i)
      for (int k = 0; k < kMargins; ++k) {
        const double now = std::fabs(good.margins[i].value[k]), then = std::fabs(first.margins[i].value[k]);
        if (!std::isfinite(now) || !std::isfinite(then) || !(then > 0)) continue;
        if (now / then < least) {
          least = now / then;
          mi = static_cast<int>(i);
          mk = k;
        }
      }
    if (mi < 0) return std::nullopt;
    // The margin at hist[j] and its parameter as an offset from good's.
    const auto g = [&](size_t j) { return std::fabs(hist[j]->margins[mi].value[mk]); };
    const auto x = [&](size_t j) { return Tr<T>::to_double(T(hist[j]->param - good.param)); };
    const auto root = [&](size_t j) {  // the secant through hist[j - 1] and hist[j]
      return x(j) + g(j) * (x(j) - x(j - 1)) / (g(j - 1) - g(j));
    };
    const double r = root(n - 1);
    if (!std::isfinite(r) || !(r * dir > 0)) return std::nullopt;
    const double tol = tolerance_rel() * std::max(1.0, std::fabs(Tr<T>::to_double(good.param)));
    double aim;
    if (std::fabs(r) < tol / 2) {
      aim = dir * 0.9 * tol;
    } else {
      const double older = n >= 3 ? root(n - 2) : kNaN;
      const double short_by = std::isfinite(older) ? std::max(tol / 4, 2 * std::fabs(r - older))
                                                         : std::numeric_limits<double>::infinity();
      aim = short_by < std::fabs(r) / 2 ? r - dir * short_by : r / 2;
    }
    T at = good.param + from_double<T>(aim, bits);
    if (dir > 0 ? (good.param < at && at < bad) : (bad < at && at < good.param)) return at;
    return std::nullopt;
  }

  // Locates the end between the accepted point `good` (with its predecessor) and the
  // refused value `bad` (secant steps on a vanishing margin, else bisection), names its
  // cause and looks beyond it.
  // `first` is the branch's start point: the margins are compared with their values there
  // (the accepted points may already have crept close to a* before the location begins).
  BranchEnd<T> locate_end(BranchPoint<T> good, std::optional<BranchPoint<T>> prev, T bad, int dir,
                          const BranchPoint<T>& first) {
    Trial<T> last_bad;
    bool have_bad = false;
    std::optional<BranchPoint<T>> prev2;
    for (long it = 0; it < max_bisections() && wide(good.param, bad); ++it) {
      T p = good.param + (bad - good.param) / 2;
      if (prev) {
        std::vector<const BranchPoint<T>*> hist{&*prev, &good};
        if (prev2) hist.insert(hist.begin(), &*prev2);
        if (std::optional<T> s = border_secant(hist, bad, dir, first)) p = std::move(*s);
      }
      Trial<T> t = correct(p, good, predict(good, prev ? &*prev : nullptr, p));
      if (t.good) {
        prev2 = std::move(prev);
        prev = std::move(good);
        good = std::move(*t.point);
      } else {
        bad = p;
        last_bad = std::move(t);
        have_bad = true;
      }
    }
    BranchEnd<T> e;
    e.param = good.param + (bad - good.param) / 2;
    e.bracket_lo = dir > 0 ? good.param : bad;
    e.bracket_hi = dir > 0 ? bad : good.param;
    e.last_point = good.orbit.points[0];
    // The cause: the margin (or det(J - I)) that shrank the most since the location began.
    double best = 1e-3;
    for (size_t i = 0; i < good.margins.size(); ++i)
      for (int k = 0; k < kMargins; ++k) {
        const double now = std::fabs(good.margins[i].value[k]), then = std::fabs(first.margins[i].value[k]);
        if (std::isnan(now) || std::isnan(then) || std::isinf(now) || !(then > 0)) continue;
        const double ratio = now / then;
        if (ratio < best) {
          best = ratio;
          e.reason = EndReason::border;
          e.margin = k;
          e.impact = static_cast<int>(i);
          e.knot = k == static_cast<int>(Margin::clearance) ? good.margins[i].graze_knot : good.margins[i].knot;
        }
      }
    // An impact landing on a knot also makes the clearance of a neighbouring flight vanish
    // at that knot (the flight starts or ends next to it), and a corner impact can make
    // several margins vanish together: among the margins within a factor 100 of the
    // smallest, name the most specific one (knot, sticking, speed, then clearance).
    if (e.reason == EndReason::border) {
      const double limit = best * 100;
      for (Margin pref : {Margin::knot, Margin::sticking, Margin::speed, Margin::clearance}) {
        const int k = static_cast<int>(pref);
        int found = -1;
        double least = limit;
        for (size_t i = 0; i < good.margins.size(); ++i) {
          const double now = std::fabs(good.margins[i].value[k]), then = std::fabs(first.margins[i].value[k]);
          if (std::isnan(now) || std::isnan(then) || std::isinf(now) || !(then > 0)) continue;
          if (now / then <= least) {
            least = now / then;
            found = static_cast<int>(i);
          }
        }
        if (found >= 0) {
          e.margin = k;
          e.impact = found;
          e.knot = pref == Margin::clearance ? good.margins[found].graze_knot : good.margins[found].knot;
          break;
        }
      }
    }
    const double fold_ratio = std::fabs(good.test_fold) / std::max(std::fabs(first.test_fold), 1e-300);
    if (fold_ratio < best && std::fabs(good.test_fold) < 1e-3) {
      e.reason = EndReason::fold;
      e.margin = e.impact = e.knot = -1;
    }
    if (e.margin < 0 && e.reason != EndReason::fold) {
      const auto why = have_bad ? last_bad.why : Trial<T>::Why::no_convergence;
      e.reason = why == Trial<T>::Why::period ? EndReason::period_collapse
                 : why == Trial<T>::Why::events ? EndReason::event_change
                                                : EndReason::lost;
    }
    // A period-2k orbit next to a period-k orbit traversed twice (its points q/2 apart
    // within kDoublingGap, where they are O(1) apart on an ordinary orbit) is at the period
    // doubling it is born from: near the doubling the gap shrinks like the square root of the
    // distance to a*, ~1e-6 where the end is located. The multiplier test sees a fold there
    // (the period-k orbit's -1 is the period-2k orbit's +1), or the corrector past a* falls
    // onto the period-k orbit (a period collapse to q/2).
    constexpr double kDoublingGap = 1e-3;
    bool on_mother = false;
    const bool onto_half = e.reason == EndReason::fold ||
                           (e.reason == EndReason::period_collapse && last_bad.point && 2 * last_bad.point->orbit.minimal_period == q);
    if (onto_half && q % 2 == 0 && half_period_gap(good.orbit) < kDoublingGap) {
      e.reason = EndReason::doubling;
      e.mother_period = q / 2;
      on_mother = locate_mother_doubling(e, good.param, good.orbit.points[0]);
    }
    const std::string i1 = std::to_string(e.impact + 1);
    switch (e.reason) {
      case EndReason::border:
        switch (static_cast<Margin>(e.margin)) {
          case Margin::knot: e.detail = "impact " + i1 + " reaches the knot theta = " + knot_text(e.knot); break;
          case Margin::clearance:
            if (base.wall.smooth()) e.graze_theta = good.margins[e.impact].graze_theta;
            e.detail = "flight " + i1 + " grazes the wall at " +
                       (base.wall.smooth() ? "theta ~ " + approximate_text(e.graze_theta) : "the knot theta = " + knot_text(e.knot));
            break;
          case Margin::speed: e.detail = "impact " + i1 + " reaches zero relative speed (touchdown)"; break;
          case Margin::sticking: e.detail = "impact " + i1 + " reaches the sticking threshold"; break;
        }
        break;
      case EndReason::fold: e.detail = "a multiplier reaches +1 where the orbit meets another and disappears"; break;
      case EndReason::doubling:
        e.detail = "the orbit closes onto a period-" + std::to_string(e.mother_period) +
                   " orbit traversed twice, whose multiplier reaches -1: the branch is born at its period doubling" +
                   (on_mother ? "; a* located on the period-" + std::to_string(e.mother_period) + " orbit" : std::string());
        break;
      case EndReason::period_collapse:
        e.detail = "the orbit falls onto one of minimal period " +
                   std::to_string(last_bad.point ? last_bad.point->orbit.minimal_period : 0);
        break;
      case EndReason::event_change:
        e.detail = "the event sequence changes to " + (last_bad.point ? event_text(last_bad.point->events) : std::string("?"));
        break;
      default: e.detail = "the corrector stops converging"; break;
    }
    look_beyond(e, good, dir);
    return e;
  }

  // Is the period-q orbit Newton finds beyond an end the branch's continuation, or another
  // orbit? At a knot the wall's velocity flips, so the image jumps and no nearby orbit can
  // continue the branch (issue 23): an orbit found there is typically one that already
  // exists on the branch side. Decided by running Newton from it at the branch side, as far
  // from a* as the look beyond: an orbit that persists there, away from the branch's own
  // orbit, is another branch; one far from every point of the branch orbit but not found on
  // the branch side is not decided ("unrelated"); one that stays next to the branch's last
  // orbit is a continuation (the events changed, the orbit did not jump).
  BeyondRelation relation_of(const PeriodicOrbit<T>& o, const std::vector<StepEvent>& events, const BranchPoint<T>& good,
                             int dir, double scale, bool doubling_end) const {
    // The nearest point of the branch's orbit to the orbit found (the rotation may differ).
    const auto nearest = [&](const State<T>& y) {
      double d = std::numeric_limits<double>::infinity();
      for (const State<T>& x : good.orbit.points) d = std::min(d, state_distance(x, y));
      return d;
    };
    constexpr double kJump = 1e-4;  // the ends are located to ~1e-12; a continuation moves ~ beyond
    // Beyond a doubling end Newton falls onto the orbit the branch was born from (the
    // period-q/2 orbit exists on both sides of its period doubling).
    // It moves faster than a continuation: kMother, looser than kJump.
    constexpr double kMother = 1e-2;
    if (doubling_end && o.minimal_period == q / 2 && nearest(o.points[0]) <= kMother) return BeyondRelation::mother;
    if (nearest(o.points[0]) <= kJump) return BeyondRelation::continuation;
    // On the branch side: the same orbit (its events) away from the branch's own orbit.
    const T back = good.param - from_double<T>(dir * opt.beyond * scale, bits);
    try {
      const Model<T> m = at(back);
      const PeriodicOrbit<T> before = find_periodic(m, q, o.points[0], opt.newton);
      if (before.converged && nearest(before.points[0]) > kJump && same_cycle(analyse_orbit(m, par, before).events, events))
        return BeyondRelation::other_branch;
    } catch (const Undecided&) {
    }
    return BeyondRelation::unrelated;
  }

  void look_beyond(BranchEnd<T>& e, const BranchPoint<T>& good, int dir) {
    if (!opt.classify_beyond) return;
    const double scale = std::max(1.0, std::fabs(Tr<T>::to_double(e.param)));
    e.beyond_param = e.param + from_double<T>(dir * opt.beyond * scale, bits);
    const double pb = Tr<T>::to_double(e.beyond_param);
    if (!(pb > 0) || (par == Parameter::eps && pb > 1)) {
      e.beyond_note = "the value beyond is outside the model's range";
      return;
    }
    const Model<T> m = at(e.beyond_param);
    try {
      const PeriodicOrbit<T> o = find_periodic(m, q, newton_start(m, good.events, good.orbit.points[0]), opt.newton);
      if (o.converged) {
        const std::vector<StepEvent> events = analyse_orbit(m, par, o).events;
        e.beyond_orbit = event_text(events);
        e.beyond_orbit_period = o.minimal_period;
        e.beyond_relation = relation_of(o, events, good, dir, scale, e.reason == EndReason::doubling);
      }
    } catch (const Undecided&) {
    }
    e.beyond = classify(ImpactMap<T>(m), good.orbit.points[0], opt.classify);
    e.beyond_done = true;
  }
};

}  // namespace

template <class T>
Branch<T> continue_branch(const Model<T>& m, Parameter p, long q, const State<T>& guess, const T& lo, const T& hi,
                          const ContinuationOptions& opt) {
  Branch<T> br;
  br.parameter = p;
  br.period = q;
  Continuer<T> c{m, p, q, opt, m.bits};
  PeriodicOrbit<T> o0 = find_periodic(m, q, guess, opt.newton);
  ++c.runs;
  if (!o0.converged) {
    br.note = "the guess does not converge to a period-" + std::to_string(q) + " orbit: " + o0.note;
    return br;
  }
  if (o0.minimal_period != q) {
    br.note = "the guess converges to an orbit of minimal period " + std::to_string(o0.minimal_period) + ", not " +
              std::to_string(q);
    return br;
  }
  const BranchPoint<T> start = analyse_orbit(m, p, std::move(o0));
  // Newton also "converges" onto v = wall velocity with a flight of a few ulps (a ride in
  // the limit: the velocity-dependent model's grid search finds (0.0625, 4 + 4e-13)). It
  // satisfies P(x) = x at every parameter value: not a branch.
  const double speed = start.min_margin[static_cast<int>(Margin::speed)];
  if (!std::isnan(speed) && speed < 1e-9 * std::max(1.0, std::fabs(Tr<T>::to_double(start.orbit.points[0].v)))) {
    std::ostringstream why;
    why << "the orbit touches down (relative impact speed " << speed << "): a ride in the limit, not a branch to follow";
    br.note = why.str();
    return br;
  }
  br.started = true;
  const double range = Tr<T>::to_double(T(hi - lo));
  const double h0 = opt.step > 0 ? opt.step : range / 100;
  // At most range/40 per step, so that a branch diagram has points all along it.
  const double hmax = std::max(h0, range / 40), hmin = h0 * 1e-4;
  std::vector<BranchPoint<T>> side[2];
  long accepted = 1;
  for (int d : {-1, 1}) {
    std::vector<BranchPoint<T>>& pts = side[d > 0];
    const T end = d > 0 ? hi : lo;
    BranchEnd<T>& e = d > 0 ? br.high : br.low;
    BranchPoint<T> cur = start;
    std::optional<BranchPoint<T>> prev;
    T refused = end;  // the nearest value refused since cur was accepted, if have_refused
    bool have_refused = false;
    double h = h0;
    for (;;) {
      if (!c.wide(cur.param, end)) {
        e.reason = EndReason::range_end;
        e.param = e.bracket_lo = e.bracket_hi = cur.param;
        e.detail = "the range ends";
        break;
      }
      // Half of the points for each direction (the high one also gets what the low one left).
      const long budget = d < 0 ? 1 + (opt.max_points - 1) / 2 : opt.max_points;
      if (accepted >= budget) {
        e.reason = EndReason::max_points;
        e.param = e.bracket_lo = e.bracket_hi = cur.param;
        e.detail = "the number of points reaches --max-points";
        break;
      }
      T t = cur.param + from_double<T>(d * h, m.bits);
      if (d > 0 ? !(t < end) : !(end < t)) t = end;
      // Short of a value already refused from cur.
      if (have_refused && (d > 0 ? !(t < refused) : !(refused < t))) t = cur.param + (refused - cur.param) / 2;
      // A margin heading for 0 within the step: aim at its root (border_secant), so that the
      // trial lands on the branch side of a border instead of past it.
      std::vector<const BranchPoint<T>*> hist;
      if (prev) {
        hist = {&*prev, &cur};
        if (pts.size() >= 3) hist.insert(hist.begin(), &pts[pts.size() - 3]);
        if (std::optional<T> s = c.border_secant(hist, t, d, start)) t = std::move(*s);
      }
      Trial<T> tr = c.correct(t, cur, c.predict(cur, prev ? &*prev : nullptr, t));
      if (tr.good) {
        BranchPoint<T> next = std::move(*tr.point);
        std::vector<Bifurcation<T>> found;
        c.smooth_events(cur, next, found);
        br.bifurcations.insert(br.bifurcations.end(), found.begin(), found.end());
        const bool easy = next.orbit.iterations <= 3;
        prev = std::move(cur);
        cur = std::move(next);
        pts.push_back(cur);
        ++accepted;
        have_refused = false;
        if (easy) h = std::min(h * 1.5, hmax);
        continue;
      }
      h /= 2;
      refused = t;
      have_refused = true;
      // A margin heading for 0 inside the refused step: the next step aims at its root.
      if (!hist.empty())
        if (std::optional<T> s = c.border_secant(hist, t, d, start)) h = std::min(h, std::fabs(Tr<T>::to_double(T(*s - cur.param))));
      if (h < hmin || !c.wide(cur.param, t)) {
        e = c.locate_end(cur, prev, t, d, start);
        break;
      }
    }
  }
  std::reverse(side[0].begin(), side[0].end());
  br.points = std::move(side[0]);
  br.start = br.points.size();
  br.points.push_back(start);
  br.points.insert(br.points.end(), side[1].begin(), side[1].end());
  std::sort(br.bifurcations.begin(), br.bifurcations.end(),
            [](const Bifurcation<T>& x, const Bifurcation<T>& y) { return x.param < y.param; });
  br.corrector_runs = c.runs;
  return br;
}

namespace {

template <class T>
mpq_class exact_of(const T& x) {
  if constexpr (std::is_same_v<T, double>) {
    return mpq_class(x);
  } else {
    const auto d = Decimal::parse(Tr<T>::to_string(x));  // round trip: within half an ulp
    if (!d) throw std::runtime_error("not a finite decimal: " + Tr<T>::to_string(x));
    return d->value();
  }
}

// The widened bracket (analysis/end_estimate.hpp) around out.center, T's computed value of
// p mantissa bits with a bracket `width` wide, from the value re-located in Mpfr (its bracket
// `refined_width` wide): radius 4 max(error, half T's bracket), plus the re-located bracket's
// half width and 2 ulps of T (the texts' roundings).
void widen(EndEstimate& out, const Mpfr& refined, const Mpfr& refined_width, double width, double scale, long p) {
  mpq_class r;
  mpfr_get_q(r.get_mpq_t(), refined.get());
  out.refined = Tr<Mpfr>::to_string(refined);
  out.error = mpq_class(abs(mpq_class(r - out.center))).get_d();
  out.radius = 4 * std::max(out.error, width / 2) + Tr<Mpfr>::to_double(refined_width) / 2 +
               std::ldexp(scale, -static_cast<int>(p) + 1);
  out.lo = out.center - mpq_class(out.radius);
  out.hi = out.center + mpq_class(out.radius);
  out.kind = EndEstimate::Kind::estimate;
}

// Re-locates one end of b (dir: +1 high, -1 low) in Mpfr and widens T's bracket
// (analysis/end_estimate.hpp). The Mpfr corrector starts from the branch's last accepted
// point on that side (inside the branch, far from a* compared with T's errors), which gives
// the reference events; T's bracket is then checked at the new precision: its branch side
// is stepped back (16x per step) until it is on the branch, its far side out until it is not,
// and the end is narrowed between them by locate_end, as in T (the same corrector, secant
// steps on a vanishing margin, bisection and cause).
template <class T>
EndEstimate estimate_one(const ModelSpec& spec, const Branch<T>& b, const BranchEnd<T>& e, int dir,
                         const ContinuationOptions& opt) {
  EndEstimate out;
  if (e.reason == EndReason::range_end || e.reason == EndReason::max_points) {
    out.kind = EndEstimate::Kind::given;
    out.center = exact_of(e.param);
    return out;
  }
  const long p = Tr<T>::bits(e.param), hb = p + 64;
  out.bits = hb;
  out.center = exact_of(e.param);
  ContinuationOptions o = opt;
  o.classify_beyond = false;
  const Model<Mpfr> base = make_model<Mpfr>(spec, hb);
  Continuer<Mpfr> c{base, b.parameter, b.period, o, hb};
  c.stop_rel = std::ldexp(1.0, -static_cast<int>(std::min(p + 24, 1000L)));
  const auto up = [hb](const T& x) { return Tr<Mpfr>::from_decimal(Tr<T>::to_string(x), hb); };
  const auto up_state = [&](const State<T>& x) { return State<Mpfr>{up(x.theta), up(x.v)}; };
  const BranchPoint<T>& edge = dir > 0 ? b.points.back() : b.points.front();
  // The references: the branch's last two accepted orbits, at hb bits (the secant through
  // them predicts the orbit at the first trial values: a constant prediction over the
  // distance to a* can leave Newton's basin, and a trial refused for that is a false end).
  const auto reference = [&](const BranchPoint<T>& x) -> std::optional<BranchPoint<Mpfr>> {
    try {
      const Model<Mpfr> m = c.at(up(x.param));
      PeriodicOrbit<Mpfr> orbit = find_periodic(m, b.period, newton_start(m, x.events, up_state(x.orbit.points[0])), o.newton);
      if (!orbit.converged || orbit.minimal_period != b.period) return std::nullopt;
      BranchPoint<Mpfr> r = analyse_orbit(m, b.parameter, std::move(orbit));
      if (!same_cycle(r.events, x.events)) return std::nullopt;
      return r;
    } catch (const Undecided&) {
      return std::nullopt;
    }
  };
  // A doubling end: a* re-located on the period-q/2 orbit at hb bits, as in T (next to a*
  // the period-q orbit is not a reference: see locate_mother_doubling).
  if (e.reason == EndReason::doubling) {
    BranchEnd<Mpfr> r;
    if (!c.locate_mother_doubling(r, up(edge.param), up_state(edge.orbit.points[0]))) {
      out.note = "at " + std::to_string(hb) + " bits the period-" + std::to_string(e.mother_period) +
                 " orbit's multiplier -1 is not bracketed next to the end";
      return out;
    }
    widen(out, r.param, Mpfr(r.bracket_hi - r.bracket_lo), Tr<T>::to_double(T(e.bracket_hi - e.bracket_lo)),
          std::max(1.0, std::fabs(Tr<T>::to_double(e.param))), p);
    return out;
  }
  const double scale = std::max(1.0, std::fabs(Tr<T>::to_double(e.param)));
  double w = std::max(Tr<T>::to_double(T(e.bracket_hi - e.bracket_lo)), std::ldexp(scale, -static_cast<int>(p)));
  // The reference is the outermost accepted point at least max(1e-9 max(1, |a*|), 1000 w)
  // inside: the continuation's steps aim at a border's root, so its last points can lie
  // within T's error of a*, and at hb bits such a point may be past a*.
  const double inside = std::max(1e-9 * scale, 1e3 * w);
  const long n = static_cast<long>(b.points.size());
  long k = dir > 0 ? n - 1 : 0;
  while (k != static_cast<long>(b.start) && std::fabs(Tr<T>::to_double(T(b.points[k].param - e.param))) < inside) k -= dir;
  const std::optional<BranchPoint<Mpfr>> ref0 = reference(b.points[k]);
  if (!ref0) {
    out.note = "at " + std::to_string(hb) + " bits Newton does not find the branch's last orbit";
    return out;
  }
  const BranchPoint<Mpfr>& ref = *ref0;
  std::optional<BranchPoint<Mpfr>> ref_prev;
  if (k - dir >= 0 && k - dir < n) ref_prev = reference(b.points[k - dir]);
  const Mpfr near0 = up(dir > 0 ? e.bracket_lo : e.bracket_hi), far0 = up(dir > 0 ? e.bracket_hi : e.bracket_lo);
  const double span = std::fabs(Tr<Mpfr>::to_double(Mpfr(near0 - ref.param)));
  const auto shifted = [&](const Mpfr& x, double by) { return Mpfr(x + from_double<Mpfr>(by, hb)); };
  // The branch side: T's, or stepped back towards the reference point.
  BranchPoint<Mpfr> good = ref;
  std::optional<BranchPoint<Mpfr>> prev = ref_prev;
  for (double back = 0;; back = back == 0 ? w : back * 16) {
    if (back >= span) break;  // the reference itself is the branch side
    const Mpfr at = shifted(near0, -dir * back);
    Trial<Mpfr> t = c.correct(at, ref, c.predict(ref, ref_prev ? &*ref_prev : nullptr, at));
    if (t.good) {
      prev = std::move(good);
      good = std::move(*t.point);
      break;
    }
  }
  // The far side: T's, or stepped out until the corrector refuses it (at most 1e-6 max(1, |a*|)
  // beyond, the distance of the look beyond).
  std::optional<Mpfr> bad;
  for (double out_by = 0; out_by <= 1e-6 * scale; out_by = out_by == 0 ? w : out_by * 16) {
    const Mpfr at = shifted(far0, dir * out_by);
    Trial<Mpfr> t = c.correct(at, good, c.predict(good, prev ? &*prev : nullptr, at));
    if (!t.good) {
      bad = at;
      break;
    }
    prev = std::move(good);
    good = std::move(*t.point);
  }
  if (!bad) {
    out.note = "at " + std::to_string(hb) + " bits the branch goes on past the bracket";
    return out;
  }
  // The cause is named as in T: by the margins' shrinking since the branch's start point
  // (locate_end reads only its margins and det(J - I)).
  BranchPoint<Mpfr> first;
  first.margins = b.points[b.start].margins;
  first.test_fold = b.points[b.start].test_fold;
  const BranchEnd<Mpfr> r = c.locate_end(good, prev, *bad, dir, first);
  if (r.reason != e.reason) {
    out.note = std::string("at ") + std::to_string(hb) + " bits the end has another cause (" + name(r.reason) + ")";
    return out;
  }
  widen(out, r.param, Mpfr(r.bracket_hi - r.bracket_lo), Tr<T>::to_double(T(e.bracket_hi - e.bracket_lo)), scale, p);
  return out;
}

// Re-locates a smooth bifurcation of b (fold, period doubling, Neimark-Sacker) in Mpfr as
// estimate_one does an end: the orbits at p + 64 bits on either side of T's bracket (Newton
// from the nearest branch point), the bracket widened 16x per step until its test function
// changes sign between them, then regula falsi (locate_smooth) to 2^-(p + 24) relative.
template <class T>
EndEstimate estimate_smooth(const ModelSpec& spec, const Branch<T>& b, const Bifurcation<T>& x, const ContinuationOptions& opt) {
  EndEstimate out;
  const long p = Tr<T>::bits(x.param), hb = p + 64;
  out.bits = hb;
  out.center = exact_of(x.param);
  const Model<Mpfr> base = make_model<Mpfr>(spec, hb);
  Continuer<Mpfr> c{base, b.parameter, b.period, opt, hb};
  c.stop_rel = std::ldexp(1.0, -static_cast<int>(std::min(p + 24, 1000L)));
  const auto up = [hb](const T& v) { return Tr<Mpfr>::from_decimal(Tr<T>::to_string(v), hb); };
  const BranchPoint<T>* near = &b.points.front();
  for (const BranchPoint<T>& q : b.points)
    if (std::fabs(Tr<T>::to_double(T(q.param - x.param))) < std::fabs(Tr<T>::to_double(T(near->param - x.param)))) near = &q;
  const State<Mpfr> guess{up(near->orbit.points[0].theta), up(near->orbit.points[0].v)};
  const auto orbit_at = [&](const Mpfr& v) -> std::optional<BranchPoint<Mpfr>> {
    try {
      const Model<Mpfr> m = c.at(v);
      PeriodicOrbit<Mpfr> o = find_periodic(m, b.period, newton_start(m, near->events, guess), opt.newton);
      if (!o.converged || o.minimal_period != b.period) return std::nullopt;
      BranchPoint<Mpfr> bp = analyse_orbit(m, b.parameter, std::move(o));
      if (!same_cycle(bp.events, near->events)) return std::nullopt;
      return bp;
    } catch (const Undecided&) {
      return std::nullopt;
    }
  };
  const auto g = [&x](const BranchPoint<Mpfr>& bp) {
    return x.kind == SmoothKind::fold ? bp.test_fold : x.kind == SmoothKind::period_doubling ? bp.test_pd : bp.test_ns;
  };
  const double scale = std::max(1.0, std::fabs(Tr<T>::to_double(x.param)));
  const double width = Tr<T>::to_double(T(x.bracket_hi - x.bracket_lo));
  const Mpfr lo0 = up(x.bracket_lo), hi0 = up(x.bracket_hi);
  for (double by = std::max(width, std::ldexp(scale, -static_cast<int>(p))); by < 1e-3 * scale; by *= 16) {
    const auto A = orbit_at(Mpfr(lo0 - from_double<Mpfr>(by, hb))), B = orbit_at(Mpfr(hi0 + from_double<Mpfr>(by, hb)));
    if (!A || !B) continue;
    const double ga = g(*A), gb = g(*B);
    if (!((ga < 0 && gb > 0) || (ga > 0 && gb < 0))) continue;
    if (x.kind == SmoothKind::neimark_sacker && !(A->orbit.multipliers.complex && B->orbit.multipliers.complex)) continue;
    const std::optional<Bifurcation<Mpfr>> r = c.locate_smooth(x.kind, *A, *B);
    if (!r) break;
    widen(out, r->param, Mpfr(r->bracket_hi - r->bracket_lo), width, scale, p);
    return out;
  }
  out.note = "at " + std::to_string(hb) + " bits the test function does not change sign next to the bracket";
  return out;
}

}  // namespace

template <class T>
void estimate_end_accuracy(const ModelSpec& spec, Branch<T>& b, const ContinuationOptions& opt) {
  if (!b.started || b.points.empty()) return;
  b.low.estimate = estimate_one(spec, b, b.low, -1, opt);
  b.high.estimate = estimate_one(spec, b, b.high, 1, opt);
  for (Bifurcation<T>& x : b.bifurcations) x.estimate = estimate_smooth(spec, b, x, opt);
}

#define BOUNCER_CONTINUATION_INSTANTIATE(T, kind)                                                                \
  template Branch<T> continue_branch<T>(const Model<T>&, Parameter, long, const State<T>&, const T&,       \
                                        const T&, const ContinuationOptions&);                            \
  template BranchPoint<T> analyse_orbit<T>(const Model<T>&, Parameter, PeriodicOrbit<T>);                   \
  template void estimate_end_accuracy<T>(const ModelSpec&, Branch<T>&, const ContinuationOptions&);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_CONTINUATION_INSTANTIATE)
#undef BOUNCER_CONTINUATION_INSTANTIATE

}  // namespace bouncer
