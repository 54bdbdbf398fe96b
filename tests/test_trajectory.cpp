// The real-time trajectory (analysis/trajectory.hpp: trace_trajectory) and the model calls it
// draws from (ImpactMap::rebound, ImpactMap::after_sticking), against truth derived here:
//   * a flight is the parabola y = f(theta_n) + v_n s - (a/2) s^2 of the step's own start
//     state, and it lands on the wall (the triangle 4 theta - 1 / 3 - 4 theta, written here)
//     at the map's impact time t_n + tau;
//   * at every impact row the velocities read off the flights before and after it (from the
//     trace's heights alone) obey eq. 2, v+ - fdot = -eps (v- - fdot) (eps = 1: elastic);
//   * a chatter: its first bounce lasts 2 w0 / a with w0 = eps x the relative impact speed
//     read off the flight, each next one eps times the last, and the collapse comes after the
//     geometric sum 2 w0 / (a (1 - eps)); the release is at the peak (t = 3.5, height 1) for
//     the sticking cycle from the release state (1/2, 4) (eps 1/2, a 24);
//   * the eq. 5 fixed point (eps 1/2, a 24, (1/4, 12): v* = 4(1+eps)/(1-eps) = 12 = a p / 2
//     with p = 1) hits the wall at t = 1.25, 2.25, 3.25, its apex is 3 and its heights repeat
//     with period 1;
//   * the walk after a stuck collision on the falling wall (eps 0.3, a 24 from (0.6, -3):
//     the gap s - 12 s^2 closes at s = 1/12 with relative speed 1) rides to the valley, where
//     --downward-sticking impact adds the corner collision of speed 8 (rebound 2.4 <= 4.2:
//     sticks again), and releases at the peak 1/2 of the next period.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bouncer/analysis/trajectory.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using Tr = ScalarTraits<Mpfr>;
constexpr long kBits = 200;

TrajectoryRequest request(Law law, const std::string& a, const std::string& eps, const std::string& theta,
                          const std::string& v, long periods, long samples, const std::string& precision = "mpfr:200") {
  TrajectoryRequest r;
  r.model = test_support::spec(law, a, eps);
  r.start.theta = parse_decimal("theta", theta);
  r.start.v = parse_decimal("v", v);
  validate(r.model, r.start, "theta", "v");
  r.periods = periods;
  r.samples = samples;
  r.precision = parse_precision("precision", precision);
  return r;
}

Mpfr num(const std::string& s) { return Tr::from_decimal(s, kBits); }
double dist(const Mpfr& x, const Mpfr& y) {
  const Mpfr d = x - y;
  return std::fabs(d.to_double());
}
Mpfr phase(const Mpfr& t) { return t - Tr::floor(t); }
// The triangle wall and its velocity at absolute time t, independent of the library's Wall.
Mpfr triangle(const Mpfr& t) {
  const Mpfr th = phase(t);
  return th < num("0.5") ? Mpfr(4 * th - 1) : Mpfr(3 - 4 * th);
}
int triangle_velocity(const Mpfr& t) { return phase(t) < num("0.5") ? 4 : -4; }

using Point = TracePoint<Mpfr>;

// The velocity after the start row `from` (the step's launch), read off the first flight
// point of the same step: y = y0 + v s - (a/2) s^2.
Mpfr launch_velocity(const std::vector<Point>& pts, size_t from, const Mpfr& a) {
  for (size_t i = from + 1; i < pts.size(); ++i)
    if (pts[i].event == TraceEvent::flight) {
      const Mpfr s = pts[i].t - pts[from].t;
      return Mpfr((pts[i].particle - pts[from].particle) / s + a * s / 2);
    }
  ADD_FAILURE() << "no flight after point " << from;
  return num("0");
}

