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
//   5. the state repeats after q <= max_period steps over the second half of the window,
//      and over at least q steps (theta compared modulo 1)    -> fixed (q = 1) / periodic
//   6. leading Lyapunov exponent over the window (AD tangent map):
//      (measured over max(steps, 2000) further steps in 20 blocks)
//      lambda > max(0.01, 3 stderr)                            -> chaotic
//      lambda < -0.002: a period-q search over 20 * steps further steps (q up to
//      10 * steps, beyond max_period)                          -> fixed/periodic
//      not found and lambda < -3 stderr (contracting)          -> undecided
//      otherwise (lambda ~ 0)                                  -> quasiperiodic
// Around these window rules (classify()):
//   0. before anything, the start itself: if the state returns to the start within
//      max_period steps to ~machine precision (2^-(bits-10)) without sticking, and the
//      q-step multipliers there are unstable (|mu| > 1 + 1e-6), the start lies on an
//      unstable period-q orbit                                 -> fixed / periodic
//      (rounding would carry a numerical orbit off it, and a window much later would
//      report whatever the orbit falls to instead)
//   7. a `chaotic` verdict (and in a dissipative model a `quasiperiodic` one: a chaotic
//      transient whose exponent is within its error of 0) is re-checked after
//      R = recheck_factor x max(transient, steps) further steps, with the same rules:
//      settled on fixed/periodic/sticking/effective sticking (or, from chaotic,
//      quasiperiodic) -> transient_chaos (with the step it settled at); still aperiodic ->
//      the later label; growing -> unbounded; anything else -> undecided. In a conservative
//      map (elastic, eps = 1) nothing settles: a quiet later window keeps `chaotic`. A
//      window of 500 steps after 5000 can catch a long chaotic transient, so the label
//      must not depend on that window.
// Every evidence line ends with the windows used: [windows: transient N, steps M, recheck R].
// For unbounded orbits the growth is described further (accelerator modes vs diffusion):
// mean dv per step, phase clusters on the circle (the spokes of the polar portrait), and
// the smallest Q <= max_period at which the phases repeat (to 0.01) while v grows.
#include "bouncer/analysis/classify.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <type_traits>
#include <vector>

#include "bouncer/analysis/jacobian.hpp"
#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/base/cancel.hpp"

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
    case OrbitClass::transient_chaos: return "transient_chaos";
    case OrbitClass::outside: return "outside";
  }
  return "?";
}

std::optional<OrbitClass> orbit_class_named(std::string_view text) {
  for (int i = 0; i < kOrbitClassCount; ++i)
    if (text == name(static_cast<OrbitClass>(i))) return static_cast<OrbitClass>(i);
  return std::nullopt;
}

const char* name(RecheckRule r) { return r == RecheckRule::full ? "full" : "recurrence"; }

std::optional<RecheckRule> recheck_rule_named(std::string_view text) {
  for (RecheckRule r : {RecheckRule::full, RecheckRule::recurrence})
    if (text == name(r)) return r;
  return std::nullopt;
}

