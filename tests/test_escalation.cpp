// Precision escalation and certified orbit enclosures (verify/escalation.hpp,
// verify/enclosure.hpp), checked against independent truth:
//   * the schedule and the driver's bookkeeping on synthetic computations whose answers
//     are known by construction;
//   * every enclosure (naive and Lohner, point and interval parameter) contains the orbit
//     computed independently in MPFR at 2048 bits (whose own error is far below the
//     enclosure widths);
//   * the interval Jacobian of one step (Dual<Mpfi>) contains central finite differences
//     computed in MPFR at 1024 bits;
//   * the mean-value form does not suffer the wrapping effect on an orbit whose true
//     Jacobian products stay bounded (its horizon at 128 bits is several times naive's).
#include <gtest/gtest.h>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "bouncer/verify/escalation.hpp"
#include "bouncer/verify/interval_dual.hpp"

namespace bouncer {
namespace {

ModelSpec constant_model(const char* a, const char* eps) {
  ModelSpec m;
  m.law = Law::constant;
  m.a = *Decimal::parse(a);
  m.eps = *Decimal::parse(eps);
  m.wall = parse_wall("wall", "triangle");
  return m;
}

InitialCondition release() { return {*Decimal::parse("0.5"), Decimal::from_int(4)}; }

TEST(Schedule, DoublesUpToMaxBits) {
  EscalationSchedule s{64, 4096};
  EXPECT_EQ(s.bits(), (std::vector<long>{64, 128, 256, 512, 1024, 2048, 4096}));
  EscalationSchedule t{64, 1000};
  EXPECT_EQ(t.bits(), (std::vector<long>{64, 128, 256, 512, 1000}));
  EscalationSchedule u{256, 256};
  EXPECT_EQ(u.bits(), (std::vector<long>{256}));
  EXPECT_NE(s.text().find("4096"), std::string::npos);
}

// A computation that needs `need` bits: it certifies bits/2 steps, then is undecided.
int fake(long bits, Progress& p, long need) {
  p.steps = bits / 2;
  if (bits < need) throw Undecided(Reason::impact_at_corner);
  return static_cast<int>(bits);
}

TEST(Escalate, ReportsBitsNeededAndAttempts) {
  auto e = escalate<int>(EscalationSchedule{64, 4096}, [](long b, Progress& p) { return fake(b, p, 300); });
  ASSERT_TRUE(e.result);
  EXPECT_EQ(*e.result, 512);
  EXPECT_EQ(e.bits, 512);
  ASSERT_EQ(e.attempts.size(), 4u);
  EXPECT_FALSE(e.attempts[0].decided);
  EXPECT_EQ(e.attempts[0].steps, 32);
  EXPECT_TRUE(e.attempts[3].decided);
  EXPECT_TRUE(e.gave_up.empty());
}

TEST(Escalate, GivesUpWithWhereAndWhy) {
  auto e = escalate<int>(EscalationSchedule{64, 256}, [](long b, Progress& p) { return fake(b, p, 10000); });
  EXPECT_FALSE(e.result);
  EXPECT_EQ(e.attempts.size(), 3u);
  EXPECT_EQ(e.best_bits, 256);
  EXPECT_EQ(e.best_steps, 128);
  EXPECT_NE(e.gave_up.find("step 129"), std::string::npos) << e.gave_up;
  EXPECT_NE(e.gave_up.find(describe(Reason::impact_at_corner)), std::string::npos) << e.gave_up;
}

TEST(Escalate, StopsWhenStalled) {
  EscalationSchedule s{64, 4096};
  s.stop_when_stalled = true;
  int calls = 0;
  auto e = escalate<int>(s, [&](long, Progress& p) -> int {
    ++calls;
    p.steps = 10;
    throw Undecided(Reason::phase_at_corner);
  });
  EXPECT_FALSE(e.result);
  EXPECT_EQ(calls, 2);
}

// The exact orbit, computed independently at 2048 bits, lies in every enclosure.
void expect_encloses_reference(const ModelSpec& spec, EnclosureMethod method, long bits, int steps) {
  OrbitEnclosure orbit(interval_model(spec, bits), make_state<Mpfi>(release(), bits), method);
  const ImpactMap<Mpfr> ref(make_model<Mpfr>(spec, 2048));
  State<Mpfr> x = make_state<Mpfr>(release(), 2048);
  int done = 0;
  for (int n = 1; n <= steps; ++n) {
    EnclosedStep e;
    try {
      e = orbit.step();
    } catch (const Undecided&) {
      break;
    }
    const StepResult<Mpfr> r = ref.step(x);
    x = r.next;
    ASSERT_EQ(e.event.kind, r.kind) << "step " << n;
    ASSERT_TRUE(e.next.theta.contains(x.theta)) << name(method) << " step " << n << " theta";
    ASSERT_TRUE(e.next.v.contains(x.v)) << name(method) << " step " << n << " v";
    ++done;
  }
  EXPECT_GT(done, 20) << name(method);
}

TEST(Enclosure, NaiveContainsTheOrbit) {
  expect_encloses_reference(constant_model("28.82", "0.96"), EnclosureMethod::naive, 128, 400);
  expect_encloses_reference(constant_model("24", "0.5"), EnclosureMethod::naive, 128, 400);
}

TEST(Enclosure, LohnerContainsTheOrbit) {
  expect_encloses_reference(constant_model("28.82", "0.96"), EnclosureMethod::lohner, 128, 1500);
  expect_encloses_reference(constant_model("31", "0.96"), EnclosureMethod::lohner, 128, 1500);
  expect_encloses_reference(constant_model("24", "0.5"), EnclosureMethod::lohner, 128, 400);
}

TEST(Enclosure, IntervalParameterContainsEveryPointOrbit) {
  const ModelSpec spec = constant_model("28.82", "0.96");
  const mpq_class lo = Decimal::parse("28.8199999999")->value(), hi = Decimal::parse("28.8200000001")->value();
  OrbitEnclosure orbit(interval_model(spec, 128, std::make_pair(lo, hi)), make_state<Mpfi>(release(), 128),
                       EnclosureMethod::lohner);
  std::vector<ImpactMap<Mpfr>> maps;
  std::vector<State<Mpfr>> xs;
  for (const char* a : {"28.8199999999", "28.82", "28.8200000001", "28.82000000007"}) {
    maps.emplace_back(make_model<Mpfr>(constant_model(a, "0.96"), 1024));
    xs.push_back(make_state<Mpfr>(release(), 1024));
  }
  for (int n = 1; n <= 300; ++n) {
    const EnclosedStep e = orbit.step();
    for (size_t i = 0; i < maps.size(); ++i) {
      xs[i] = maps[i].step(xs[i]).next;
      ASSERT_TRUE(e.next.theta.contains(xs[i].theta) && e.next.v.contains(xs[i].v)) << "a #" << i << " step " << n;
    }
  }
}

TEST(Enclosure, IntervalJacobianContainsFiniteDifferences) {
  const ModelSpec spec = constant_model("28.82", "0.96");
  const long bits = 1024;
  // A state a few steps into the orbit, as exact MPFR numbers.
  const ImpactMap<Mpfr> map(make_model<Mpfr>(spec, bits));
  State<Mpfr> x = make_state<Mpfr>(release(), bits);
  for (int i = 0; i < 5; ++i) x = map.step(x).next;
  // Interval Jacobian over a small box around x.
  Model<Mpfi> mi = interval_model(spec, bits);
  Model<IDual> md{mi.law, mi.downward, mi.bits, IDual(mi.a), IDual(mi.eps), IDual(mi.c), IDual(mi.collapse),
                  mi.veldep_collapse, Wall<IDual>{}};
  for (size_t j = 0; j < mi.wall.start.size(); ++j) {
    md.wall.start.push_back(IDual(mi.wall.start[j]));
    md.wall.end.push_back(IDual(mi.wall.end[j]));
    md.wall.height.push_back(IDual(mi.wall.height[j]));
    md.wall.velocity.push_back(IDual(mi.wall.velocity[j]));
  }
  md.wall.turn = mi.wall.turn;
  md.wall.direction = mi.wall.direction;
  md.wall.top = IDual(mi.wall.top);
  const ImpactMap<IDual> dmap(md);
  Mpfr r(bits);
  mpfr_set_d(r.get(), 1e-30, MPFR_RNDN);
  const Mpfi pm(-r, r);
  const State<IDual> box{IDual::variable(Mpfi(x.theta, x.theta) + pm, 0), IDual::variable(Mpfi(x.v, x.v) + pm, 1)};
  const StepResult<IDual> jr = dmap.step(box);
  // Central differences with h = 1e-60: error O(h^2) ~ 1e-120, far inside the enclosure
  // (whose width is O(box) ~ 1e-30).
  Mpfr h(bits);
  mpfr_set_d(h.get(), 1e-60, MPFR_RNDN);
  for (int k = 0; k < 2; ++k) {
    State<Mpfr> xp = x, xm = x;
    (k == 0 ? xp.theta : xp.v) += h;
    (k == 0 ? xm.theta : xm.v) -= h;
    const State<Mpfr> yp = map.step(xp).next, ym = map.step(xm).next;
    const Mpfr dth = (yp.theta - ym.theta) / (2 * h), dv = (yp.v - ym.v) / (2 * h);
    EXPECT_TRUE(jr.next.theta.d[k].contains(dth)) << "d theta / d x" << k;
    EXPECT_TRUE(jr.next.v.d[k].contains(dv)) << "d v / d x" << k;
    EXPECT_LT(jr.next.theta.d[k].width().to_double(), 1e-20);
  }
}

TEST(Enclosure, LohnerBeatsTheWrappingEffect) {
  // eps = 0.96, a = 28.82: the orbit's Jacobian products stay bounded (it falls onto a
  // periodic attractor), so the exact enclosure need not grow; naive boxes blow up anyway.
  const ModelSpec spec = constant_model("28.82", "0.96");
  const Horizon naive = certified_horizon(spec, release(), 128, EnclosureMethod::naive, 5000);
  const Horizon lohner = certified_horizon(spec, release(), 128, EnclosureMethod::lohner, 5000);
  EXPECT_FALSE(naive.reached_max);
  EXPECT_LT(naive.steps, 1000);
  EXPECT_TRUE(lohner.reached_max) << lohner.reason;
  EXPECT_GT(lohner.steps, 4 * naive.steps);
}

TEST(Enclosure, ParsesMethodNames) {
  EXPECT_EQ(parse_enclosure_method("method", "naive"), EnclosureMethod::naive);
  EXPECT_EQ(parse_enclosure_method("method", "lohner"), EnclosureMethod::lohner);
  EXPECT_THROW(parse_enclosure_method("method", "qr"), InputError);
}

}  // namespace
}  // namespace bouncer