TEST(Trajectory, FlightIsTheParabolaLandingAtTheMapsImpactTime) {
  for (const auto& [law, eps, theta, v] : {std::tuple{Law::elastic, "1", "0.2", "7"},
                                          std::tuple{Law::constant, "0.8", "0.1", "9"}}) {
    SCOPED_TRACE(std::string("eps ") + eps);
    const TrajectoryRequest r = request(law, "19", eps, theta, v, 6, 100);
    const ImpactMap<Mpfr> map(make_model<Mpfr>(r.model, kBits));
    const Trajectory<Mpfr> tr = trace_trajectory<Mpfr>(r, map);
    ASSERT_TRUE(tr.stopped.empty()) << tr.stopped;
    const Mpfr a = num("19"), end = num(theta) + 6;
    State<Mpfr> s{num(theta), num(v)};
    Mpfr tn = num(theta);
    long checked = 0;
    for (long n = 1; tn < end; ++n) {
      const StepResult<Mpfr> st = map.step(s);
      ASSERT_EQ(st.kind, EventKind::impact);
      const Mpfr t_impact = tn + st.tau, y0 = triangle(tn);
      long flights = 0, impacts = 0;
      for (const Point& q : tr.points) {
        if (q.step != n) continue;
        EXPECT_LT(dist(q.wall, triangle(q.t)), 1e-50);
        if (q.event == TraceEvent::flight) {
          const Mpfr sf = q.t - tn;
          EXPECT_TRUE(tn < q.t && q.t < t_impact);
          EXPECT_LT(dist(q.particle, Mpfr(y0 + s.v * sf - a * sf * sf / 2)), 1e-45) << "step " << n;
          EXPECT_FALSE(q.particle < q.wall);
          ++flights;
        } else if (q.event == TraceEvent::impact) {
          EXPECT_LT(dist(q.t, t_impact), 1e-50);
          EXPECT_LT(dist(q.particle, triangle(t_impact)), 1e-45);  // on the wall
          ++impacts;
        }
      }
      if (t_impact <= end) {
        EXPECT_EQ(impacts, 1) << "step " << n;
        ++checked;
      }
      EXPECT_GT(flights, 0) << "step " << n;
      s = st.next;
      tn = t_impact;
    }
    EXPECT_GE(checked, 3);
    EXPECT_EQ(tr.impacts, checked);
  }
}

TEST(Trajectory, ImpactRowsObeyTheCollisionLaw) {
  for (const auto& [law, eps] : {std::pair{Law::elastic, "1"}, std::pair{Law::constant, "0.8"}}) {
    SCOPED_TRACE(std::string("eps ") + eps);
    const Trajectory<Mpfr> tr = trace_trajectory<Mpfr>(request(law, "19", eps, "0.1", "9", 8, 64));
    const std::vector<Point>& pts = tr.points;
    const Mpfr a = num("19"), e = num(eps);
    size_t launch = 0;  // the start row, then each impact row
    long checked = 0;
    for (size_t i = 1; i < pts.size(); ++i) {
      ASSERT_NE(pts[i].event, TraceEvent::chatter);
      if (pts[i].event != TraceEvent::impact) continue;
      const Mpfr v_launch = launch_velocity(pts, launch, a);
      const Mpfr v_minus = v_launch - a * (pts[i].t - pts[launch].t);
      launch = i;
      if (i + 1 == pts.size() || pts.back().step == pts[i].step) break;  // no flight after it
      const Mpfr v_plus = launch_velocity(pts, i, a);
      const int fdot = triangle_velocity(pts[i].t);
      EXPECT_LT(dist(Mpfr(v_plus - fdot), Mpfr(-e * (v_minus - fdot))), 1e-30) << "impact at t " << pts[i].t.to_double();
      EXPECT_LT(v_minus.to_double(), fdot);  // an impact: approaching the wall
      ++checked;
    }
    EXPECT_GE(checked, 4);
  }
}

