// bouncer trajectory: the particle's height and the wall's height against time (the paper's
// fig. realtime), from a state (theta, v) of the impact map, over a few wall periods.
//
// The time axis is absolute time t with t = theta_0 at the start state, so the wall is
// f(t mod 1). The map gives each step's start state (theta_n, v_n: on the wall, particle
// velocity v_n, absolute, not relative to the wall: ImpactMap::step forms W = v - fdot) and
// its duration tau. Between them the particle is drawn exactly:
//   * a flight (event impact): the parabola y = f(theta_n) + v_n s - (a/2) s^2, s = t - t_n,
//     up to the impact at t_n + tau;
//   * a ride (event ride): on the wall until t_n + tau;
//   * a sticking step: the flight to the collision where it stuck (stuck_theta, stuck_v),
//     then the chatter (bounces of relative launch speed w_k, w_{k+1} = eps w_k, each lasting
//     2 w_k / a in the wall's frame) until the collapse, then the ride on the wall to the
//     release at t_n + tau (README "Sticking"). The ride from the stuck collision is the
//     same walk as ImpactMap's (to the next downward turn; an upward turn with
//     --downward-sticking impact is a collision of relative speed u_next - u_prev).
// Every number is computed in the chosen point type and printed so that it reads back to
// the same value; the picture is drawn from the same rows.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>
#include <sstream>

#include "bouncer/model/impact_map.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

struct TrajectoryRequest {
  ModelSpec model;
  InitialCondition start;
  long periods = 3, samples = 400;
  Precision precision;
};

TrajectoryRequest trajectory_request(const Options& o) {
  TrajectoryRequest r;
  r.model = model_from(o);
  r.start.theta = parse_decimal("theta", o.get_or("theta", "0.3"));
  r.start.v = parse_decimal("v", o.get_or("v", "12"));
  validate(r.model, r.start, "theta", "v");
  r.periods = integer_from(o, "periods", 1, 100, 3);
  r.samples = integer_from(o, "samples", 8, 10000, 400);
  r.precision = point_precision(o);
  return r;
}

// One row of the CSV and one point of the picture.
struct Row {
  std::string t, y, wall, event;
  long step = 0;
  double td = 0, yd = 0, wd = 0;
};

template <class T>
class Tracer {
  using Tr = ScalarTraits<T>;

 public:
  Tracer(const TrajectoryRequest& r, const ImpactMap<T>& map) : r_(r), map_(map), m_(map.model()), wall_(m_.wall) {
    bits_ = r.precision.bits;
    t0_ = Tr::from_decimal(r.start.theta.text(), bits_);
    t_end_ = t0_ + Tr::from_int(r.periods, bits_);
    inv_n_ = Tr::from_int(1, bits_) / Tr::from_int(r.samples, bits_);
  }

  std::vector<Row> rows;
  long impacts = 0, sticking_steps = 0, steps = 0;
  std::string note;  // why the trace stopped early, if it did

