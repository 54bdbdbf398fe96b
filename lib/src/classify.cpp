// Attractor types (analysis/classify.hpp). The decision order, each with its evidence:
//   1. a step undecided (NaN, overflow, walk limit)            -> undecided
//   2. unbounded growth of the running maximum of v            -> unbounded (v ~ n^alpha)
//      (not for constant eps < 1, whose orbits all enter a proved trapping region)
//   3. a sticking step whose release state recurs exactly      -> sticking, k = steps
//      between the two releases (the release state is a constant of the wall, so the
//      recurrence is exact in every precision)
//   4. veldep: a chatter run (>= 32 consecutive impacts on one segment with strictly
//      decreasing relative velocity) or a ride (relative velocity rounded to 0)
//                                                              -> effective_sticking
//   5. the state repeats after q <= max_period steps over the second half of the window
//      (theta compared modulo 1)                               -> fixed (q = 1) / periodic
//   6. leading Lyapunov exponent over the window (AD tangent map):
//      (measured over max(steps, 2000) further steps in 20 blocks)
//      lambda > max(0.01, 3 stderr)                            -> chaotic
//      lambda < -0.002: a period-q search over 20 * steps further steps (q up to
//      10 * steps, beyond max_period)                          -> fixed/periodic
//      not found and lambda < -3 stderr (contracting)          -> undecided
//      otherwise (lambda ~ 0)                                  -> quasiperiodic
#include "bouncer/analysis/classify.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

#include "bouncer/analysis/jacobian.hpp"
#include "bouncer/analysis/lyapunov.hpp"