TEST(Trajectory, ChatterIsGeometricAndCollapsesAtTheClosedForm) {
  const Trajectory<Mpfr> tr = trace_trajectory<Mpfr>(request(Law::constant, "24", "0.5", "0.5", "4", 5, 400));
  EXPECT_EQ(tr.sticking_steps, 1);
  const std::vector<Point>& pts = tr.points;
  const Mpfr a = num("24"), eps = num("0.5");
  const auto first_chatter = std::find_if(pts.begin(), pts.end(), [](const Point& q) { return q.event == TraceEvent::chatter; });
  ASSERT_NE(first_chatter, pts.end());
  // The stuck collision: the impact row before the chatter; the flight before it.
  size_t stuck = static_cast<size_t>(first_chatter - pts.begin()) - 1, launch = stuck - 1;
  ASSERT_EQ(pts[stuck].event, TraceEvent::impact);
  while (pts[launch].event == TraceEvent::flight) --launch;
  const Mpfr ts = pts[stuck].t;
  const Mpfr v_minus = launch_velocity(pts, launch, a) - a * (ts - pts[launch].t);
  const Mpfr w0 = eps * (triangle_velocity(ts) - v_minus);  // eq. 2 in the wall's frame
  ASSERT_TRUE(num("0") < w0);
  // Chatter rows are on or above the wall; the bounces longer than the grid's step (1/400)
  // are drawn, ending on the wall at the partial sums of 2 w0 eps^k / a.
  size_t i = stuck + 1;
  for (; pts[i].event == TraceEvent::chatter; ++i) EXPECT_FALSE(pts[i].particle < pts[i].wall);
  Mpfr touchdown = ts, bounce = 2 * w0 / a;
  long drawn = 0;
  for (; bounce.to_double() > 1.0 / 400; bounce *= eps, ++drawn) {
    touchdown += bounce;
    EXPECT_TRUE(std::any_of(pts.begin() + static_cast<long>(stuck), pts.begin() + static_cast<long>(i), [&](const Point& q) {
      return dist(q.t, touchdown) < 1e-45 && dist(q.particle, q.wall) < 1e-55;
    })) << "no touchdown at the end of bounce " << drawn;
  }
  EXPECT_GE(drawn, 3);
  // The collapse: the first stuck row, after the whole geometric sum.
  ASSERT_EQ(pts[i].event, TraceEvent::stuck);
  EXPECT_LT(dist(Mpfr(pts[i].t - ts), Mpfr(2 * w0 / (a * (1 - eps)))), 1e-45);
  // Riding the rising wall to the release at the peak.
  const auto release = std::find_if(pts.begin(), pts.end(), [](const Point& q) { return q.event == TraceEvent::release; });
  ASSERT_NE(release, pts.end());
  EXPECT_LT(dist(release->t, num("3.5")), 1e-50);
  EXPECT_LT(dist(release->particle, num("1")), 1e-50);
  for (auto q = pts.begin() + static_cast<long>(i); q != release; ++q) {
    EXPECT_EQ(q->event, TraceEvent::stuck);
    EXPECT_LT(dist(q->particle, triangle(q->t)), 1e-50);
  }
}