  void run() {
    State<T> s = make_state<T>(m_, r_.start);
    T tn = t0_;
    add(tn, height(s.theta), "start");
    try {
      while (tn < t_end_) {
        if (++steps > 100000) {
          note = "more than 1e5 steps in the window (stopped there)";
          break;
        }
        const StepResult<T> st = map_.step(s);
        T t_next = tn + st.tau;
        const T y0 = wall_.height_at(segment(s.theta), s.theta);
        if (st.kind == EventKind::impact) {
          flight(tn, y0, s.v, t_next, "flight");
          if (t_next <= t_end_) {
            T y = parabola(y0, s.v, T(t_next - tn));
            add(t_next, std::move(y), "impact");
            ++impacts;
          }
        } else if (st.kind == EventKind::ride) {
          on_wall(tn, t_next, "ride");
          if (t_next <= t_end_) add(t_next, height(st.next.theta), "ride");
        } else {
          ++sticking_steps;
          // Duration of the part after the stuck collision (chatter, ride), by the walk below.
          std::vector<Chatter> chatters;
          const T after = after_stuck(st, chatters);
          const T ts = t_next - after;
          // A start on the wall with its velocity (W = 0) rides to the corner first; with
          // --downward-sticking impact the collision there may be the one that sticks.
          const bool rode = !(wall_.velocity[segment(s.theta)] < s.v);
          if (rode) {
            on_wall(tn, ts, "ride");
          } else {
            flight(tn, y0, s.v, ts, "flight");
          }
          if (rode) {
            if (ts <= t_end_) add(ts, wall_at(ts), "impact");
          } else if (ts <= t_end_) {
            T y = parabola(y0, s.v, T(ts - tn));
            add(ts, std::move(y), "impact");
            ++impacts;
          }
          // Chatter sequences (at the stuck collision, and at upward turns with
          // --downward-sticking impact), each followed by riding, up to the release.
          T from = ts;
          for (size_t c = 0; c < chatters.size(); ++c) {
            const T start = ts + chatters[c].offset;
            on_wall(from, start, "stuck");
            from = chatter(start, chatters[c].w);
          }
          on_wall(from, t_next, "stuck");
          if (t_next <= t_end_) add(t_next, height(st.next.theta), "release");
        }
        s = st.next;
        tn = std::move(t_next);
      }
    } catch (const Undecided& u) {
      note = std::string("step ") + std::to_string(steps) + " undecided: " + u.what();
    }
  }

 private:
  struct Chatter {
    T offset;  // from the stuck collision
    T w;       // relative launch speed of the first bounce
  };

  const TrajectoryRequest& r_;
  const ImpactMap<T>& map_;
  const Model<T>& m_;
  const Wall<T>& wall_;
  long bits_ = 53;
  T t0_, t_end_, inv_n_;

  int segment(const T& theta) const { return wall_.segment_of(theta); }
  T phase(const T& t) const {
    T p = t - Tr::floor(t);
    return p;
  }
  T height(const T& theta) const { return wall_.height_at(segment(theta), theta); }
  T wall_at(const T& t) const { return height(phase(t)); }
  T parabola(const T& y0, const T& v0, const T& s) const {
    T y = y0 + v0 * s - m_.a * s * s / 2;
    return y;
  }
  // Relative speed after a collision of relative speed `speed` (ImpactMap::collide).
  T out_speed(const T& speed) const {
    using std::exp;
    T out = speed;
    if (m_.law == Law::constant) out *= m_.eps;
    if (m_.law == Law::veldep) out *= exp(-Tr::pow_3_5(T(speed / m_.c)));
    return out;
  }

  void add(const T& t, T y, const char* event) {
    Row row;
    T w = wall_at(t);
    row.t = Tr::to_string(t);
    row.y = Tr::to_string(y);
    row.wall = Tr::to_string(w);
    row.event = event;
    row.step = steps;
    row.td = Tr::to_double(t);
    row.yd = Tr::to_double(y);
    row.wd = Tr::to_double(w);
    rows.push_back(std::move(row));
  }

