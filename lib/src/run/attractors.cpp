// Every attractor at a parameter point (run/attractors.hpp): the recurrence mapper.
#include "bouncer/run/workers.hpp"
#include "bouncer/run/attractors.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <thread>
#include <unordered_set>

#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "bouncer/base/cancel.hpp"
#include "bouncer/base/error.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/trapping.hpp"
#include "bouncer/run/cells.hpp"

namespace bouncer {

const char* name(StartSampling s) { return s == StartSampling::grid ? "grid" : "halton"; }

const char* name(AttractorKind k) {
  switch (k) {
    case AttractorKind::periodic: return "periodic";
    case AttractorKind::family: return "family";
    case AttractorKind::sticking: return "sticking";
    case AttractorKind::chaotic: return "chaotic";
    case AttractorKind::quasiperiodic: return "quasiperiodic";
    case AttractorKind::effective_sticking: return "effective_sticking";
    case AttractorKind::accelerator: return "accelerator";
    case AttractorKind::escape: return "escape";
    case AttractorKind::undecided: return "undecided";
  }
  return "?";
}

double share_stderr(long k, long n) {
  if (n <= 0) return 0;
  const double p = static_cast<double>(k) / static_cast<double>(n);
  return std::sqrt(p * (1 - p) / static_cast<double>(n));
}

namespace {

constexpr double kRepeatTol = 1e-9;  // states repeat (as classify: relative, theta mod 1)
constexpr double kMatchTol = 1e-6;   // two periodic attractors are one: a point within this
constexpr double kNearTol = 1e-8;    // a start has reached a stable periodic orbit
constexpr double kOverlap = 0.5;     // two aperiodic sets are one: this share of cells shared
constexpr size_t kSample = 64;       // points kept of an aperiodic set
constexpr long kMaxPoints = 1000;    // points kept of a sticking cycle (its period may be 10^4)

std::string fmt(double x, int digits = 4) {
  std::ostringstream os;
  os << std::setprecision(digits) << x;
  return os.str();
}

void check_request(const AttractorsRequest& r) {
  auto in = [](const std::string& field, long x, long lo, long hi) {
    if (x < lo || x > hi)
      throw InputError(field, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                                  std::to_string(x) + ")");
  };
  if (r.nx < 1 || r.ny < 1 || r.nx > 8192 || r.ny > 8192 || r.nx * r.ny > 4000000)
    throw InputError("starts", "must be NxM with 1 <= N, M <= 8192 and N*M <= 4000000 (got " + std::to_string(r.nx) + "x" +
                                   std::to_string(r.ny) + ")");
  if (r.cells_theta < 16 || r.cells_v < 16 || r.cells_theta > 4096 || r.cells_v > 4096)
    throw InputError("cells", "must be NxM with 16 <= N, M <= 4096 (got " + std::to_string(r.cells_theta) + "x" +
                                  std::to_string(r.cells_v) + ")");
  if (!(r.theta_lo < r.theta_hi)) throw InputError("theta-range", "needs LO < HI");
  if (r.theta_lo < Decimal::from_int(0) || r.theta_hi > Decimal::from_int(1))
    throw InputError("theta-range", "must lie in [0, 1] (got '" + r.theta_lo.text() + ":" + r.theta_hi.text() + "')");
  if (r.v_range) {
    if (!(r.v_range->first < r.v_range->second)) throw InputError("v-range", "needs LO < HI");
    if (r.v_range->second.approx() > 1e6 || r.v_range->first.approx() < -1e6) throw InputError("v-range", "must lie within +-1e6");
  }
  in("recurrences", r.consecutive_recurrences, 1, 1000000);
  in("attractor-steps", r.attractor_steps, 10, 10000000);
  in("hits", r.consecutive_hits, 1, 1000000);
  in("lost-steps", r.lost_steps, 1, 1000000);
  in("max-steps", r.max_steps, 100, 1000000000);
  in("max-period", r.max_period, 1, 4096);
  in("lyapunov-steps", r.lyapunov_steps, 100, 1000000000);
  in("max-bits", r.max_bits, 64, 4096);
  if (!r.precision.is_analysis())
    throw InputError("precision", "interval precision is not supported here (use " + precision_names<AnalysisScalars>(" or ") + ")");
}

// The radical inverse of i in base b: i's digits mirrored behind the point, as num/den.
std::pair<long, long> radical_inverse(long i, long b) {
  long num = 0, den = 1;
  for (; i > 0; i /= b) {
    num = num * b + i % b;
    den *= b;
  }
  return {num, den};
}

// A scrambled order of n starts: i -> i * s mod n with s coprime to n near 0.618 n, so that
// the first batches sample the whole window.
long scramble_stride(long n) {
  if (n <= 2) return 1;
  long s = std::max(1L, static_cast<long>(static_cast<double>(n) * 0.6180339887)) | 1;
  while (std::gcd(s, n) != 1) ++s;
  return s;
}

struct CellGrid {
  long ct = 0, cv = 0;
  double v_lo = 0, v_hi = 0;
  // The cell of (theta, v); -1 above the grid (a step towards escape). Below: the bottom row.
  long of(double theta, double v) const {
    if (!(v <= v_hi)) return -1;
    long i = static_cast<long>(std::floor(theta * static_cast<double>(ct)));
    long j = static_cast<long>(std::floor((v - v_lo) / (v_hi - v_lo) * static_cast<double>(cv)));
    i = std::clamp(i, 0L, ct - 1);
    j = std::clamp(j, 0L, cv - 1);
    return j * ct + i;
  }
  // The cell and its 8 neighbours (theta wraps), for the points of a periodic orbit.
  void around(double theta, double v, std::vector<long>& out) const {
    const long c = of(theta, v);
    if (c < 0) return;
    const long i = c % ct, j = c / ct;
    for (long dj = -1; dj <= 1; ++dj)
      for (long di = -1; di <= 1; ++di) {
        const long jj = j + dj;
        if (jj < 0 || jj >= cv) continue;
        out.push_back(jj * ct + (i + di + ct) % ct);
      }
  }
};

void sort_unique(std::vector<long>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// An attractor while the mapper runs, in the run's scalar.
template <class T>
struct Att {
  AttractorKind kind = AttractorKind::undecided;
  long period = 0;
  std::vector<State<T>> points;  // the orbit (periodic, family member, sticking), or a sample
  std::vector<double> family_v;  // family: the member's sorted velocities
  bool has_multipliers = false;
  Eigen2<T> multipliers{};
  double lambda = 0, lambda_stderr = 0;
  long lyapunov_steps = 0;
  long long followed = 0;
  double accel_gain = 0;
  std::string evidence;
  std::vector<long> cells;  // sorted
  double fam_min = 0, fam_max = 0;
  long fam_members = 0;
  long first_start = -1;
  bool periodic_like() const { return kind == AttractorKind::periodic || kind == AttractorKind::sticking; }
};

template <class T>
struct Outcome {
  int label = AttractorsResult::kUndecidedStart;  // a known attractor, or a candidate's
  std::unique_ptr<Att<T>> candidate;              // a new recurrence, characterized
  long long steps = 0;
};

template <class T>
class Mapper {
 public:
  using Tr = ScalarTraits<T>;
  const AttractorsRequest& r;
  ImpactMap<T> map;
  CellGrid grid;
  std::vector<int> owner;
  std::vector<Att<T>> atts;
  int sticking_att = -1;

  explicit Mapper(const AttractorsRequest& req) : r(req), map(make_model<T>(req.model, req.precision.bits)) {
    const Model<T>& m = map.model();
    double lowest = 0;
    for (const T& u : m.wall.velocity) lowest = std::min(lowest, Tr::to_double(u));
    if (m.wall.smooth()) lowest = -Tr::to_double(m.wall.two_pi);  // min 2 pi cos(2 pi theta)
    grid.ct = r.cells_theta;
    grid.cv = r.cells_v;
    grid.v_lo = lowest;
    double top = r.v_range->second.approx();
    if (const auto t = trapping_top(m)) top = std::max(top, Tr::to_double(*t));
    grid.v_hi = top;
    owner.assign(static_cast<size_t>(grid.ct * grid.cv), -1);
  }

  long cell(const State<T>& s) const { return grid.of(Tr::to_double(s.theta), Tr::to_double(s.v)); }

  // --- one start -----------------------------------------------------------------------
  Outcome<T> follow(State<T> s) const {
    Outcome<T> out;
    std::unordered_set<long> visited;
    visited.reserve(512);
    long rec = 0, hits = 0, lost = 0, sticks = 0, skipped = 0;
    int hit_label = -1;
    try {
      for (long n = 0; n < r.max_steps; ++n) {
        throw_if_cancelled(n);
        StepResult<T> st = map.step(s);
        s = std::move(st.next);
        ++out.steps;
        if (st.kind == EventKind::sticking && sticking_att >= 0) {
          out.label = sticking_att;  // the release state's future is the sticking cycle
          return out;
        }
        if (st.kind == EventKind::sticking && ++sticks == 2) {
          // Stuck twice, no sticking cycle known yet: the release state's orbit, followed
          // until the release recurs exactly, is one (however long its period) or is not.
          Att<T> a = sticking_cycle(s, out.steps, r.max_steps);
          if (a.kind == AttractorKind::sticking) {
            out.candidate = std::make_unique<Att<T>>(std::move(a));
            return out;
          }
        }
        const long c = cell(s);
        if (c < 0) {
          rec = hits = 0;
          if (++lost >= r.lost_steps) {
            out.candidate = std::make_unique<Att<T>>(escape(s, out.steps));
            return out;
          }
          continue;
        }
        lost = 0;
        const int k = owner[static_cast<size_t>(c)];
        bool approaching = false;  // on a known periodic orbit's cells: converging, not new
        if (k >= 0) {
          const Att<T>& a = atts[static_cast<size_t>(k)];
          if (a.kind == AttractorKind::sticking) {
            hits = 0;  // (a sticking cycle has no cells: its starts are decided by sticking)
          } else if (a.kind == AttractorKind::periodic) {
            hits = 0;
            approaching = true;
            for (const State<T>& p : a.points)
              if (state_distance(s, p) <= kNearTol) {
                out.label = k;
                return out;
              }
          } else {
            hits = hit_label == k ? hits + 1 : 1;
            hit_label = k;
            if (hits >= r.consecutive_hits) {
              out.label = k;
              return out;
            }
          }
        } else {
          hits = 0;
        }
        // A revisit on a known periodic orbit's cells neither counts nor breaks a run of
        // recurrences (the start is likely converging to it: the `near` test decides), up to
        // a budget, after which it counts: another orbit may pass through those cells.
        if (visited.insert(c).second) {
          rec = 0;
        } else if (approaching && skipped < 100 * r.consecutive_recurrences) {
          ++skipped;
        } else if (++rec >= r.consecutive_recurrences) {
          out.candidate = std::make_unique<Att<T>>(characterize(s, out.steps, 0));
          return out;
        }
      }
    } catch (const Undecided&) {
      // a step the scalar could not decide (NaN, overflow): the start stays undecided
    }
    return out;
  }

  // --- characterization ----------------------------------------------------------------
  // The smallest q <= qmax with run[i + q] = run[i] over the second half of the run (and at
  // least q comparisons), or 0.
  static long repeat_period(const std::vector<State<T>>& run, long qmax) {
    const long L = static_cast<long>(run.size());
    for (long q = 1; q <= std::min(qmax, L / 2); ++q) {
      bool ok = true;
      for (long i = std::min(L / 2, L - 2 * q); i + q < L && ok; ++i) ok = state_distance(run[i], run[i + q]) <= kRepeatTol;
      if (ok) return q;
    }
    return 0;
  }

  void record_cells(Att<T>& a, const std::vector<State<T>>& run) const {
    for (const State<T>& x : run) {
      const long c = cell(x);
      if (c >= 0) a.cells.push_back(c);
    }
    sort_unique(a.cells);
  }
  void point_cells(Att<T>& a) const {
    for (const State<T>& p : a.points) grid.around(Tr::to_double(p.theta), Tr::to_double(p.v), a.cells);
    sort_unique(a.cells);
  }

  // The sticking cycle through the release state `release` (the state after a sticking step).
  Att<T> sticking_cycle(const State<T>& release, long long& steps, long cap = 0) const {
    Att<T> a;
    if (cap <= 0) cap = r.max_steps;
    State<T> x = release;
    std::vector<State<T>> orbit{release};
    for (long k = 1; k <= cap; ++k) {
      StepResult<T> st = map.step(x);
      x = std::move(st.next);
      ++steps;
      if (st.kind == EventKind::sticking && x.theta == release.theta && x.v == release.v) {
        a.kind = AttractorKind::sticking;
        a.period = k;
        a.points = std::move(orbit);
        a.followed = k;
        a.lambda = -std::numeric_limits<double>::infinity();
        a.evidence = "the release state (" + fmt(Tr::to_double(release.theta), 6) + ", " + fmt(Tr::to_double(release.v), 6) +
                     ") recurs exactly after " + std::to_string(k) + " steps, at a sticking step";
        // No cells: every start that sticks is decided by the sticking step itself, and the
        // cells of a long cycle would cover other attractors'.
        return a;
      }
      if (static_cast<long>(orbit.size()) < kMaxPoints) orbit.push_back(x);
    }
    a.kind = AttractorKind::undecided;
    a.evidence = "a sticking step, but the release state did not recur within " + std::to_string(cap) + " steps";
    a.points.assign(orbit.begin(), orbit.begin() + std::min<long>(static_cast<long>(orbit.size()), kSample));
    record_cells(a, orbit);
    return a;
  }

  // A periodic attractor of period q through x (on it to kRepeatTol): Newton refines it.
  Att<T> periodic(const State<T>& x, long q, const std::vector<State<T>>& run, const std::string& how) const {
    Att<T> a;
    a.kind = AttractorKind::periodic;
    a.period = q;
    NewtonOptions no;
    const PeriodicOrbit<T> o = find_periodic<T>(map.model(), q, x, no);
    if (o.converged && !o.points.empty() && state_distance(o.points[0], x) <= kMatchTol) {
      a.points = o.points;
      a.period = o.minimal_period > 0 ? o.minimal_period : q;
      a.points.resize(static_cast<size_t>(a.period));
      a.has_multipliers = true;
      a.multipliers = o.multipliers;
      if (o.marginal) a.kind = AttractorKind::family;
      a.evidence = how + "; Newton: residual " + fmt(o.residual, 2);
    } else {
      // Newton did not confirm it: the recorded orbit itself (the certificate decides).
      a.points.assign(run.end() - q, run.end());
      a.evidence = how + "; Newton did not converge (" + o.note + ")";
    }
    // Start the orbit at its point of smallest theta (a canonical order for the output).
    const auto first = std::min_element(a.points.begin(), a.points.end(), [](const State<T>& u, const State<T>& w) {
      return Tr::to_double(u.theta) < Tr::to_double(w.theta);
    });
    std::rotate(a.points.begin(), first, a.points.end());
    if (a.kind == AttractorKind::family) {
      for (const State<T>& p : a.points) a.family_v.push_back(Tr::to_double(p.v));
      std::sort(a.family_v.begin(), a.family_v.end());
      a.fam_min = a.fam_max = Tr::to_double(a.points[0].theta);
      a.fam_members = 1;
    }
    point_cells(a);
    return a;
  }

  // Follows an orbit `n` steps, keeping the last `keep` states; returns the release state of
  // the last sticking step seen (or none).
  std::optional<State<T>> advance(State<T>& x, long n, std::vector<State<T>>& tail, size_t keep, long long& steps) const {
    std::optional<State<T>> release;
    tail.clear();
    for (long i = 0; i < n; ++i) {
      throw_if_cancelled(i);
      StepResult<T> st = map.step(x);
      x = std::move(st.next);
      ++steps;
      if (st.kind == EventKind::sticking) release = x;
      if (static_cast<long>(i) >= n - static_cast<long>(keep)) tail.push_back(x);
    }
    return release;
  }

  Att<T> characterize(State<T> x, long long& steps, int depth) const {
    const long long start_steps = steps;
    std::vector<State<T>> run;
    Att<T> a;
    try {
      std::optional<State<T>> release =
          advance(x, r.attractor_steps, run, static_cast<size_t>(r.attractor_steps), steps);
      if (release) {
        a = sticking_cycle(*release, steps);
      } else if (const long q = repeat_period(run, r.max_period); q > 0) {
        a = periodic(run.back(), q, run,
                     "recurrence: the state repeats after " + std::to_string(q) + " step" + (q == 1 ? "" : "s") + " to " +
                         fmt(kRepeatTol, 2));
      } else {
        a = classified(x, run, steps, depth);
        record_cells(a, run);
      }
    } catch (const Undecided& e) {
      a = Att<T>{};
      a.kind = AttractorKind::undecided;
      a.evidence = std::string("a step was undecided: ") + e.what();
      record_cells(a, run);
    }
    a.followed = steps - start_steps;
    return a;
  }

  // The orbit does not repeat within max_period after its recurrence: classify decides.
  Att<T> classified(State<T> x, std::vector<State<T>>& run, long long& steps, int depth) const {
    const Classification c = classify<T>(map, x, r.classify);
    Att<T> a;
    const long window = r.classify.transient + r.classify.steps;
    // classify's own steps: its window, and the re-check of an aperiodic verdict.
    const bool rechecked = c.cls == OrbitClass::chaotic || c.cls == OrbitClass::quasiperiodic ||
                           c.cls == OrbitClass::transient_chaos;
    steps += window + (rechecked ? r.classify.recheck_factor * std::max(r.classify.transient, r.classify.steps) +
                                       std::max(4L, r.classify.steps)
                                 : 0);
    switch (c.cls) {
      case OrbitClass::fixed:
      case OrbitClass::periodic:
      case OrbitClass::sticking:
      case OrbitClass::transient_chaos: {
        // A long period, a slow approach or a long chaotic transient: follow the orbit past
        // what classify saw, then read its period off the tail.
        const long R = r.classify.recheck_factor * std::max(r.classify.transient, r.classify.steps);
        const long n = window + (c.cls == OrbitClass::transient_chaos ? R + c.settled_at : 0);
        const long q = std::max(1L, c.period);
        std::vector<State<T>> tail;
        const auto release = advance(x, n, tail, static_cast<size_t>(std::min(n, 4 * q + 16)), steps);
        const OrbitClass settled = c.cls == OrbitClass::transient_chaos ? c.settled_class : c.cls;
        if (release && settled == OrbitClass::sticking) return sticking_cycle(*release, steps);
        if ((settled == OrbitClass::fixed || settled == OrbitClass::periodic) && repeat_period(tail, q) == q) {
          run.insert(run.end(), tail.begin(), tail.end());
          return periodic(tail.back(), q, tail, "classify: " + std::string(name(c.cls)) + " (" + c.evidence + ")");
        }
        if (depth < 1) return characterize(x, steps, depth + 1);
        a.kind = AttractorKind::undecided;
        a.evidence = "classify said " + std::string(name(c.cls)) + " but the orbit did not repeat later (" + c.evidence + ")";
        break;
      }
      case OrbitClass::chaotic:
      case OrbitClass::quasiperiodic: {
        a.kind = c.cls == OrbitClass::chaotic ? AttractorKind::chaotic : AttractorKind::quasiperiodic;
        // Its cells: the set followed further (up to 20 recordings), then its exponent.
        std::vector<State<T>> more;
        const long n = std::min(r.lyapunov_steps, 20 * r.attractor_steps);
        advance(x, n, more, static_cast<size_t>(n), steps);
        run.insert(run.end(), more.begin(), more.end());
        LyapunovOptions lo;
        lo.transient = 0;
        lo.steps = r.lyapunov_steps;
        lo.blocks = 20;
        const LyapunovResult l = lyapunov<T>(map.model(), x, lo);
        steps += l.steps;
        a.lambda = l.lambda;
        a.lambda_stderr = l.stderr_;
        a.lyapunov_steps = l.steps;
        a.evidence = "classify: " + std::string(name(c.cls)) + "; exponent " + fmt(l.lambda) + " +- " + fmt(l.stderr_, 2) +
                     " per collision over " + std::to_string(l.steps) + " steps" + (l.note.empty() ? "" : " (" + l.note + ")");
        if (l.undecided || l.contracted) a.kind = AttractorKind::undecided;
        break;
      }
      case OrbitClass::effective_sticking:
        a.kind = AttractorKind::effective_sticking;
        a.evidence = "classify: " + c.evidence;
        break;
      case OrbitClass::unbounded:
        a = from_growth(c);
        break;
      default:
        a.kind = AttractorKind::undecided;
        a.evidence = "classify: " + std::string(name(c.cls)) + " (" + c.evidence + ")";
        break;
    }
    for (size_t i = 0; i < run.size() && a.points.size() < kSample; i += std::max<size_t>(1, run.size() / kSample))
      a.points.push_back(run[i]);
    return a;
  }

  static Att<T> from_growth(const Classification& c) {
    Att<T> a;
    if (c.growth_kind == "accelerator" && c.accel_period > 0) {
      a.kind = AttractorKind::accelerator;
      a.period = c.accel_period;
      a.accel_gain = c.accel_gain;
    } else {
      a.kind = AttractorKind::escape;
    }
    a.evidence = "classify: " + c.evidence;
    return a;
  }

  // A start that left the grid: classify tells an accelerator mode from other escapes.
  Att<T> escape(const State<T>& x, long long& steps) const {
    const Classification c = classify<T>(map, x, r.classify);
    steps += r.classify.transient + r.classify.steps;
    if (c.cls == OrbitClass::unbounded) return from_growth(c);
    Att<T> a;
    a.kind = AttractorKind::escape;
    a.evidence = "left the trapping region's grid for " + std::to_string(r.lost_steps) + " steps; then classify: " +
                 name(c.cls) + " (" + c.evidence + ")";
    return a;
  }

  // --- matching ------------------------------------------------------------------------
  static bool aperiodic(AttractorKind k) {
    return k == AttractorKind::chaotic || k == AttractorKind::quasiperiodic || k == AttractorKind::effective_sticking ||
           k == AttractorKind::undecided;
  }
  static double shared(const std::vector<long>& a, const std::vector<long>& b) {
    if (a.empty()) return 0;
    size_t n = 0;
    for (size_t i = 0, j = 0; i < a.size() && j < b.size();) {
      if (a[i] == b[j]) ++n, ++i, ++j;
      else if (a[i] < b[j]) ++i;
      else ++j;
    }
    return static_cast<double>(n) / static_cast<double>(a.size());
  }

  int match(const Att<T>& c) const {
    for (size_t k = 0; k < atts.size(); ++k) {
      const Att<T>& a = atts[k];
      bool same = false;
      if (c.kind == AttractorKind::sticking && a.kind == AttractorKind::sticking) {
        same = a.period == c.period;
      } else if (c.kind == AttractorKind::periodic && a.kind == AttractorKind::periodic && a.period == c.period) {
        for (const State<T>& p : a.points) same = same || state_distance(p, c.points[0]) <= kMatchTol;
      } else if (c.kind == AttractorKind::family && a.kind == AttractorKind::family && a.period == c.period) {
        same = true;
        for (size_t i = 0; i < c.family_v.size() && same; ++i)
          same = std::fabs(c.family_v[i] - a.family_v[i]) <= kMatchTol * std::max(1.0, std::fabs(a.family_v[i]));
      } else if (c.kind == a.kind && (c.kind == AttractorKind::accelerator || c.kind == AttractorKind::escape)) {
        same = a.period == c.period;
      } else if (aperiodic(c.kind) && aperiodic(a.kind)) {
        same = shared(c.cells, a.cells) >= kOverlap;
      }
      if (same) return static_cast<int>(k);
    }
    return -1;
  }

  void label_cells(int k, const std::vector<long>& cells) {
    for (long c : cells)
      if (owner[static_cast<size_t>(c)] < 0) owner[static_cast<size_t>(c)] = k;
  }

  // A candidate of start `start`: the attractor it matches (its cells added), or a new one.
  int absorb(Att<T>&& c, long start) {
    const int k = match(c);
    if (k >= 0) {
      Att<T>& a = atts[static_cast<size_t>(k)];
      if (a.kind == AttractorKind::family) {
        for (const State<T>& p : c.points) {
          a.fam_min = std::min(a.fam_min, Tr::to_double(p.theta));
          a.fam_max = std::max(a.fam_max, Tr::to_double(p.theta));
        }
        ++a.fam_members;
      }
      if (!a.periodic_like()) {
        std::vector<long> u;
        std::set_union(a.cells.begin(), a.cells.end(), c.cells.begin(), c.cells.end(), std::back_inserter(u));
        a.cells = std::move(u);
        label_cells(k, c.cells);
      }
      return k;
    }
    c.first_start = start;
    atts.push_back(std::move(c));
    const int n = static_cast<int>(atts.size()) - 1;
    if (atts.back().kind == AttractorKind::sticking && sticking_att < 0) sticking_att = n;
    label_cells(n, atts.back().cells);
    return n;
  }
};

template <class T>
FoundAttractor found(const Att<T>& a) {
  FoundAttractor f;
  f.kind = a.kind;
  f.period = a.period;
  for (const State<T>& p : a.points) f.points.push_back({number_of(p.theta), number_of(p.v)});
  if (a.has_multipliers) {
    for (int i = 0; i < 2; ++i) {
      f.multipliers.emplace_back(number_of(a.multipliers.re[i]), number_of(a.multipliers.im[i]));
      f.multiplier_moduli.push_back(a.multipliers.modulus(i));
    }
    const double m0 = f.multiplier_moduli[0], m1 = f.multiplier_moduli[1];
    f.stable = a.kind == AttractorKind::family ? std::min(m0, m1) < 1 : std::max(m0, m1) < 1;
  }
  if (a.kind == AttractorKind::sticking) f.stable = true;  // the release is a point: J = 0
  f.family_theta_min = a.fam_min;
  f.family_theta_max = a.fam_max;
  f.family_members = a.fam_members;
  f.lambda = a.lambda;
  f.lambda_stderr = a.lambda_stderr;
  f.lyapunov_steps = a.lyapunov_steps;
  f.followed_steps = a.followed;
  f.accel_gain = a.accel_gain;
  f.evidence = a.evidence;
  f.first_start = a.first_start;
  return f;
}

template <class T>
AttractorsResult run_mapper(const AttractorsRequest& req, const GridOptions& run) {
  using Tr = ScalarTraits<T>;
  const auto t0 = std::chrono::steady_clock::now();
  Mapper<T> m(req);
  const long N = req.nx * req.ny;
  const long bits = req.precision.bits;
  auto num = [&](const Decimal& d) { return Tr::from_decimal(d.text(), bits); };
  const T th0 = num(req.theta_lo), th1 = num(req.theta_hi), v0 = num(req.v_range->first), v1 = num(req.v_range->second);
  std::vector<State<T>> starts(static_cast<size_t>(N));
  for (long i = 0; i < N; ++i) {
    if (req.sampling == StartSampling::grid) {
      starts[static_cast<size_t>(i)] = {cell_centre(th0, th1, i % req.nx, req.nx), cell_centre(v0, v1, i / req.nx, req.ny)};
    } else {
      const auto [a2, b2] = radical_inverse(i + 1, 2);
      const auto [a3, b3] = radical_inverse(i + 1, 3);
      starts[static_cast<size_t>(i)] = {th0 + (th1 - th0) * Tr::from_int(a2, bits) / Tr::from_int(b2, bits),
                                        v0 + (v1 - v0) * Tr::from_int(a3, bits) / Tr::from_int(b3, bits)};
    }
  }
  AttractorsResult res;
  res.request = req;
  res.label.assign(static_cast<size_t>(N), AttractorsResult::kUndecidedStart);
  for (const State<T>& s : starts) {
    res.theta.push_back(number_of(s.theta));
    res.v.push_back(number_of(s.v));
  }
  const auto& wall = m.map.model().wall;
  std::vector<long> order;
  order.reserve(static_cast<size_t>(N));
  const long stride = scramble_stride(N);
  for (long i = 0; i < N; ++i) {
    const long s = static_cast<long>((static_cast<__int128>(i) * stride) % N);
    const State<T>& x = starts[static_cast<size_t>(s)];
    if (x.v < wall.velocity_at(x.theta)) {
      res.label[static_cast<size_t>(s)] = AttractorsResult::kOutside;
      continue;
    }
    order.push_back(s);
  }
  const unsigned threads = worker_threads(run.threads);
  const std::atomic<bool>* cancel = current_cancel_flag();
  ProgressBar bar(run.label.empty() ? "attractors" : run.label, static_cast<long>(order.size()), run.progress);
  long done = 0, batch = 1;
  while (done < static_cast<long>(order.size())) {
    const long n = std::min(batch, static_cast<long>(order.size()) - done);
    std::vector<Outcome<T>> out(static_cast<size_t>(n));
    std::atomic<long> next{0};
    std::exception_ptr error;
    std::atomic<bool> failed{false};
    auto work = [&] {
      CancelScope scope(cancel);
      for (long j; (j = next++) < n && !failed;) {
        try {
          out[static_cast<size_t>(j)] = m.follow(starts[static_cast<size_t>(order[static_cast<size_t>(done + j)])]);
        } catch (...) {
          if (!failed.exchange(true)) error = std::current_exception();
        }
      }
    };
    run_workers(static_cast<unsigned>(std::min<long>(threads, n)), work);
    if (error) std::rethrow_exception(error);
    for (long j = 0; j < n; ++j) {
      Outcome<T>& o = out[static_cast<size_t>(j)];
      const long s = order[static_cast<size_t>(done + j)];
      res.steps += o.steps;
      if (o.candidate) {
        ++res.candidates;
        res.steps += o.candidate->followed;
        o.label = m.absorb(std::move(*o.candidate), s);
      }
      res.label[static_cast<size_t>(s)] = o.label;
    }
    done += n;
    bar.advance(n);
    batch = std::min(2 * batch, 256L);
    if (done == 1) batch = 1;  // sizes 1, 1, 2, 4, ...
  }
  bar.finish();
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Counts, and the attractors renumbered by basin size (largest first; ties: found first).
  std::vector<long> count(m.atts.size(), 0);
  for (int l : res.label) {
    if (l >= 0) ++count[static_cast<size_t>(l)];
    else if (l == AttractorsResult::kOutside) ++res.outside;
    else ++res.undecided;
  }
  res.inside = N - res.outside;
  std::vector<int> rank(m.atts.size());
  std::iota(rank.begin(), rank.end(), 0);
  std::stable_sort(rank.begin(), rank.end(), [&](int x, int y) {
    return count[static_cast<size_t>(x)] > count[static_cast<size_t>(y)];
  });
  std::vector<int> new_id(m.atts.size());
  for (size_t i = 0; i < rank.size(); ++i) new_id[static_cast<size_t>(rank[i])] = static_cast<int>(i);
  for (int& l : res.label)
    if (l >= 0) l = new_id[static_cast<size_t>(l)];
  std::vector<long> cells(m.atts.size(), 0);
  for (int o : m.owner)
    if (o >= 0) ++cells[static_cast<size_t>(o)];
  const auto tc = std::chrono::steady_clock::now();
  for (size_t i = 0; i < rank.size(); ++i) {
    const Att<T>& a = m.atts[static_cast<size_t>(rank[i])];
    FoundAttractor f = found(a);
    f.id = static_cast<int>(i);
    f.starts = count[static_cast<size_t>(rank[i])];
    f.cells = cells[static_cast<size_t>(rank[i])];
    f.fraction = res.inside > 0 ? static_cast<double>(f.starts) / static_cast<double>(res.inside) : 0;
    f.fraction_stderr = share_stderr(f.starts, res.inside);
    const bool provable = a.kind == AttractorKind::periodic || a.kind == AttractorKind::family || a.kind == AttractorKind::sticking;
    if (req.certify && provable && !a.points.empty()) {
      PeriodicQuestion q;
      q.model = req.model;
      q.period = a.period;
      const auto th = Decimal::parse(Tr::to_string(a.points[0].theta));
      const auto v = Decimal::parse(Tr::to_string(a.points[0].v));
      if (th && v) q.guess = InitialCondition{*th, *v};
      q.schedule = EscalationSchedule{64, req.max_bits, false};
      f.certificate = certify_periodic(q);
    }
    res.attractors.push_back(std::move(f));
  }
  res.certify_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tc).count();
  res.undecided_fraction = res.inside > 0 ? static_cast<double>(res.undecided) / static_cast<double>(res.inside) : 0;
  res.undecided_stderr = share_stderr(res.undecided, res.inside);
  res.cell_theta = 1.0 / static_cast<double>(m.grid.ct);
  res.cell_v = (m.grid.v_hi - m.grid.v_lo) / static_cast<double>(m.grid.cv);
  res.grid_v_lo = m.grid.v_lo;
  res.grid_v_hi = m.grid.v_hi;
  return res;
}

}  // namespace

std::pair<Decimal, Decimal> attractors_v_range(const AttractorsRequest& r) { return starts_v_range(r.model, r.v_range); }

AttractorsResult find_attractors(const AttractorsRequest& r, const GridOptions& run) {
  check_request(r);
  AttractorsRequest req = r;
  req.v_range = attractors_v_range(r);
  return with_point_scalar(req.precision, [&](auto tag) { return run_mapper<typename decltype(tag)::type>(req, run); });
}

}  // namespace bouncer
