// Real-time trajectories (analysis/trajectory.hpp). The physics is the map's: step() for
// each step, after_sticking() for the collapses and the ride of a sticking step, rebound()
// for the chatter's bounces; this file only places the points in time.
#include "bouncer/analysis/trajectory.hpp"

#include <algorithm>
#include <iterator>
#include <utility>

namespace bouncer {

const char* name(TraceEvent e) {
  switch (e) {
    case TraceEvent::start: return "start";
    case TraceEvent::flight: return "flight";
    case TraceEvent::impact: return "impact";
    case TraceEvent::chatter: return "chatter";
    case TraceEvent::stuck: return "stuck";
    case TraceEvent::release: return "release";
    case TraceEvent::ride: return "ride";
  }
  return "?";
}

namespace {

template <class T>
class Tracer {
  using Tr = ScalarTraits<T>;
  using Ev = TraceEvent;

 public:
  Tracer(const TrajectoryRequest& r, const ImpactMap<T>& map)
      : r_(r), map_(map), m_(map.model()), wall_(m_.wall), bits_(m_.bits) {
    t0_ = Tr::from_decimal(r.start.theta.text(), bits_);
    t_end_ = t0_ + Tr::from_int(r.periods, bits_);
    inv_n_ = Tr::from_int(1, bits_) / Tr::from_int(r.samples, bits_);
  }

  Trajectory<T> out;

  void run() {
    State<T> s = make_state<T>(m_, r_.start);
    T tn = t0_;
    add(tn, height(s.theta), Ev::start);
    try {
      while (tn < t_end_) {
        if (++out.steps > 100000) {
          out.stopped = "more than 1e5 steps in the window (stopped there)";
          break;
        }
        const StepResult<T> st = map_.step(s);
        T t_next = tn + st.tau;
        const T y0 = wall_.height_at_phase(s.theta);
        if (st.kind == EventKind::impact) {
          flight(tn, y0, s.v, t_next, Ev::flight);
          if (t_next <= t_end_) {
            add(t_next, parabola(y0, s.v, T(t_next - tn)), Ev::impact);
            ++out.impacts;
          }
        } else if (st.kind == EventKind::ride) {
          on_wall(tn, t_next, Ev::ride);
          if (t_next <= t_end_) add(t_next, height(st.next.theta), Ev::ride);
        } else {
          ++out.sticking_steps;
          // The part after the stuck collision (collapses, ride), as the map walks it.
          std::vector<typename ImpactMap<T>::Collapse> collapses;
          const T after = map_.after_sticking(st, collapses);
          const T ts = t_next - after;
          // A start on the wall with its velocity (W = 0) rides to the corner first; with
          // --downward-sticking impact the collision there may be the one that sticks.
          const bool rode = !(wall_.velocity_at(s.theta) < s.v);
          if (rode) {
            on_wall(tn, ts, Ev::ride);
            if (ts <= t_end_) add(ts, wall_at(ts), Ev::impact);
          } else {
            flight(tn, y0, s.v, ts, Ev::flight);
            if (ts <= t_end_) {
              add(ts, parabola(y0, s.v, T(ts - tn)), Ev::impact);
              ++out.impacts;
            }
          }
          // Each collapse's chatter, then riding, up to the release.
          T from = ts;
          for (const auto& c : collapses) {
            const T start = ts + c.offset;
            on_wall(from, start, Ev::stuck);
            from = chatter(start, c.w);
          }
          on_wall(from, t_next, Ev::stuck);
          if (t_next <= t_end_) add(t_next, height(st.next.theta), Ev::release);
        }
        s = st.next;
        tn = std::move(t_next);
      }
    } catch (const Undecided& u) {
      out.stopped = std::string("step ") + std::to_string(out.steps) + " undecided: " + u.what();
    }
  }

 private:
  const TrajectoryRequest& r_;
  const ImpactMap<T>& map_;
  const Model<T>& m_;
  const Wall<T>& wall_;
  long bits_;
  T t0_, t_end_, inv_n_;

  int segment(const T& theta) const { return wall_.segment_of(theta); }
  T phase(const T& t) const {
    T p = t - Tr::floor(t);
    return p;
  }
  T height(const T& theta) const { return wall_.height_at_phase(theta); }
  T wall_at(const T& t) const { return height(phase(t)); }
  T parabola(const T& y0, const T& v0, const T& s) const {
    T y = y0 + v0 * s - m_.a * s * s / 2;
    return y;
  }

  void add(const T& t, T y, Ev event) {
    out.points.push_back({t, std::move(y), wall_at(t), event, out.steps});
  }