  // The sample times strictly inside (a, b), clipped to the window: the grid t0 + k/N and
  // the wall's knots (so the wall's corners are rows).
  std::vector<T> times_inside(const T& a, const T& b) const {
    std::vector<T> out;
    const T hi = b < t_end_ ? b : t_end_;
    if (!(a < hi)) return out;
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
        if (!(t < hi)) { beyond = true; break; }
        if (a < t) knots.push_back(std::move(t));
      }
      if (beyond) break;
    }
    std::merge(grid.begin(), grid.end(), knots.begin(), knots.end(), std::back_inserter(out),
               [](const T& x, const T& y) { return x < y; });
    // no duplicates (a knot on the grid)
    std::vector<T> uniq;
    for (T& t : out)
      if (uniq.empty() || uniq.back() < t) uniq.push_back(std::move(t));
    return uniq;
  }

  void flight(const T& tn, const T& y0, const T& v0, const T& tb, const char* event) {
    for (const T& t : times_inside(tn, tb)) add(t, parabola(y0, v0, T(t - tn)), event);
  }
  void on_wall(const T& ta, const T& tb, const char* event) {
    for (const T& t : times_inside(ta, tb)) add(t, wall_at(t), event);
  }

  // The chatter from time `start` with first relative launch speed w: bounces drawn until
  // they are below what the samples resolve; returns the time of the collapse (constant
  // eps: exactly start + 2w / (a(1 - eps)); otherwise the bounces' summed durations).
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
          add(ti, std::move(y), "chatter");
        }
        if (tb < t_end_) add(tb, wall_at(tb), "chatter");
      }
      t = tb;
      w = out_speed(w);
    }
    if (m_.law != Law::constant) collapse = t;
    if (collapse < t) collapse = t;
    on_wall(t, collapse, "chatter");  // the unresolved tail: the particle is on the wall to the pixel
    if (collapse < t_end_) add(collapse, wall_at(collapse), "stuck");
    return collapse;
  }

  // The walk after the stuck collision (ImpactMap::ride): its duration to the step's end,
  // and the chatter sequences it contains (offsets from the stuck collision).
  T after_stuck(const StepResult<T>& st, std::vector<Chatter>& chatters) const {
    int j = st.stick_segment;
    T from = st.stuck_theta;
    T d = Tr::from_int(0, bits_);
    chatters.push_back({d, T(st.stuck_v - wall_.velocity[j])});
    for (int guard = 0; guard < 4 * wall_.segments() + 4; ++guard) {
      d += wall_.end[j] - from;
      const int k = wall_.next(j);
      if (wall_.turn[j] == Turn::down) return d;
      if (wall_.turn[j] == Turn::up && m_.downward == DownwardSticking::impact) {
        const T out = out_speed(T(wall_.velocity[k] - wall_.velocity[j]));
        T room = m_.collapse * (wall_.end[k] - wall_.start[k]);
        if (!(out <= room)) return d;  // the corner collision launches the particle
        chatters.push_back({d, out});
      }
      j = k;
      from = wall_.start[k];
    }
    return d;
  }
};