namespace {

constexpr double kRepeatTol = 1e-9;  // relative agreement of states for "repeats"

template <class T>
bool same_state(const State<T>& x, const State<T>& y) {
  return x.theta == y.theta && x.v == y.v;
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

// Phase branches: the phases of the window as points on the circle, split at every gap
// wider than max(0.02, 3 ln(L)/L) (L points spread uniformly leave a largest gap of about
// ln(L)/L, so a wider gap is structure, not chance). 0 when no gap is that wide.
int phase_branches(std::vector<double> th) {
  const size_t L = th.size();
  if (L < 8) return 0;
  for (double& t : th) t -= std::floor(t);
  std::sort(th.begin(), th.end());
  const double gap = std::max(0.02, 3 * std::log(static_cast<double>(L)) / static_cast<double>(L));
  int n = 0;
  for (size_t i = 0; i < L; ++i) {
    const double next = i + 1 < L ? th[i + 1] : th[0] + 1;
    if (next - th[i] > gap) ++n;
  }
  return n;
}

double circle_distance(double a, double b) {
  double d = std::fabs(a - b);
  d -= std::floor(d);
  return std::min(d, 1 - d);
}

// Accelerator modes: the smallest Q <= qmax such that over the second half of the window
// theta_{i+Q} = theta_i to 0.01 (on the circle) and v_{i+Q} > v_i for every i; D is the
// mean of v_{i+Q} - v_i. Fills growth_rate, branches, accel_period, accel_gain, growth_kind.
void describe_growth(Classification& c, const std::vector<double>& th, const std::vector<double>& v, long qmax) {
  const long L = static_cast<long>(v.size());
  if (L < 2) return;
  c.growth_rate = (v.back() - v.front()) / static_cast<double>(L - 1);
  c.branches = phase_branches(th);
  constexpr double kPhaseTol = 0.01;
  for (long q = 1; q <= std::min(qmax, L / 2); ++q) {
    bool ok = true;
    double gain = 0;
    long n = 0;
    for (long i = L / 2; i + q < L && ok; ++i) {
      ok = circle_distance(th[i], th[i + q]) <= kPhaseTol && v[i + q] > v[i];
      gain += v[i + q] - v[i];
      ++n;
    }
    if (ok && n > 0) {
      c.accel_period = q;
      c.accel_gain = gain / static_cast<double>(n);
      break;
    }
  }
  if (c.accel_period > 0) {
    // The mode's own statistics are those after capture: the window may begin in the wander
    // before it (a chaotic or quasiperiodic stretch), whose phases fill the circle and whose
    // growth is slower. Capture = the earliest step from which the recurrence holds.
    const long q = c.accel_period;
    long from = L / 2;
    while (from > 0 && circle_distance(th[from - 1], th[from - 1 + q]) <= kPhaseTol && v[from - 1 + q] > v[from - 1]) --from;
    c.captured_from = from;
    if (L - from >= 2) {
      c.growth_rate = (v.back() - v[from]) / static_cast<double>(L - 1 - from);
      c.branches = phase_branches(std::vector<double>(th.begin() + from, th.end()));
    }
  }
  if (c.accel_period > 0 && c.alpha > 0.8) c.growth_kind = "accelerator";
  else if (c.accel_period == 0 && c.alpha > 0.3 && c.alpha < 0.7) c.growth_kind = "diffusive";
  else c.growth_kind = "irregular";
}

template <class T>
std::string windows_text(const ClassifyOptions& opt) {
  const long R = opt.recheck_factor > 0 ? opt.recheck_factor * std::max(opt.transient, opt.steps) : 0;
  return " [windows: transient " + std::to_string(opt.transient) + ", steps " + std::to_string(opt.steps) + ", recheck " +
         (R > 0 ? std::to_string(R) : std::string("off")) + "]";
}

}  // namespace

namespace {

// The exact return of a deterministic orbit: once a state recurs exactly (every bit, and the
// knot), the orbit repeats its cycle for ever, so the steps up to any later step are known
// without taking them. Brent's method: the state saved at steps 1, 2, 4, 8, ... is compared
// with each later one; a cycle of period p starting by step m is seen by step 2 max(m, p).
// States with a zero coordinate are not compared (-0 and +0 compare equal but could step
// differently).
template <class T>
struct ExactCycle {
  State<T> saved{};
  long saved_at = -1, next_save = 1;
  long period = 0;  // found: the state at step n equals the one at step n - period
  void see(const State<T>& s, long n) {
    if (period) return;
    using Tr = ScalarTraits<T>;
    const double th = Tr::to_double(s.theta), v = Tr::to_double(s.v);
    const bool comparable = th != 0 && v != 0 && std::isfinite(th) && std::isfinite(v);
    if (comparable && saved_at >= 0 && s.knot == saved.knot && s.theta == saved.theta && s.v == saved.v) {
      period = n - saved_at;
      return;
    }
    if (n >= next_save) {
      saved = s;
      saved_at = comparable ? n : -1;
      next_save = 2 * n;
    }
  }
};

// The steps of one window run (the transient, then the window of W steps), with what rules
// 1-6 need of them: the window's states, events, segments and relative velocities, the
// growth samples of the whole run and the last sticking step. One orbit per run; several
// runs advance together (run_windows), each exactly as alone.
template <class T>
struct WindowRun {
  State<T> s;
  long N = 0, W = 0;
  long n = 0;  // steps taken
  std::vector<State<T>> win;
  std::vector<EventKind> kinds;
  std::vector<int> segs;
  std::vector<double> rel;  // relative velocity after each step (v - u of the segment)
  GrowthSamples growth;
  long last_stick = -1;     // step index (1-based) of the last sticking step
  State<T> release{};
  std::string undecided;    // the step's reason, when a step was undecided
  bool failed = false;
  ExactCycle<T> cycle;      // watched during the transient (opt.exact_cycles)
  bool watch = true, carried = false;

  WindowRun(State<T> start, const ClassifyOptions& opt)
      : s(std::move(start)), N(std::max(0L, opt.transient) + std::max(4L, opt.steps)), W(std::max(4L, opt.steps)),
        watch(opt.exact_cycles) {
    win.reserve(static_cast<size_t>(W) + 1);
  }
  bool done() const { return failed || n >= N; }

  // After a step: if the orbit has just recurred exactly (ExactCycle), take one more cycle and
  // carry the run along it to the last whole cycle before the window: the states, growth
  // samples and last sticking step that stepping would give, bit for bit (every v of the cycle
  // is in the running maximum already). True if it moved.
  bool carry(const ImpactMap<T>& map) {
    const long p = cycle.period;
    if (!p || carried || failed) return false;
    carried = true;
    const long window_at = N - W;
    if (n + p >= window_at) return false;
    std::vector<State<T>> states;
    std::vector<char> stuck;
    for (long i = 0; i < p; ++i) {
      const long before = last_stick;
      step_or_fail(map);
      if (failed) return false;
      states.push_back(s);
      stuck.push_back(last_stick != before);
    }
    const long end = n + (window_at - n) / p * p;
    if (end == n) return false;
    for (long i = p - 1; i >= 0; --i)
      if (stuck[static_cast<size_t>(i)]) {
        last_stick = end - (p - 1 - i);
        release = states[static_cast<size_t>(i)];
        break;
      }
    while (growth.next <= static_cast<double>(end)) growth.add(static_cast<long>(growth.next), growth.runmax);
    n = end;  // s is the cycle's last state, as p, 2p, ... steps later
    return true;
  }