  // The sample times strictly inside (a, b), clipped to the window: the grid t0 + k/N and
  // the wall's knots (so the wall's corners are points).
  std::vector<T> times_inside(const T& a, const T& b) const {
    std::vector<T> merged;
    const T hi = b < t_end_ ? b : t_end_;
    if (!(a < hi)) return merged;
    // grid: k from ceil((a - t0) N) on
    T k0 = Tr::floor(T((a - t0_) * Tr::from_int(r_.samples, bits_)));
    long k = static_cast<long>(Tr::to_double(k0));
    std::vector<T> grid, knots;
    for (;; ++k) {
      T t = t0_ + Tr::from_int(k, bits_) * inv_n_;
      if (!(t < hi)) break;
      if (a < t) grid.push_back(std::move(t));
    }
    T p = Tr::floor(a);
    for (long per = static_cast<long>(Tr::to_double(p));; ++per) {
      bool beyond = false;
      for (int j = 0; j < wall_.segments(); ++j) {
        T t = Tr::from_int(per, bits_) + wall_.start[j];
        if (!(t < hi)) {
          beyond = true;
          break;
        }
        if (a < t) knots.push_back(std::move(t));
      }
      if (beyond) break;
    }
    std::merge(grid.begin(), grid.end(), knots.begin(), knots.end(), std::back_inserter(merged),
               [](const T& x, const T& y) { return x < y; });
    // no duplicates (a knot on the grid)
    std::vector<T> uniq;
    for (T& t : merged)
      if (uniq.empty() || uniq.back() < t) uniq.push_back(std::move(t));
    return uniq;
  }

  void flight(const T& tn, const T& y0, const T& v0, const T& tb, Ev event) {
    for (const T& t : times_inside(tn, tb)) add(t, parabola(y0, v0, T(t - tn)), event);
  }
  void on_wall(const T& ta, const T& tb, Ev event) {
    for (const T& t : times_inside(ta, tb)) add(t, wall_at(t), event);
  }

  // The chatter from time `start` with first relative launch speed w: bounces drawn until
  // they are below what the samples resolve; returns the time of the collapse (constant
  // eps: exactly start + 2w / (a(1 - eps)), the bounces' summed durations in closed form;
  // otherwise the bounces' summed durations).
  T chatter(const T& start, const T& w0) {
    const T two = Tr::from_int(2, bits_);
    T t = start, w = w0;
    T collapse = start;  // a touchdown (w0 = 0) collapses at once
    if (m_.law == Law::constant && Tr::from_int(0, bits_) < w0) collapse = start + two * w0 / (m_.a * (1 - m_.eps));
    const double resolve = 1.0 / (50.0 * static_cast<double>(r_.samples));
    for (int k = 0; k < 2000; ++k) {
      const T dur = two * w / m_.a;
      if (m_.law == Law::constant && Tr::to_double(dur) < resolve) break;
      if (Tr::to_double(dur) < resolve * 1e-6 || !(Tr::from_int(0, bits_) < dur)) break;
      const T tb = t + dur;
      // In the wall's frame the gap is w s - (a/2) s^2: particle = wall + gap.
      if (t < t_end_) {
        for (const T& ti : times_inside(t, tb)) {
          T s = ti - t;
          T y = wall_at(ti) + w * s - m_.a * s * s / 2;
          add(ti, std::move(y), Ev::chatter);
        }
        if (tb < t_end_) add(tb, wall_at(tb), Ev::chatter);
      }
      t = tb;
      w = map_.rebound(w);
    }
    if (m_.law != Law::constant) collapse = t;
    if (collapse < t) collapse = t;
    on_wall(t, collapse, Ev::chatter);  // the unresolved tail: the particle is on the wall to the pixel
    if (collapse < t_end_) add(collapse, wall_at(collapse), Ev::stuck);
    return collapse;
  }
};

}  // namespace

template <class T>
Trajectory<T> trace_trajectory(const TrajectoryRequest& r, const ImpactMap<T>& map) {
  Tracer<T> tracer(r, map);
  tracer.run();
  return std::move(tracer.out);
}

template <class T>
Trajectory<T> trace_trajectory(const TrajectoryRequest& r) {
  const ImpactMap<T> map(make_model<T>(r.model, r.precision.bits));
  return trace_trajectory<T>(r, map);
}

#define BOUNCER_X(T, kind)                                                                   \
  template Trajectory<T> trace_trajectory<T>(const TrajectoryRequest&, const ImpactMap<T>&); \
  template Trajectory<T> trace_trajectory<T>(const TrajectoryRequest&);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