void finish(const TrajectoryRequest& r, const std::vector<Row>& rows, long impacts, long sticking, long steps,
            const std::string& note, const RunFlags& f, const Provenance& prov) {
  std::string csv = "t,particle,wall,event,step\n";
  Series wall, particle, hits, stuck, chat;
  wall.label = "wall f(t)";
  wall.color = Rgb{120, 120, 120};
  wall.lines = true;
  wall.markers = false;
  particle.label = "particle";
  particle.color = Rgb{20, 20, 20};
  particle.lines = true;
  particle.markers = false;
  hits.label = "impacts (and the start)";
  hits.color = Rgb{30, 70, 210};
  hits.marker_size = 4;
  stuck.label = "sticking: riding the wall";
  stuck.color = Rgb{215, 25, 28};
  stuck.marker_size = 2;
  chat.label = "chatter (collapse)";
  chat.color = Rgb{250, 110, 100};
  chat.marker_size = 1;
  double ymax = 1, ymin = -1;  // the wall's range at least (any --wall profile)
  for (const Row& row : rows) {
    ymin = std::min({ymin, row.wd, row.yd});
    ymax = std::max(ymax, row.wd);
    csv += row.t + ',' + row.y + ',' + row.wall + ',' + row.event + ',' + std::to_string(row.step) + '\n';
    wall.x.push_back(row.td);
    wall.y.push_back(row.wd);
    particle.x.push_back(row.td);
    particle.y.push_back(row.yd);
    ymax = std::max(ymax, row.yd);
    if (row.event == "impact" || row.event == "start") {
      hits.x.push_back(row.td);
      hits.y.push_back(row.yd);
    } else if (row.event == "stuck" || row.event == "release" || row.event == "ride") {
      stuck.x.push_back(row.td);
      stuck.y.push_back(row.wd);
    } else if (row.event == "chatter") {
      chat.x.push_back(row.td);
      chat.y.push_back(row.yd);
    }
  }
  if (!note.empty()) csv += "# stopped: " + note + "\n";
  Figure fig;
  fig.series.push_back(std::move(wall));
  fig.series.push_back(std::move(particle));
  if (!stuck.x.empty()) fig.series.push_back(std::move(stuck));
  if (!chat.x.empty()) fig.series.push_back(std::move(chat));
  fig.series.push_back(std::move(hits));
  fig.title = "Particle and wall heights against time, " + model_title(r.model.law) + " model";
  std::string par = "a = " + r.model.a.text();
  if (r.model.law == Law::constant) par += ", ε = " + r.model.eps.text();
  if (r.model.law == Law::veldep) par += ", c = " + r.model.c.text();
  fig.subtitle = par + "; from θ0 = " + r.start.theta.text() + ", v0 = " + r.start.v.text() + "; " +
                 std::to_string(impacts) + (impacts == 1 ? " impact" : " impacts") +
                 (sticking ? ", " + std::to_string(sticking) + " sticking" : "") + ", " + r.precision.text();
  fig.xlabel = "t (wall periods; θ = t mod 1)";
  fig.ylabel = "height (units: A = 1)";
  const double t0 = rows.empty() ? 0 : rows.front().td;
  fig.x_min = t0;
  fig.x_max = t0 + static_cast<double>(r.periods);
  fig.y_min = ymin - 0.06 * (ymax - ymin);
  fig.y_max = ymax + 0.05 * (ymax - ymin);
  fig.width = 1000;
  fig.height = 640;
  fig.legend_below = true;
  fig.metadata = png_metadata(prov, fig.title);
  nlohmann::ordered_json s;
  s["command"] = "trajectory";
  s["periods"] = r.periods;
  s["samples_per_period"] = r.samples;
  s["rows"] = rows.size();
  s["steps"] = steps;
  s["impacts"] = impacts;
  s["sticking_steps"] = sticking;
  s["max_height"] = ymax;
  if (!note.empty()) s["stopped"] = note;
  s["precision"] = r.precision.text();
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

const std::set<std::string>& trajectory_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "periods", "samples", "precision"});
    const std::set<std::string> run = single_run_keys();
    k.insert(run.begin(), run.end());
    return k;
  }();
  return keys;
}

int run_trajectory(const Options& o, const RunFlags& f) {
  const TrajectoryRequest req = trajectory_request(o);
  const Provenance prov = provenance_for("trajectory", job_options(o), req.precision, f.invocation);
  return with_point_scalar(req.precision, [&](auto tag) -> int {
    using T = typename decltype(tag)::type;
    const ImpactMap<T> map(make_model<T>(req.model, req.precision.bits));
    Tracer<T> tr(req, map);
    tr.run();
    finish(req, tr.rows, tr.impacts, tr.sticking_steps, tr.steps, tr.note, f, prov);
    return 0;
  });
}

}  // namespace

Command add_trajectory(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "trajectory", "Particle and wall heights against time from a state (theta, v), impacts and sticking marked");
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("theta", "Phase of the start impact in [0, 1) (default 0.3; with --eps 0.5 --a 24 the eq. 5 fixed point)");
  opts->add("v", "Particle velocity after the start impact, >= the wall velocity at theta (default 12)");
  opts->add("periods", "Wall periods drawn, integer in [1, 100] (default 3)");
  opts->add("samples", "Samples per wall period, integer in [8, 10000] (default 400); impacts and corners are added exactly");
  opts->add("precision", kPointPrecisionHelp);
  auto flags = add_single_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "trajectory", trajectory_keys()), opts->collected());
    return run_trajectory(o, run_flags_from(o, *flags, argv_text));
  };
  return {sub, run};
}

}  // namespace bouncer::cli