template <class T>
void fixed_point_returns(const char* precision, double tol) {
  SCOPED_TRACE(precision);
  using TrT = ScalarTraits<T>;
  const Trajectory<T> tr = trace_trajectory<T>(request(Law::constant, "24", "0.5", "0.25", "12", 3, 400, precision));
  EXPECT_TRUE(tr.stopped.empty());
  EXPECT_EQ(tr.impacts, 3);
  EXPECT_EQ(tr.sticking_steps, 0);
  std::vector<double> impacts, t, y;
  for (const TracePoint<T>& q : tr.points) {
    t.push_back(TrT::to_double(q.t));
    y.push_back(TrT::to_double(q.particle));
    if (q.event == TraceEvent::impact) {
      impacts.push_back(t.back());
      EXPECT_LT(std::fabs(y.back()), tol);  // f(1/4) = 0
    }
  }
  ASSERT_EQ(impacts.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(impacts[k], 1.25 + k, tol);
  // The apex v*^2 / (2a) = 3 above f(1/4) = 0, at t = 3/4 + k (on the grid).
  EXPECT_NEAR(*std::max_element(y.begin(), y.end()), 3, tol);
  long repeats = 0;
  for (size_t i = 0; i < t.size(); ++i)
    for (size_t j = i + 1; j < t.size(); ++j)
      if (std::fabs(t[j] - (t[i] + 1)) < tol) {
        EXPECT_NEAR(y[j], y[i], 1e3 * tol) << "t " << t[i];
        ++repeats;
      }
  EXPECT_GE(repeats, 2 * 400);  // two of the three periods have a successor
}

TEST(Trajectory, Eq5FixedPointReturnsEveryPeriod) {
  fixed_point_returns<double>("double", 1e-12);
  fixed_point_returns<Mpfr>("mpfr:200", 1e-14);
}

TEST(Trajectory, VeldepCollapseRestickingAtTheValleyStaysAboveTheWall) {
  // veldep (c = 1) with --veldep-collapse on and --downward-sticking impact from (0.6, -3):
  // the flight meets the falling wall at 0.6 + 1/12 (the gap s - 12 s^2, whatever the law),
  // and the corner collision at the valley sticks again. (A copy of the walk that tested
  // the corner with the constant law's threshold drew this collision half a period late,
  // through the wall.)
  TrajectoryRequest r = request(Law::veldep, "24", "1", "0.6", "-3", 2, 40, "mpfr:120");
  r.model.c = parse_decimal("c", "1");
  r.model.veldep_collapse = true;
  r.model.downward = DownwardSticking::impact;
  const Trajectory<Mpfr> tr = trace_trajectory<Mpfr>(r);
  EXPECT_GE(tr.sticking_steps, 1);
  const auto impact = std::find_if(tr.points.begin(), tr.points.end(), [](const Point& q) { return q.event == TraceEvent::impact; });
  ASSERT_NE(impact, tr.points.end());
  EXPECT_LT(dist(impact->t, Mpfr(num("0.6") + num("1") / 12)), 1e-30);
  for (const Point& q : tr.points) {
    EXPECT_GT(Mpfr(q.particle - q.wall).to_double(), -1e-30) << "below the wall at t " << q.t.to_double();
    EXPECT_LT(dist(q.wall, triangle(q.t)), 1e-30);
  }
}

TEST(Trajectory, ReboundIsTheCollisionLaw) {
  const ImpactMap<Mpfr> constant(make_model<Mpfr>(test_support::spec(Law::constant, "24", "0.3"), kBits));
  const ImpactMap<Mpfr> elastic(make_model<Mpfr>(test_support::spec(Law::elastic, "24"), kBits));
  const ImpactMap<Mpfr> veldep(make_model<Mpfr>(test_support::spec(Law::veldep, "24", "1", "10"), kBits));
  EXPECT_LT(dist(constant.rebound(num("8")), num("2.4")), 1e-55);
  EXPECT_LT(dist(elastic.rebound(num("8")), num("8")), 1e-55);
  EXPECT_NEAR(veldep.rebound(num("8")).to_double(), 8 * std::exp(-std::pow(0.8, 0.6)), 1e-14);
}

TEST(Trajectory, AfterStickingIsTheMapsWalk) {
  for (const DownwardSticking downward : {DownwardSticking::paper, DownwardSticking::impact}) {
    ModelSpec spec = test_support::spec(Law::constant, "24", "0.3");
    spec.downward = downward;
    const ImpactMap<Mpfr> map(make_model<Mpfr>(spec, kBits));
    const StepResult<Mpfr> st = map.step(State<Mpfr>{num("0.6"), num("-3")});
    ASSERT_EQ(st.kind, EventKind::sticking);
    const Mpfr stuck = num("0.6") + num("1") / 12;  // where the gap s - 12 s^2 closes
    EXPECT_LT(dist(st.stuck_theta, stuck), 1e-55);
    std::vector<ImpactMap<Mpfr>::Collapse> collapses;
    const Mpfr after = map.after_sticking(st, collapses);
    EXPECT_LT(dist(after, Mpfr(num("1.5") - stuck)), 1e-55);      // released at the next peak
    EXPECT_LT(dist(Mpfr(st.tau - after), num("1") / 12), 1e-55);  // the flight to the stuck collision
    ASSERT_EQ(collapses.size(), downward == DownwardSticking::impact ? 2u : 1u);
    EXPECT_LT(dist(collapses[0].offset, num("0")), 1e-60);
    EXPECT_LT(dist(collapses[0].w, num("0.3")), 1e-55);  // 0.3 x relative impact speed |-5 - (-4)|
    if (collapses.size() == 2) {
      EXPECT_LT(dist(collapses[1].offset, Mpfr(1 - stuck)), 1e-55);  // at the valley
      EXPECT_LT(dist(collapses[1].w, num("2.4")), 1e-55);             // 0.3 x (4 - (-4))
    }
  }
}

}  // namespace
}  // namespace bouncer