namespace bouncer {

const char* name(OrbitClass c) {
  switch (c) {
    case OrbitClass::fixed: return "fixed";
    case OrbitClass::periodic: return "periodic";
    case OrbitClass::sticking: return "sticking";
    case OrbitClass::quasiperiodic: return "quasiperiodic";
    case OrbitClass::chaotic: return "chaotic";
    case OrbitClass::unbounded: return "unbounded";
    case OrbitClass::effective_sticking: return "effective_sticking";
    case OrbitClass::undecided: return "undecided";
  }
  return "?";
}

namespace {

constexpr double kRepeatTol = 1e-9;  // relative agreement of states for "repeats"

template <class T>
bool same_state(const State<T>& x, const State<T>& y) {
  return x.theta == y.theta && x.v == y.v;
}

// Distance of two states with theta compared modulo 1 (theta in [0, 1)).
template <class T>
double state_distance(const State<T>& x, const State<T>& y) {
  using Tr = ScalarTraits<T>;
  double dt = std::fabs(Tr::to_double(x.theta - y.theta));
  dt = std::min(dt, std::fabs(1.0 - dt));
  const double scale = std::max(1.0, std::fabs(Tr::to_double(x.v)));
  const double dv = std::fabs(Tr::to_double(x.v - y.v)) / scale;
  return std::max(dt, dv);
}

std::string fmt(double x, int digits = 3) {
  std::ostringstream os;
  os << std::setprecision(digits) << x;
  return os.str();
}

struct GrowthSamples {
  std::vector<std::pair<double, double>> pts;
  double next = 1, runmax = 0;
  void add(long n, double v) {
    runmax = std::max(runmax, v);
    if (n >= next) {
      pts.emplace_back(static_cast<double>(n), runmax);
      while (next <= n) next = std::ceil(next * 1.25);
    }
  }
  double max_at(double n) const {
    double m = 0;
    for (const auto& p : pts)
      if (p.first <= n) m = p.second;
    return m;
  }
  double alpha(long N) const {
    std::vector<std::pair<double, double>> tail;
    for (const auto& p : pts)
      if (p.first >= N / 16.0) tail.push_back(p);
    return growth_exponent(tail);
  }
};

}  // namespace

template <class T>
Classification classify(const ImpactMap<T>& map, State<T> s, const ClassifyOptions& opt) {
  using Tr = ScalarTraits<T>;
  Classification c;
  c.lambda = std::numeric_limits<double>::quiet_NaN();
  const Model<T>& model = map.model();
  const long W = std::max(4L, opt.steps);
  const long N = std::max(0L, opt.transient) + W;

  std::vector<State<T>> win;
  std::vector<EventKind> kinds;
  std::vector<int> segs;
  std::vector<double> rel;  // relative velocity after each step (v - u of the segment)
  win.reserve(W + 1);
  GrowthSamples growth;
  long last_stick = -1;     // step index (1-based) of the last sticking step
  State<T> release{};
  long n = 0;
  try {
    for (; n < N; ++n) {
      StepResult<T> r = map.step(s);
      s = std::move(r.next);
      growth.add(n + 1, Tr::to_double(s.v));
      if (r.kind == EventKind::sticking) {
        last_stick = n + 1;
        release = s;
      }
      if (n >= N - W) {
        win.push_back(s);
        kinds.push_back(r.kind);
        segs.push_back(r.segment);
        const int j = model.wall.segment_of(s.theta);
        rel.push_back(Tr::to_double(s.v - model.wall.velocity[j]));
      }
    }
  } catch (const Undecided& e) {
    c.cls = OrbitClass::undecided;
    c.evidence = "step " + std::to_string(n + 1) + " undecided: " + e.what();
    return c;
  }

  // 2. Unbounded growth. Not with constant eps < 1: there every orbit enters the trapping
  //    region v <= 4(1 + 3 eps)/(1 - eps) (proofs/trapping_region), so growth is a transient.
  const bool trapped = model.law == Law::constant && certainly(Tr::lt(model.eps, Tr::from_int(1, model.bits)));
  if (!trapped) {
    const double alpha = growth.alpha(N);
    const double early = growth.max_at(N / 16.0);
    if (N >= 64 && alpha > 0.2 && growth.runmax > 1.5 * early) {
      c.cls = OrbitClass::unbounded;
      c.alpha = alpha;
      c.evidence = "running max of v grows as n^" + fmt(alpha) + " (from " + fmt(early) + " at step " +
                   std::to_string(N / 16) + " to " + fmt(growth.runmax) + " at step " + std::to_string(N) + ")";
      return c;
    }
  }

  // 3. Sticking: the last release state recurs at a later sticking step.
  if (last_stick > 0) {
    try {
      State<T> x = release;
      const long cap = std::max(20000L, 4 * N);
      for (long k = 1; k <= cap; ++k) {
        StepResult<T> r = map.step(x);
        x = std::move(r.next);
        if (r.kind == EventKind::sticking && same_state(x, release)) {
          c.cls = OrbitClass::sticking;
          c.period = k;
          c.lambda = -std::numeric_limits<double>::infinity();
          c.evidence = "sticking with period " + std::to_string(k) + ": release state (" + fmt(Tr::to_double(release.theta), 6) +
                       ", " + fmt(Tr::to_double(release.v), 6) + ") recurs exactly after " + std::to_string(k) +
                       " steps (last sticking at step " + std::to_string(last_stick) + ")";
          return c;
        }
      }
    } catch (const Undecided&) {
      // fall through: judged on the window alone
    }
  }

  // 4. Effective sticking (velocity-dependent law).
  if (model.law == Law::veldep) {
    long best = 0, run = 1;
    double minrel = std::numeric_limits<double>::infinity();
    bool rode = false;
    for (size_t i = 0; i < win.size(); ++i) {
      minrel = std::min(minrel, std::fabs(rel[i]));
      if (kinds[i] == EventKind::ride) rode = true;
      if (i > 0 && kinds[i] == EventKind::impact && segs[i] == segs[i - 1] && rel[i] < rel[i - 1]) {
        ++run;
      } else {
        run = 1;
      }
      best = std::max(best, run);
    }
    if (rode || best >= 32) {
      c.cls = OrbitClass::effective_sticking;
      c.evidence = rode ? "relative velocity reached 0 at this precision (the particle rides the wall)"
                        : "chatter: " + std::to_string(best) +
                              " consecutive impacts on one wall segment with decreasing relative velocity (min " +
                              fmt(minrel) + ")";
      return c;
    }
  }

  // 5. Periodic: smallest q whose shift matches over the second half of the window.
  const long L = static_cast<long>(win.size());
  const long qmax = std::min(opt.max_period, L / 2);
  for (long q = 1; q <= qmax; ++q) {
    double worst = 0;
    bool ok = true;
    for (long i = L / 2; i + q < L; ++i) {
      const double d = state_distance(win[i], win[i + q]);
      worst = std::max(worst, d);
      if (!(d <= kRepeatTol)) { ok = false; break; }
    }
    if (!ok) continue;
    c.cls = q == 1 ? OrbitClass::fixed : OrbitClass::periodic;
    c.period = q;
    std::string mult;
    try {
      TangentMap<T> tm(model);
      LinearOrbit<T> lo = tm.steps(win.back(), q);
      Eigen2<T> e = eigenvalues(lo.J);
      const double m0 = e.modulus(0), m1 = e.modulus(1);
      c.lambda = m0 > 0 ? std::log(m0) / static_cast<double>(q) : -std::numeric_limits<double>::infinity();
      mult = "; multipliers |mu| = " + fmt(m0, 6) + ", " + fmt(m1, 6) +
             (std::fabs(m0 - 1) < 1e-6 ? " (marginal: a family)" : "");
    } catch (const Undecided&) {
    }
    c.evidence = "state repeats after " + std::to_string(q) + " step" + (q == 1 ? "" : "s") + " to " + fmt(worst, 2) +
                 " over the last " + std::to_string(L - L / 2) + " steps" + mult;
    return c;
  }

  // 6. Bounded and aperiodic: the Lyapunov exponent decides.
  LyapunovOptions lo;
  lo.transient = 0;
  lo.steps = std::max(W, 2000L);
  lo.blocks = 20;
  LyapunovResult lr = lyapunov(model, win.back(), lo);
  c.lambda = lr.lambda;
  if (lr.undecided) {
    c.cls = OrbitClass::undecided;
    c.evidence = "no period <= " + std::to_string(opt.max_period) + "; Lyapunov run " + lr.note;
    return c;
  }
  if (lr.contracted) {
    c.cls = OrbitClass::undecided;
    c.evidence = "no period <= " + std::to_string(opt.max_period) + " and a contracting step: " + lr.note;
    return c;
  }
  const double thr = std::max(0.01, 3 * lr.stderr_);
  const std::string lam = "lambda = " + fmt(lr.lambda, 4) + " +- " + fmt(lr.stderr_, 2) + " per collision over " +
                          std::to_string(lr.steps) + " steps";
  if (lr.lambda > thr) {
    c.cls = OrbitClass::chaotic;
    c.evidence = "bounded, no period <= " + std::to_string(opt.max_period) + ", " + lam;
    return c;
  }
  const bool contracting = lr.lambda < -3 * lr.stderr_ && lr.lambda < -0.002;
  long searched = 0;
  if (lr.lambda < -0.002) {
    // A contracting orbit that did not repeat within max_period: look for a longer period
    // (or a slower transient) over E = 20 * steps further steps. Candidates q are the
    // returns of the last state, each verified over one full period: O(E) work.
    const long E = std::max(20 * W, 4 * opt.max_period);
    try {
      std::vector<State<T>> ext;
      ext.reserve(E);
      State<T> x = win.back();
      for (long i = 0; i < E; ++i) {
        x = map.step(x).next;
        ext.push_back(x);
      }
      const long last = E - 1;
      for (long q = 1; q <= E / 2; ++q) {
        if (!(state_distance(ext[last - q], ext[last]) <= kRepeatTol)) continue;
        double worst = 0;
        bool ok = true;
        for (long i = last - q + 1; i <= last && ok; ++i) {
          const double d = state_distance(ext[i - q], ext[i]);
          worst = std::max(worst, d);
          ok = d <= kRepeatTol;
        }
        if (!ok) continue;
        c.cls = q == 1 ? OrbitClass::fixed : OrbitClass::periodic;
        c.period = q;
        c.evidence = "state repeats after " + std::to_string(q) + " steps to " + fmt(worst, 2) +
                     " (extended search over " + std::to_string(E) + " further steps, beyond max-period " +
                     std::to_string(opt.max_period) + "); " + lam;
        return c;
      }
    } catch (const Undecided&) {
    }
    searched = E / 2;
  }
  if (contracting) {
    c.cls = OrbitClass::undecided;
    c.evidence = "contracting (" + lam + ") but no period <= " + std::to_string(std::max(searched, opt.max_period)) +
                 " within tolerance: a longer transient or period is needed";
    return c;
  }
  c.cls = OrbitClass::quasiperiodic;
  c.evidence = "bounded, no period <= " + std::to_string(opt.max_period) + ", " + lam + " (~0)";
  return c;
}

template Classification classify<double>(const ImpactMap<double>&, State<double>, const ClassifyOptions&);
template Classification classify<Mpfr>(const ImpactMap<Mpfr>&, State<Mpfr>, const ClassifyOptions&);
template Classification classify<long double>(const ImpactMap<long double>&, State<long double>, const ClassifyOptions&);
template Classification classify<Quad>(const ImpactMap<Quad>&, State<Quad>, const ClassifyOptions&);

}  // namespace bouncer
