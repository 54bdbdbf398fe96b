// The batched double step ImpactMap<double>::step_n against the scalar step, its truth here:
// every output field of every lane must equal step()'s bit for bit (NaN and the sign of
// zero included), and a lane whose step is undecided must report step()'s reason, whatever
// the other lanes of its group do. The states cover the rare branches as well as the common
// flight: riding starts, starts at a knot, sticking (constant eps and the veldep collapse,
// both downward-sticking conventions), corner impacts, jumps over the top (also very long
// ones, which the map refuses), flat segments, and non-finite inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bouncer/model/impact_map.hpp"
#include "test_support.hpp"

using namespace bouncer;
using bouncer::test_support::spec;

namespace {

std::uint64_t bits_of(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

struct Outcome {
  bool undecided = false;
  Reason why{};
  StepResult<double> r;
};

Outcome scalar(const ImpactMap<double>& map, const State<double>& s) {
  Outcome o;
  try {
    o.r = map.step(s);
  } catch (const Undecided& e) {
    o.undecided = true;
    o.why = e.reason;
  }
  return o;
}

// Every field of StepResult<double>, compared bit for bit.
void expect_same(const Outcome& want, bool undecided, Reason why, const StepResult<double>& got, const std::string& at) {
  ASSERT_EQ(want.undecided, undecided) << at;
  if (undecided) {
    EXPECT_EQ(want.why, why) << at;
    return;
  }
  const StepResult<double>& w = want.r;
  EXPECT_EQ(bits_of(w.next.theta), bits_of(got.next.theta)) << at;
  EXPECT_EQ(bits_of(w.next.v), bits_of(got.next.v)) << at;
  EXPECT_EQ(w.next.knot, got.next.knot) << at;
  EXPECT_EQ(bits_of(w.tau), bits_of(got.tau)) << at;
  EXPECT_EQ(w.periods, got.periods) << at;
  EXPECT_EQ(w.segment, got.segment) << at;
  EXPECT_EQ(w.kind, got.kind) << at;
  EXPECT_EQ(w.corner, got.corner) << at;
  EXPECT_EQ(w.indirect, got.indirect) << at;
  EXPECT_EQ(w.stick_segment, got.stick_segment) << at;
  EXPECT_EQ(w.passed_upward_turn, got.passed_upward_turn) << at;
  EXPECT_EQ(bits_of(w.stuck_theta), bits_of(got.stuck_theta)) << at;
  EXPECT_EQ(bits_of(w.stuck_v), bits_of(got.stuck_v)) << at;
  EXPECT_EQ(w.phase_bits_lost, got.phase_bits_lost) << at;
}

// What each branch of the step was taken by, counted from the scalar results (so that the
// test shows it reached the rare cases it claims to compare).
struct Seen {
  long impact = 0, sticking = 0, ride = 0, corner = 0, jump = 0, undecided = 0, knot_start = 0;
};

// The states: random starts over the phase space, then the orbits from them (whose states
// are the map's own: knots after releases and corner impacts, sticking, riding).
std::vector<State<double>> states_for(const ImpactMap<double>& map, std::mt19937_64& rng, long starts, long steps) {
  const Wall<double>& wall = map.model().wall;
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<State<double>> out;
  for (long i = 0; i < starts; ++i) {
    const double theta = unit(rng);
    const double u = wall.velocity[wall.segment_of(theta)];
    // Slow (riding, short hops), moderate, and fast starts (jumps over the top, long flights).
    const double kind = unit(rng);
    double v = kind < 0.05 ? u : kind < 0.6 ? u + 30 * unit(rng) : kind < 0.95 ? u + 200 * unit(rng) : u + 1e6 * unit(rng);
    State<double> s{theta, v};
    if (unit(rng) < 0.05) {  // a start exactly at a knot, moving with or off the wall
      s.knot = static_cast<int>(unit(rng) * wall.segments()) % wall.segments();
      s.theta = wall.start[static_cast<size_t>(s.knot)];
      s.v = wall.velocity[static_cast<size_t>(s.knot)] + (unit(rng) < 0.3 ? 0 : 20 * unit(rng));
    }
    for (long k = 0; k < steps; ++k) {
      out.push_back(s);
      try {
        s = map.step(s).next;
      } catch (const Undecided&) {
        break;
      }
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const State<double>& s : {State<double>{nan, 5}, State<double>{0.3, nan}, State<double>{0.3, inf},
                                 State<double>{0.7, 1e300}, State<double>{0.1, 1e17}})
    out.push_back(s);
  return out;
}

Seen check_model(const ModelSpec& spec_, const std::string& label, long starts = 300, long steps = 40) {
  const ImpactMap<double> map(make_model<double>(spec_, 53));
  std::mt19937_64 rng(20261127);
  std::vector<State<double>> states = states_for(map, rng, starts, steps);
  // Shuffled, so that each group mixes orbits, cases and failures.
  std::shuffle(states.begin(), states.end(), rng);
  constexpr int K = kStepLanes;
  while (states.size() % K) states.push_back(states[states.size() % 7]);
  Seen seen;
  for (size_t g = 0; g < states.size(); g += K) {
    StepResult<double> out[K];
    Reason why[K];
    const unsigned failed = map.step_n<K>(&states[g], out, why);
    for (int k = 0; k < K; ++k) {
      const State<double>& s = states[g + static_cast<size_t>(k)];
      const Outcome want = scalar(map, s);
      seen.undecided += want.undecided;
      seen.knot_start += s.knot >= 0;
      if (!want.undecided) {
        seen.impact += want.r.kind == EventKind::impact;
        seen.sticking += want.r.kind == EventKind::sticking;
        seen.ride += want.r.kind == EventKind::ride;
        seen.corner += want.r.corner;
        seen.jump += want.r.phase_bits_lost > 0;
      }
      expect_same(want, (failed >> k) & 1u, why[k], out[k],
                  label + " state (" + std::to_string(s.theta) + ", " + std::to_string(s.v) + ", knot " +
                      std::to_string(s.knot) + ")");
      if (::testing::Test::HasFailure()) return seen;
    }
  }
  // The groups really contained flights, jumps, rides, starts at knots and failures.
  EXPECT_GT(seen.impact + seen.sticking, 10000) << label;
  EXPECT_GT(seen.jump, 100) << label;
  EXPECT_GT(seen.ride, 0) << label;
  EXPECT_GT(seen.undecided, 0) << label;
  EXPECT_GT(seen.knot_start, 10) << label;
  std::printf("%s: impact %ld, sticking %ld, ride %ld, corner %ld, jump %ld, undecided %ld, knot starts %ld\n",
              label.c_str(), seen.impact, seen.sticking, seen.ride, seen.corner, seen.jump, seen.undecided,
              seen.knot_start);
  return seen;
}

ModelSpec with_wall(ModelSpec m, const std::string& wall) {
  m.wall = parse_wall("wall", wall);
  validate(m);
  return m;
}

}  // namespace

TEST(StepN, ElasticTriangle) {
  const Seen seen = check_model(spec(Law::elastic, "19"), "elastic a 19");
  EXPECT_GT(seen.corner, 0);
}

TEST(StepN, ConstantEpsStickingBothConventions) {
  // eps 0.9 at a = 19 (bench_grid's basin); eps = 0.5 at a = 24: the fixed-point family and
  // sticking, under both conventions at the upward turn; eps = 0 sticks at every impact.
  check_model(spec(Law::constant, "19", "0.9"), "constant a 19 eps 0.9");
  ModelSpec m = spec(Law::constant, "24", "0.5");
  const Seen paper = check_model(m, "constant a 24 eps 0.5");
  m.downward = DownwardSticking::impact;
  const Seen impact = check_model(m, "constant a 24 eps 0.5 impact convention");
  const Seen zero = check_model(spec(Law::constant, "10", "0"), "constant a 10 eps 0");
  EXPECT_GT(paper.sticking, 100);
  EXPECT_GT(impact.sticking, 100);
  EXPECT_GT(paper.corner + impact.corner, 0);
  EXPECT_GT(zero.sticking, 10000);
}

TEST(StepN, VelocityDependent) {
  const Seen chaos = check_model(spec(Law::veldep, "27", "1", "1000"), "veldep a 27 c 1000");
  ModelSpec low = spec(Law::veldep, "14", "1", "1");
  check_model(low, "veldep a 14 c 1");
  low.veldep_collapse = true;
  const Seen collapse = check_model(low, "veldep a 14 c 1 collapse");
  EXPECT_GT(chaos.corner, 0);
  EXPECT_GT(collapse.sticking, 1000);
}

TEST(StepN, AsymmetricAndFlatWalls) {
  check_model(with_wall(spec(Law::constant, "28", "0.96"), "asymmetric:0.29"), "constant asymmetric:0.29");
  check_model(with_wall(spec(Law::constant, "20", "0.8"), "sawtooth"), "constant sawtooth");
  const Seen flat = check_model(with_wall(spec(Law::elastic, "15"), "knots:0:0,0.25:1,0.5:1,0.75:-0.5"),
                                "elastic knots with a flat top");
  const Seen four = check_model(with_wall(spec(Law::veldep, "22", "1", "100"), "knots:0:-1,0.1:1,0.2:0.5,0.6:-0.25"),
                                "veldep four knots");
  EXPECT_GT(flat.corner + four.corner, 0);
}