  // One step (throws Undecided).
  void step(const ImpactMap<T>& map) { take(map.model(), map.step(s)); }
  // The step's result r (of the step from s) recorded.
  void take(const Model<T>& model, StepResult<T>&& r) {
    using Tr = ScalarTraits<T>;
    s = std::move(r.next);
    growth.add(n + 1, Tr::to_double(s.v));
    if (r.kind == EventKind::sticking) {
      last_stick = n + 1;
      release = s;
    }
    if (watch && n < N - W) cycle.see(s, n + 1);
    if (n >= N - W) {
      win.push_back(s);
      kinds.push_back(r.kind);
      segs.push_back(r.segment);
      rel.push_back(Tr::to_double(s.v - model.wall.velocity_at(s.theta)));
    }
    ++n;
  }
  void step_or_fail(const ImpactMap<T>& map) {
    try {
      step(map);
    } catch (const Undecided& e) {
      fail(e.reason);
    }
  }
  void fail(Reason why) {
    failed = true;
    undecided = "step " + std::to_string(n + 1) + " undecided: " + describe(why);
  }
};

// Advance every run to its end. The runs go in groups of kInterleave, one step of each in
// turn: the step of one orbit is a chain of dependent operations whose latency, not the
// arithmetic, sets its speed (bench_step), so independent orbits stepped side by side overlap
// in the processor. Each orbit's operations are those of the run alone, in the same order:
// the results are the same, bit for bit. In double the group's steps are one call of the
// batched step (ImpactMap::step_n), whose lanes the processor overlaps better than four calls
// of step() (bench_grid's "side by side" row).
constexpr size_t kInterleave = 4;

template <class T>
void run_windows(const ImpactMap<T>& map, const std::vector<WindowRun<T>*>& runs) {
  size_t g = 0;
  for (; g + kInterleave <= runs.size(); g += kInterleave) {
    WindowRun<T>* w[kInterleave];
    for (size_t i = 0; i < kInterleave; ++i) w[i] = runs[g + i];
    if constexpr (std::is_same_v<T, double>) {
      // double: the batched step (ImpactMap::step_n), kStepLanes orbits in one call, while none
      // has ended or failed. The lanes need not be at the same step: a run that recurs exactly
      // is carried along its cycle (carry) and the four go on together.
      static_assert(kInterleave == static_cast<size_t>(kStepLanes));
      const Model<T>& model = map.model();
      State<T> s[kInterleave];
      StepResult<T> out[kInterleave];
      Reason why[kInterleave];
      while (!w[0]->done() && !w[1]->done() && !w[2]->done() && !w[3]->done()) {
        throw_if_cancelled(w[0]->n);
        for (size_t i = 0; i < kInterleave; ++i) s[i] = w[i]->s;
        const unsigned failed = map.template step_n<kStepLanes>(s, out, why);
        for (size_t i = 0; i < kInterleave; ++i) {
          if (failed >> i & 1u) {
            w[i]->fail(why[i]);
          } else {
            w[i]->take(model, std::move(out[i]));
            w[i]->carry(map);
          }
        }
      }
    } else {
      // Rounds of one step of each, without per-step checks, while all four are at the same
      // step and none has ended (the runs of one phase start together with the same length).
      bool lockstep = true;
      for (WindowRun<T>* x : w) lockstep = lockstep && !x->done() && x->n == w[0]->n && x->N == w[0]->N;
      if (lockstep) {
        try {
          for (long k = w[0]->n, N = w[0]->N; k < N; ++k) {
            throw_if_cancelled(k);
            w[0]->step(map);
            w[1]->step(map);
            w[2]->step(map);
            w[3]->step(map);
            // An orbit that recurred exactly is carried along its cycle (below), out of step.
            if (w[0]->cycle.period | w[1]->cycle.period | w[2]->cycle.period | w[3]->cycle.period) break;
          }
        } catch (const Undecided&) {
          // A step that throws changes nothing: the runs not yet past this round (w[3] never
          // is) take it again one by one, and the one that failed records its own failure.
          const long n0 = w[3]->n;
          for (WindowRun<T>* x : w)
            if (x->n == n0) x->step_or_fail(map);
        }
      }
    }
    // Whatever is left (after a failure or an exact recurrence), one step of each in turn.
    for (bool left = true; left;) {
      left = false;
      for (WindowRun<T>* x : w)
        if (!x->done()) {
          throw_if_cancelled(x->n);
          x->step_or_fail(map);
          x->carry(map);
          left = true;
        }
    }
  }
  for (; g < runs.size(); ++g) {
    WindowRun<T>& w = *runs[g];
    while (!w.done()) {
      throw_if_cancelled(w.n);
      w.step_or_fail(map);
      w.carry(map);
    }
  }
}

// Rules 1-6 on a finished window run; `last` receives the window's last state.
template <class T>
Classification finish_window(const ImpactMap<T>& map, WindowRun<T>& w, const ClassifyOptions& opt, State<T>& last) {
  using Tr = ScalarTraits<T>;
  Classification c;
  c.lambda = std::numeric_limits<double>::quiet_NaN();
  const Model<T>& model = map.model();
  const long W = w.W;
  const long N = w.N;
  if (w.failed) {
    c.cls = OrbitClass::undecided;
    c.evidence = w.undecided;
    return c;
  }
  const std::vector<State<T>>& win = w.win;
  const std::vector<EventKind>& kinds = w.kinds;
  const std::vector<int>& segs = w.segs;
  const std::vector<double>& rel = w.rel;
  const GrowthSamples& growth = w.growth;
  const long last_stick = w.last_stick;
  const State<T>& release = w.release;
  last = win.back();

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
      std::vector<double> th, v;
      for (const State<T>& x : win) {
        th.push_back(Tr::to_double(x.theta));
        v.push_back(Tr::to_double(x.v));
      }
      describe_growth(c, th, v, std::max(opt.max_period, 64L));
      c.evidence += "; " + fmt(c.growth_rate) + " per step, " +
                    (c.branches ? std::to_string(c.branches) + " phase branch" + (c.branches == 1 ? "" : "es")
                                : std::string("phases fill the circle")) +
                    (c.accel_period ? ", phases repeat every " + std::to_string(c.accel_period) + " step" +
                                          (c.accel_period == 1 ? "" : "s") + " with gain " + fmt(c.accel_gain, 4) +
                                          " (captured by step " + std::to_string(N - W + 1 + c.captured_from) + ")"
                                    : std::string(", no phase recurrence")) +
                    ": " + c.growth_kind;
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

  // 5. Periodic: smallest q whose shift matches over the second half of the window, and
  // always over at least one full period (q comparisons): for q > L/4 the second half holds
  // fewer than q pairs, and at q = L/2 none, which once passed vacuously and labelled chaotic
  // orbits "periodic" with period steps/2.
  const long L = static_cast<long>(win.size());
  const long qmax = std::min(opt.max_period, L / 2);
  for (long q = 1; q <= qmax; ++q) {
    double worst = 0;
    bool ok = true;
    for (long i = std::min(L / 2, L - 2 * q); i + q < L; ++i) {
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

// Rules 1-6 on the window after the transient; `last` receives the window's last state.
template <class T>
Classification classify_window(const ImpactMap<T>& map, State<T> s, const ClassifyOptions& opt, State<T>& last) {
  WindowRun<T> w(std::move(s), opt);
  run_windows<T>(map, {&w});
  return finish_window(map, w, opt, last);
}

// The step from which an orbit stays on its period-q cycle: one past the last i with
// |x_{i+q} - x_i| > tolerance in `run` (the states after the start, step 1 first).
template <class T>
long settle_step(const std::vector<State<T>>& run, long q) {
  const long L = static_cast<long>(run.size());
  for (long i = L - q - 1; i >= 0; --i)
    if (!(state_distance(run[i], run[i + q]) <= kRepeatTol)) return i + 2;
  return 1;
}

}  // namespace

// 0. The start on an unstable periodic orbit, or nothing.
template <class T>
std::optional<Classification> on_unstable_orbit(const ImpactMap<T>& map, const State<T>& s, const ClassifyOptions& opt,
                                                const std::string& windows) {
  const long qmax = std::max(1L, opt.max_period);
  try {
    const double tol = std::ldexp(1.0, -static_cast<int>(std::max(20L, map.model().bits - 10)));
    State<T> x = s;
    for (long q = 1; q <= qmax; ++q) {
      StepResult<T> r = map.step(x);
      if (r.kind != EventKind::impact) break;  // sticking/ride: the window rules decide
      x = std::move(r.next);
      const double d = state_distance(x, s);
      if (!(d <= tol)) continue;
      TangentMap<T> tm(map.model());
      const LinearOrbit<T> lo = tm.steps(s, q);
      const Eigen2<T> e = eigenvalues(lo.J);
      const double m0 = e.modulus(0), m1 = e.modulus(1);
      if (!(m0 > 1 + 1e-6)) break;  // stable or marginal: the window finds it
      Classification c;
      c.cls = q == 1 ? OrbitClass::fixed : OrbitClass::periodic;
      c.period = q;
      c.lambda = std::log(m0) / static_cast<double>(q);
      c.evidence = "start lies on an unstable period-" + std::to_string(q) + " orbit: it returns after " +
                   std::to_string(q) + " step" + (q == 1 ? "" : "s") + " to " + fmt(d, 2) + ", multipliers |mu| = " +
                   fmt(m0, 6) + ", " + fmt(m1, 6) + " (rounding carries a numerical orbit off it)" + windows;
      return c;
    }
  } catch (const Undecided&) {
    // the window rules report the undecided step
  }

  return std::nullopt;
}

// Whether the map is conservative: elastic, or constant eps = 1.
template <class T>
bool is_conservative(const ImpactMap<T>& map) {
  const Model<T>& model = map.model();
  return model.law == Law::elastic ||
         (model.law == Law::constant && certainly(ScalarTraits<T>::is_zero(T(model.eps - 1))));
}

// Whether a window's verdict is re-checked later along the orbit (rule 7), and whether the map
// is conservative.
template <class T>
bool wants_recheck(const ImpactMap<T>& map, const Classification& c, const ClassifyOptions& opt, bool& conservative,
                   bool& quiet) {
  // A conservative map (elastic, or eps = 1) preserves a measure and has no attractors: a
  // chaotic orbit cannot settle, and a quiet later window is a sticky episode near an island.
  // In a dissipative map an invariant circle is rare and a chaotic transient whose exponent
  // is within its error of 0 is common, so there `quasiperiodic` is re-checked too.
  conservative = is_conservative(map);
  quiet = c.cls == OrbitClass::quasiperiodic && !conservative;
  return (c.cls == OrbitClass::chaotic || quiet) && opt.recheck_factor > 0;
}

// The re-check's options: R = recheck_factor x max(transient, steps) steps, then the window.
inline ClassifyOptions recheck_options(const ClassifyOptions& opt) {
  ClassifyOptions ro = opt;
  ro.transient = opt.recheck_factor * std::max(opt.transient, opt.steps);
  ro.recheck_factor = 0;
  return ro;
}

// Rule 7's verdict from the first window's c (ending at `last`) and the later window's.
// `R`: the steps between the first window and the later one (the full re-check's, or fewer
// when the later window was taken where the orbit joined a known chaotic set, as `joined`
// says).
template <class T>
Classification after_recheck(const ImpactMap<T>& map, Classification c, const Classification& later, const State<T>& last,
                             const ClassifyOptions& opt, const std::string& windows, bool conservative, bool quiet,
                             long R, const std::string& joined = {}) {
  const long W = std::max(4L, opt.steps);
  const long N = std::max(0L, opt.transient) + W;
  const std::string first = c.evidence + joined;
  if (quiet && (later.cls == OrbitClass::quasiperiodic || later.cls == OrbitClass::chaotic)) {
    // Aperiodic then and later: the later window's label, the earlier one as evidence.
    c.cls = later.cls;
    c.lambda = later.lambda;
    c.evidence = first + "; " + std::to_string(R) + " steps later: " + name(later.cls) + " (" + later.evidence + ")" + windows;
    return c;
  }
  switch (conservative && later.cls != OrbitClass::unbounded ? OrbitClass::chaotic : later.cls) {
    case OrbitClass::unbounded:
      // Bounded-looking chaos in the window, growth later (diffusive Fermi acceleration).
      c = later;
      c.evidence = first + "; " + std::to_string(R) + " steps later: unbounded (" + later.evidence + ")";
      break;
    case OrbitClass::chaotic:
      if (later.cls != OrbitClass::chaotic) {
        c.evidence = first + "; a re-check " + std::to_string(R) + " steps later saw " + name(later.cls) + " (" +
                     later.evidence + "), a sticky episode: the map is conservative and has no attractors";
        break;
      }
      c.lambda = later.lambda;
      c.evidence = first + "; still chaotic after " + std::to_string(R) + " further steps (" + later.evidence + ")";
      break;
    case OrbitClass::fixed:
    case OrbitClass::periodic:
    case OrbitClass::sticking:
    case OrbitClass::effective_sticking:
    case OrbitClass::quasiperiodic: {
      c.cls = OrbitClass::transient_chaos;
      c.settled_class = later.cls;
      c.period = later.period;
      c.lambda = later.lambda;
      // When did it settle? Replay the re-check run (R + W steps after step N).
      try {
        const long E = R + W;
        if (later.cls == OrbitClass::fixed || later.cls == OrbitClass::periodic) {
          // With exact cycles, the replay stops a cycle and a period after the orbit recurs
          // exactly: from the cycle's first state on, every q-shifted pair is one of the
          // cycle's, so if none of those disagrees the last disagreeing pair lies before it,
          // as in the whole replay (else the whole replay decides).
          const long q = later.period;
          std::vector<State<T>> run;
          State<T> x = last;
          ExactCycle<T> cycle;
          long stop = E, cycle_from = -1;
          for (long i = 0; i < stop; ++i) {
            x = map.step(x).next;
            run.push_back(x);
            if (opt.exact_cycles && !cycle.period) {
              cycle.see(x, i + 1);
              if (cycle.period) {
                cycle_from = i - cycle.period;  // index of the state the recurrence returned to
                stop = std::min(E, i + 1 + cycle.period + q);
              }
            }
          }
          long at = settle_step(run, q);
          if (stop < E && at - 2 >= cycle_from) {
            for (long i = stop; i < E; ++i) {
              x = map.step(x).next;
              run.push_back(x);
            }
            at = settle_step(run, q);
          }
          c.settled_at = N + at;
        } else if (later.cls == OrbitClass::sticking) {
          State<T> x = last;
          for (long i = 0; i < E; ++i) {
            StepResult<T> r = map.step(x);
            x = std::move(r.next);
            if (r.kind == EventKind::sticking) {
              c.settled_at = N + i + 1;  // exactly periodic from the first release on
              break;
            }
          }
        }
      } catch (const Undecided&) {
      }
      c.evidence = "transient chaos: " + first + "; then settled: " + std::string(name(later.cls)) +
                   (later.period ? " " + std::to_string(later.period) : std::string()) +
                   (c.settled_at ? " from step " + std::to_string(c.settled_at)
                                 : " within steps " + std::to_string(N + 1) + ".." + std::to_string(N + R + W)) +
                   " (" + later.evidence + ")";
      break;
    }
    default:
      c.cls = OrbitClass::undecided;
      c.evidence = first + "; but " + std::to_string(R) + " steps later: " + std::string(name(later.cls)) + " (" +
                   later.evidence + ")";
      break;
  }
  c.evidence += windows;
  return c;
}

template <class T>
Classification classify(const ImpactMap<T>& map, State<T> s, const ClassifyOptions& opt) {
  const std::string windows = windows_text<T>(opt);
  if (std::optional<Classification> u = on_unstable_orbit(map, s, opt, windows)) return *u;
  State<T> last = s;
  Classification c = classify_window(map, s, opt, last);
  bool conservative = false, quiet = false;
  if (!wants_recheck(map, c, opt, conservative, quiet)) {
    c.evidence += windows;
    return c;
  }
  // 7. Re-check a chaotic (or dissipative quasiperiodic) verdict much later along the orbit.
  State<T> later_last = last;
  const ClassifyOptions ro = recheck_options(opt);
  const Classification later = classify_window(map, last, ro, later_last);
  return after_recheck(map, std::move(c), later, last, opt, windows, conservative, quiet, ro.transient);
}

// Rule 7 by recurrence (RecheckRule::recurrence): the chaotic sets of one map found so far,
// each the cells of the section that one start's orbit visited in the second half of a whole
// re-check that ended chaotic. The cells: n x n over theta in [0, 1) and over the orbit's range
// of v (padded by 5%), n = sqrt(samples)/2 within [16, 128] (about four samples a row and a
// column of cells each), each visited cell with its 8 neighbours. So a second orbit of the same
// attractor, which visits its own sample of the same set, rarely steps outside: at c = 1000,
// a = 27 (veldep), none of 20000 steps of a second orbit fell outside the set of 4000 or of
// 50000 samples, where 256 x 256 cells without neighbours missed 29% and 2%.
class KnownSet {
 public:
  explicit KnownSet(const std::vector<std::pair<double, double>>& pts)
      : n_(std::clamp(static_cast<int>(std::sqrt(static_cast<double>(pts.size())) / 2), 16, 128)) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& p : pts) lo = std::min(lo, p.second), hi = std::max(hi, p.second);
    const double pad = 0.05 * (hi - lo) + 1e-9 * std::max(1.0, std::fabs(hi));
    v0_ = lo - pad;
    scale_ = n_ / (hi + pad - v0_);
    cells_.assign(static_cast<size_t>(n_) * static_cast<size_t>(n_), 0);
    for (const auto& p : pts) {
      const int i = theta_cell(p.first), j = v_cell(p.second);
      for (int di = -1; di <= 1; ++di)
        for (int dj = std::max(0, j - 1); dj <= std::min(n_ - 1, j + 1); ++dj)
          cells_[static_cast<size_t>(dj) * static_cast<size_t>(n_) + static_cast<size_t>((i + di + n_) % n_)] = 1;
    }
  }
  bool contains(double theta, double v) const {
    const double y = (v - v0_) * scale_;
    if (!(y >= 0 && y < n_)) return false;
    return cells_[static_cast<size_t>(y) * static_cast<size_t>(n_) + static_cast<size_t>(theta_cell(theta))] != 0;
  }

 private:
  int theta_cell(double theta) const {
    const double t = theta - std::floor(theta);
    return std::min(n_ - 1, static_cast<int>(t * n_));
  }
  int v_cell(double v) const { return std::clamp(static_cast<int>((v - v0_) * scale_), 0, n_ - 1); }
  int n_;
  double v0_ = 0, scale_ = 1;
  std::vector<unsigned char> cells_;
};

// Consecutive steps in a known set's cells that end a re-check by recurrence: twice the
// paper's window, long against the few steps in which an orbit that merely passes near the
// set (a chaotic saddle beside a periodic attractor) leaves its cells.
constexpr long kJoinSteps = 1000;
// Sets kept per map (the first ones found), and the whole re-checks that must have stayed
// aperiodic on a set before starts may join it. Some starts allowed to join run their whole
// re-check anyway (an audit: a set that is a long-lived chaotic transient shows itself there).
constexpr size_t kMaxKnownSets = 4;
constexpr long kConfirmations = 2;
// The audits: the 8th start allowed to join, then the 24th, 56th, 120th, ... (gaps 8, 16, 32,
// ...): a set on which more whole re-checks stayed aperiodic needs fewer more.
bool audit_at(long allowed) {
  for (long at = 7, gap = 8; at <= allowed; gap *= 2, at += gap)
    if (at == allowed) return true;
  return false;
}

bool aperiodic(OrbitClass c) { return c == OrbitClass::chaotic || c == OrbitClass::quasiperiodic; }

// A re-check run (R = ro.transient steps from `last`, then the window), as the full re-check
// takes it, with two additions:
//   * `join` (RecheckRule::recurrence): once the orbit has stayed kJoinSteps consecutive steps
//     in the cells of one of these sets, a window of the ordinary options (no transient) is
//     taken from there, and its label is the answer if it is aperiodic; otherwise the run goes
//     on to the full answer;
//   * an orbit that recurs exactly during the R steps is carried to the window along its cycle
//     without stepping (ExactCycle): the same states, growth samples and last sticking step,
//     bit for bit, as stepping them.
// `seen` receives the states of the second half of the R steps (theta, v) when asked for.
template <class T>
struct RecheckRun {
  Classification later;
  long R = 0;          // the steps before the later window
  bool joined = false;
  std::vector<std::pair<double, double>> seen;
};

template <class T>
RecheckRun<T> recheck_run(const ImpactMap<T>& map, const State<T>& last, const ClassifyOptions& opt,
                          const ClassifyOptions& ro, const std::vector<const KnownSet*>& join, bool record) {
  using Tr = ScalarTraits<T>;
  RecheckRun<T> out;
  const long R = ro.transient;
  out.R = R;
  const long W = std::max(4L, opt.steps);
  WindowRun<T> w(last, ro);
  if (record) out.seen.reserve(static_cast<size_t>(R - R / 2));
  bool may_join = !join.empty();
  long stay = 0;
  const KnownSet* where = nullptr;
  while (!w.done() && w.n < R) {
    throw_if_cancelled(w.n);
    w.step_or_fail(map);
    if (w.failed) break;
    const double th = Tr::to_double(w.s.theta), v = Tr::to_double(w.s.v);
    if (record && w.n > R / 2) out.seen.emplace_back(th, v);
    if (w.carry(map)) {
      // An exactly periodic orbit: no aperiodic set to record, none to join.
      record = false;
      out.seen.clear();
      may_join = false;
      continue;
    }
    if (!may_join) continue;
    if (where && where->contains(th, v)) {
      ++stay;
    } else {
      stay = 0;
      where = nullptr;
      for (const KnownSet* k : join)
        if (k->contains(th, v)) {
          where = k;
          stay = 1;
          break;
        }
    }
    if (stay >= kJoinSteps && w.n + W <= R) {
      ClassifyOptions wo = opt;
      wo.transient = 0;
      wo.recheck_factor = 0;
      State<T> wl = w.s;
      Classification lc = classify_window(map, w.s, wo, wl);
      if (aperiodic(lc.cls)) {
        out.later = std::move(lc);
        out.R = w.n;
        out.joined = true;
        return out;
      }
      may_join = false;  // not that set after all: the full re-check decides
    }
  }
  while (!w.done()) {
    throw_if_cancelled(w.n);
    w.step_or_fail(map);
  }
  State<T> later_last = last;
  out.later = finish_window(map, w, ro, later_last);
  return out;
}

// The aperiodic sets of one map met by whole re-checks (RecheckRule::recurrence), with how many
// whole re-checks stayed aperiodic on each.
struct KnownSets {
  std::vector<KnownSet> sets;
  std::vector<long> confirmed;
  // A whole re-check that stayed aperiodic, with the states of its second half: it confirms the
  // set that holds 99% of them, or starts a new one.
  void confirm(const std::vector<std::pair<double, double>>& seen) {
    if (seen.empty()) return;
    for (size_t i = 0; i < sets.size(); ++i) {
      size_t in = 0;
      for (const auto& p : seen) in += sets[i].contains(p.first, p.second);
      if (in >= seen.size() - seen.size() / 100) {
        ++confirmed[i];
        return;
      }
    }
    if (sets.size() < kMaxKnownSets) {
      sets.emplace_back(seen);
      confirmed.push_back(1);
    }
  }
  std::vector<const KnownSet*> trusted() const {
    std::vector<const KnownSet*> out;
    for (size_t i = 0; i < sets.size(); ++i)
      if (confirmed[i] >= kConfirmations) out.push_back(&sets[i]);
    return out;
  }
};

template <class T>
std::vector<Classification> classify_many(const ImpactMap<T>& map, const std::vector<State<T>>& starts,
                                          const ClassifyOptions& opt) {
  const std::string windows = windows_text<T>(opt);
  const size_t n = starts.size();
  std::vector<Classification> out(n);
  std::vector<bool> done(n, false);
  for (size_t i = 0; i < n; ++i)
    if (std::optional<Classification> u = on_unstable_orbit(map, starts[i], opt, windows)) {
      out[i] = std::move(*u);
      done[i] = true;
    }
  // The first windows, side by side.
  std::vector<WindowRun<T>> first;
  std::vector<size_t> who;
  first.reserve(n);
  for (size_t i = 0; i < n; ++i)
    if (!done[i]) {
      first.emplace_back(starts[i], opt);
      who.push_back(i);
    }
  std::vector<WindowRun<T>*> ptrs;
  for (WindowRun<T>& w : first) ptrs.push_back(&w);
  run_windows<T>(map, ptrs);
  // The re-checks, side by side.
  const ClassifyOptions ro = recheck_options(opt);
  const bool by_recurrence = opt.recheck == RecheckRule::recurrence && !is_conservative(map);
  std::vector<State<T>> lasts(who.size());
  std::vector<WindowRun<T>> later;
  std::vector<size_t> again;  // indices into who
  std::vector<char> cons(who.size(), 0), quiet(who.size(), 0);
  later.reserve(who.size());
  for (size_t k = 0; k < who.size(); ++k) {
    lasts[k] = starts[who[k]];
    Classification c = finish_window(map, first[k], opt, lasts[k]);
    bool co = false, qu = false;
    const bool re = wants_recheck(map, c, opt, co, qu);
    cons[k] = co;
    quiet[k] = qu;
    if (!re) c.evidence += windows;
    out[who[k]] = std::move(c);
    if (re) {
      if (!by_recurrence) later.emplace_back(lasts[k], ro);
      again.push_back(k);
    }
    first[k] = WindowRun<T>(State<T>{}, ClassifyOptions{0, 4, 1, 0});  // its memory back
  }
  if (by_recurrence) {
    // A dissipative map: the starts one after the other. A start may join a set on which
    // kConfirmations whole re-checks stayed aperiodic, except the audits (audit_at), which run
    // their whole re-check. As soon as a whole re-check of this map ends anywhere but on an
    // aperiodic set (the orbit settled, grew or failed), the sets may be long-lived transients:
    // the starts that joined are re-checked in full, and no start joins any more. So a joined
    // label stands only where every whole re-check of the map stayed aperiodic.
    KnownSets known;
    bool escaped = false;
    long allowed = 0;
    std::vector<size_t> joined;
    std::vector<Classification> firsts(who.size());
    const auto settle = [&](size_t k, const RecheckRun<T>& rc) {
      const std::string how =
          rc.joined ? "; re-check by recurrence: after " + std::to_string(rc.R) + " further steps the orbit had stayed " +
                          std::to_string(kJoinSteps) + " steps in the cells of an aperiodic set on which at least " +
                          std::to_string(kConfirmations) + " earlier starts of this map stayed aperiodic through " +
                          "their whole re-checks of " + std::to_string(ro.transient) + " steps, and no whole re-check settled"
                    : std::string();
      out[who[k]] = after_recheck(map, firsts[k], rc.later, lasts[k], opt, windows, false, quiet[k] != 0, rc.R, how);
      out[who[k]].recheck_joined_at = rc.joined ? rc.R : 0;
    };
    for (const size_t k : again) firsts[k] = out[who[k]];
    for (const size_t k : again) {
      std::vector<const KnownSet*> join;
      if (!escaped) {
        join = known.trusted();
        if (!join.empty() && audit_at(allowed++)) join.clear();
      }
      const RecheckRun<T> rc = recheck_run(map, lasts[k], opt, ro, join, !escaped && known.sets.size() < kMaxKnownSets);
      if (rc.joined) {
        joined.push_back(k);
      } else if (aperiodic(rc.later.cls)) {
        known.confirm(rc.seen);
      } else if (!escaped) {
        escaped = true;
        for (const size_t j : joined) settle(j, recheck_run(map, lasts[j], opt, ro, {}, false));
        joined.clear();
      }
      settle(k, rc);
    }
    return out;
  }
  ptrs.clear();
  for (WindowRun<T>& w : later) ptrs.push_back(&w);
  run_windows<T>(map, ptrs);
  for (size_t m = 0; m < again.size(); ++m) {
    const size_t k = again[m];
    State<T> later_last = lasts[k];
    const Classification lc = finish_window(map, later[m], ro, later_last);
    out[who[k]] = after_recheck(map, std::move(out[who[k]]), lc, lasts[k], opt, windows, cons[k] != 0, quiet[k] != 0,
                                ro.transient);
  }
  return out;
}

bool same_behaviour(const Classification& x, const Classification& y) {
  if (x.cls != y.cls || x.period != y.period) return false;
  if (x.cls == OrbitClass::transient_chaos) return x.settled_class == y.settled_class;
  if (x.cls == OrbitClass::unbounded) return x.growth_kind == y.growth_kind && x.accel_period == y.accel_period;
  return true;
}

std::string behaviour_difference(const Classification& x, const Classification& y) {
  if (same_behaviour(x, y)) return "";
  if (x.cls != y.cls) return "class";
  if (x.period != y.period) return "period";
  if (x.cls == OrbitClass::transient_chaos)
    return std::string("settles on ") + name(x.settled_class) + " vs " + name(y.settled_class);
  if (x.growth_kind != y.growth_kind)
    return "growth kind " + (x.growth_kind.empty() ? std::string("none") : x.growth_kind) + " vs " +
           (y.growth_kind.empty() ? std::string("none") : y.growth_kind);
  return "accelerator period " + std::to_string(x.accel_period) + " vs " + std::to_string(y.accel_period);
}

const char* name(PrecisionVerdict v) {
  switch (v) {
    case PrecisionVerdict::agrees: return "agrees";
    case PrecisionVerdict::artefact: return "artefact";
    case PrecisionVerdict::precision_dependent: return "precision_dependent";
  }
  return "?";
}

namespace {

// "periodic (period 7)", "unbounded (accelerator, period 33, gain 72)", "chaotic".
std::string behaviour_words(const Classification& c) {
  std::string s = name(c.cls);
  if (c.cls == OrbitClass::fixed || c.cls == OrbitClass::periodic || c.cls == OrbitClass::sticking)
    s += " (period " + std::to_string(c.period) + ")";
  if (c.cls == OrbitClass::transient_chaos) s += " (settles on " + std::string(name(c.settled_class)) + ")";
  if (c.cls == OrbitClass::unbounded)
    s += " (" + c.growth_kind +
         (c.accel_period ? ", period " + std::to_string(c.accel_period) + ", gain " + fmt(c.accel_gain, 4) : std::string()) + ")";
  return s;
}

}  // namespace

Classification classify_start(const ModelSpec& spec, const Precision& prec, const InitialCondition& start,
                           const ClassifyOptions& opt) {
  return with_point_scalar(prec, [&](auto tag) {
    using T = typename decltype(tag)::type;
    const ImpactMap<T> map(make_model<T>(spec, prec.bits));
    return classify<T>(map, make_state<T>(map.model(), start), opt);
  });
}

std::pair<Precision, Precision> check_precisions(const Precision& run, long check_bits) {
  Precision hi;
  hi.kind = Precision::Kind::mpfr;
  hi.bits = std::min(kMaxBits, std::max({check_bits, 64L, 2 * run.bits}));
  Precision higher = hi;
  higher.bits = std::min(kMaxBits, 2 * hi.bits);
  return {hi, higher};
}

CheckedClassification check_precision(const Classification& result, const Precision& run, long check_bits,
                                      const std::function<Classification(const Precision&)>& at) {
  CheckedClassification out;
  out.result = result;
  const std::pair<Precision, Precision> p = check_precisions(run, check_bits);
  const Precision& hi = p.first;
  const Precision& higher = p.second;
  out.checks.push_back({hi, at(hi)});
  const std::string own = run.text();
  if (same_behaviour(out.result, out.checks[0].result)) {
    out.verdict = PrecisionVerdict::agrees;
    out.summary = "agrees at " + hi.text() + ": " + behaviour_words(out.checks[0].result);
    return out;
  }
  out.checks.push_back({higher, at(higher)});
  const Classification& a = out.checks[0].result;
  const Classification& b = out.checks[1].result;
  if (same_behaviour(a, b)) {
    out.verdict = PrecisionVerdict::artefact;
    out.summary = own + "'s class (" + behaviour_words(out.result) + ") is an artefact here: at " + hi.text() + " and " +
                  higher.text() + " it is " + behaviour_words(a);
  } else {
    out.verdict = PrecisionVerdict::precision_dependent;
    out.summary = "the class depends on the precision: " + own + " " + behaviour_words(out.result) + ", " + hi.text() + " " +
                  behaviour_words(a) + ", " + higher.text() + " " + behaviour_words(b) + ": not decided at these precisions";
  }
  return out;
}

CheckedClassification classify_checked(const ModelSpec& spec, const Precision& precision, const InitialCondition& start,
                                       const ClassifyOptions& opt, long check_bits) {
  return check_precision(classify_start(spec, precision, start, opt), precision, check_bits,
                         [&](const Precision& p) { return classify_start(spec, p, start, opt); });
}

#define BOUNCER_X(T, kind) \
  template Classification classify<T>(const ImpactMap<T>&, State<T>, const ClassifyOptions&); \
  template std::vector<Classification> classify_many<T>(const ImpactMap<T>&, const std::vector<State<T>>&, \
                                                        const ClassifyOptions&);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
