// Every attractor at a parameter point (run/attractors.hpp), against independent truth:
//  * the paper's eq. 5 fixed points (analysis/periodic.hpp paper::fixed_point_a, _v): where
//    they are the only attractor, a family at v* = 4(1+eps)/(1-eps) with multipliers 1 and
//    eps^2, reached by every start;
//  * basin's per-start classification (run/basin.hpp, classify over 5000 + 500 steps: an
//    independent code path) on the same starts: the same attractors, the same shares within
//    their sampling error (veldep c = 1000, a = 23.1: period 7 beside period 3; constant
//    eps = 0.5, a = 24: the eq. 5 fixed points beside a sticking cycle through (1/2, 4));
//  * the book-keeping: shares sum to 1, threads do not change the result.
#include "bouncer/run/attractors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "bouncer/analysis/periodic.hpp"
#include "bouncer/run/attractors_sweep.hpp"
#include "bouncer/run/basin.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

using test_support::expect_input_error;
using test_support::spec;

GridOptions two_threads() {
  GridOptions g;
  g.threads = 2;
  return g;
}

// The run's attractor of this kind and period, or nullptr.
const FoundAttractor* find(const AttractorsResult& r, AttractorKind k, long period) {
  for (const FoundAttractor& a : r.attractors)
    if (a.kind == k && a.period == period) return &a;
  return nullptr;
}

void expect_shares_sum_to_one(const AttractorsResult& r) {
  long starts = r.undecided;
  double sum = r.undecided_fraction;
  for (const FoundAttractor& a : r.attractors) {
    starts += a.starts;
    sum += a.fraction;
  }
  EXPECT_EQ(starts, r.inside);
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_EQ(r.inside + r.outside, static_cast<long>(r.label.size()));
}

// basin's class of each start, as (class, period), and the share of each.
struct BasinTruth {
  std::vector<std::pair<OrbitClass, long>> per_start;
  std::map<std::pair<OrbitClass, long>, long> count;
  long inside = 0;
};
BasinTruth basin_truth(const AttractorsRequest& r) {
  BasinRequest b;
  b.model = r.model;
  b.nx = r.nx;
  b.ny = r.ny;
  b.theta_lo = r.theta_lo;
  b.theta_hi = r.theta_hi;
  b.v_range = r.v_range;
  const BasinResult res = basin(b, two_threads());
  BasinTruth t;
  for (const AttractorCell& c : res.cells) {
    t.per_start.emplace_back(c.cls, c.period);
    if (c.cls == OrbitClass::outside) continue;
    ++t.count[{c.cls, c.period}];
    ++t.inside;
  }
  return t;
}

// The class basin gives the starts of an attractor of this kind.
std::pair<OrbitClass, long> basin_class(const FoundAttractor& a) {
  switch (a.kind) {
    case AttractorKind::periodic:
    case AttractorKind::family: return {a.period == 1 ? OrbitClass::fixed : OrbitClass::periodic, a.period};
    case AttractorKind::sticking: return {OrbitClass::sticking, a.period};
    case AttractorKind::chaotic: return {OrbitClass::chaotic, 0};
    case AttractorKind::quasiperiodic: return {OrbitClass::quasiperiodic, 0};
    default: return {OrbitClass::undecided, -1};
  }
}

// Each attractor's share agrees with basin's share of its class within the error of the
// difference of two binomial shares (3 standard errors), and per start the two agree on at
// least 98% of the starts.
void expect_agrees_with_basin(const AttractorsResult& r, const BasinTruth& t) {
  ASSERT_EQ(t.inside, r.inside);
  for (const FoundAttractor& a : r.attractors) {
    const auto it = t.count.find(basin_class(a));
    const long k = it == t.count.end() ? 0 : it->second;
    const double p = static_cast<double>(k) / static_cast<double>(t.inside);
    const double se = std::hypot(a.fraction_stderr, share_stderr(k, t.inside));
    EXPECT_LE(std::fabs(a.fraction - p), 3 * se + 1.0 / static_cast<double>(t.inside))
        << "attractor #" << a.id << " " << name(a.kind) << " " << a.period << ": " << a.fraction << " vs basin " << p;
  }
  long same = 0;
  for (size_t i = 0; i < r.label.size(); ++i) {
    const int l = r.label[i];
    if (l == AttractorsResult::kOutside) {
      same += t.per_start[i].first == OrbitClass::outside;
    } else if (l >= 0) {
      same += basin_class(r.attractors[static_cast<size_t>(l)]) == t.per_start[i];
    }
  }
  EXPECT_GE(static_cast<double>(same), 0.98 * static_cast<double>(r.label.size()));
}

TEST(Attractors, Eq5FixedPointsAreTheOnlyAttractor) {
  // eps = 1/2, p = 2: a = 8(1 + eps)/(p(1 - eps)) = 12, v* = 4(1 + eps)/(1 - eps) = 12, theta*
  // fills (0, 1/2) (1/(4p - 1) < eps), multipliers 1 and eps^2.
  const mpq_class eps(1, 2);
  const mpq_class a = paper::fixed_point_a(eps, 2);
  AttractorsRequest r;
  r.model = spec(Law::constant, exact_decimal(a), "0.5");
  r.nx = r.ny = 40;
  const AttractorsResult res = find_attractors(r, two_threads());
  ASSERT_EQ(res.attractors.size(), 1u);
  const FoundAttractor& f = res.attractors[0];
  EXPECT_EQ(f.kind, AttractorKind::family);
  EXPECT_EQ(f.period, 1);
  EXPECT_EQ(res.undecided, 0);
  EXPECT_EQ(f.starts, res.inside);
  const double v_star = paper::fixed_point_v(0.5);
  for (const AttractorPoint& p : f.points) EXPECT_NEAR(p.v.value, v_star, 1e-12 * v_star);
  ASSERT_EQ(f.multiplier_moduli.size(), 2u);
  EXPECT_NEAR(f.multiplier_moduli[0], 1.0, 1e-9);
  EXPECT_NEAR(f.multiplier_moduli[1], 0.25, 1e-9);
  EXPECT_GT(f.family_theta_min, 0.0);
  EXPECT_LT(f.family_theta_max, 0.5);
  EXPECT_GT(f.family_members, 10);  // the starts reach many members of the family
  ASSERT_TRUE(f.certificate);
  EXPECT_TRUE(f.certificate->certified) << f.certificate->reason;
  EXPECT_EQ(f.certificate->outcome, PeriodicOutcome::family);
  expect_shares_sum_to_one(res);
}

TEST(Attractors, VeldepPeriod7BesidePeriod3AsBasinSees) {
  AttractorsRequest r;
  r.model = spec(Law::veldep, "23.1", "1", "1000");
  r.nx = r.ny = 40;
  const AttractorsResult res = find_attractors(r, two_threads());
  const FoundAttractor* p3 = find(res, AttractorKind::periodic, 3);
  const FoundAttractor* p7 = find(res, AttractorKind::periodic, 7);
  ASSERT_TRUE(p3 && p7);
  for (const FoundAttractor* a : {p3, p7}) {
    EXPECT_TRUE(a->stable);
    EXPECT_LT(a->multiplier_moduli[0], 1.0);
    ASSERT_TRUE(a->certificate);
    EXPECT_TRUE(a->certificate->certified) << a->certificate->reason;
    EXPECT_EQ(a->certificate->outcome, PeriodicOutcome::isolated);
    EXPECT_EQ(a->certificate->stability, "stable");
    EXPECT_EQ(a->certificate->minimal_period, a->period);
    EXPECT_GT(a->starts, 0);
    EXPECT_EQ(static_cast<long>(a->points.size()), a->period);
  }
  EXPECT_GT(p3->fraction, p7->fraction);  // period 3 dominates; period 7 is the small basin
  EXPECT_EQ(res.undecided, 0);
  expect_shares_sum_to_one(res);
  expect_agrees_with_basin(res, basin_truth(res.request));
}

TEST(Attractors, StickingCycleBesideEq5FixedPoints) {
  // eps = 1/2, a = 24 = eq. 5 with p = 1 (paper sec. III, fig. basin2): the fixed points
  // v* = 12 and a sticking cycle through the release state (1/2, 4).
  AttractorsRequest r;
  r.model = spec(Law::constant, exact_decimal(paper::fixed_point_a(mpq_class(1, 2), 1)), "0.5");
  r.nx = r.ny = 40;
  const AttractorsResult res = find_attractors(r, two_threads());
  ASSERT_EQ(res.attractors.size(), 2u);
  const FoundAttractor* fam = find(res, AttractorKind::family, 1);
  ASSERT_TRUE(fam);
  EXPECT_NEAR(fam->points[0].v.value, paper::fixed_point_v(0.5), 1e-12 * 12);
  const FoundAttractor* stick = nullptr;
  for (const FoundAttractor& a : res.attractors)
    if (a.kind == AttractorKind::sticking) stick = &a;
  ASSERT_TRUE(stick);
  EXPECT_EQ(stick->points[0].theta.value, 0.5);  // the release state, exactly
  EXPECT_EQ(stick->points[0].v.value, 4.0);
  ASSERT_TRUE(stick->certificate);
  EXPECT_TRUE(stick->certificate->certified) << stick->certificate->reason;
  EXPECT_EQ(stick->certificate->outcome, PeriodicOutcome::through_release);
  EXPECT_EQ(stick->certificate->period, stick->period);
  EXPECT_GT(fam->fraction, 0.3);
  EXPECT_GT(stick->fraction, 0.1);
  expect_shares_sum_to_one(res);
  expect_agrees_with_basin(res, basin_truth(res.request));
}

TEST(Attractors, OrbitsThroughAnotherOrbitsCellsAreStillFound) {
  // eps = 0.96, a = 28.82: a stable period-48 orbit passes through cells of the stable
  // period-103 orbit's neighbourhood. Starts converging to it must still be decided (once
  // they were all left undecided), as basin's classification decides them.
  AttractorsRequest r;
  r.model = spec(Law::constant, "28.82", "0.96");
  r.nx = r.ny = 16;
  r.certify = false;
  const AttractorsResult res = find_attractors(r, two_threads());
  EXPECT_EQ(res.undecided, 0);
  EXPECT_TRUE(find(res, AttractorKind::periodic, 48));
  EXPECT_TRUE(find(res, AttractorKind::periodic, 103));
  expect_shares_sum_to_one(res);
  expect_agrees_with_basin(res, basin_truth(res.request));
}

TEST(Attractors, ChaoticSetWithItsExponent) {
  // veldep c = 1000, a = 27.2: a chaotic attractor (the exponent curve of docs/guide/dynamics.md is positive
  // there); basin classifies every start chaotic, and its exponent is positive.
  AttractorsRequest r;
  r.model = spec(Law::veldep, "27.2", "1", "1000");
  r.nx = r.ny = 8;
  r.lyapunov_steps = 20000;
  const AttractorsResult res = find_attractors(r, two_threads());
  ASSERT_EQ(res.attractors.size(), 1u);
  const FoundAttractor& a = res.attractors[0];
  EXPECT_EQ(a.kind, AttractorKind::chaotic);
  EXPECT_GT(a.lambda, 0.05);
  EXPECT_GT(a.lambda, 3 * a.lambda_stderr);
  EXPECT_EQ(a.lyapunov_steps, 20000);
  EXPECT_GE(a.followed_steps, a.lyapunov_steps);
  EXPECT_FALSE(a.certificate);
  EXPECT_GT(a.cells, 100);
  expect_shares_sum_to_one(res);
  expect_agrees_with_basin(res, basin_truth(res.request));
}

TEST(Attractors, ThreadsDoNotChangeTheResult) {
  AttractorsRequest r;
  r.model = spec(Law::constant, "24", "0.5");
  r.nx = r.ny = 24;
  r.certify = false;
  GridOptions one;
  one.threads = 1;
  const AttractorsResult a = find_attractors(r, one), b = find_attractors(r, two_threads());
  EXPECT_EQ(a.label, b.label);
  ASSERT_EQ(a.attractors.size(), b.attractors.size());
  for (size_t i = 0; i < a.attractors.size(); ++i) {
    EXPECT_EQ(a.attractors[i].starts, b.attractors[i].starts);
    EXPECT_EQ(a.attractors[i].points[0].theta.digits, b.attractors[i].points[0].theta.digits);
  }
}

TEST(Attractors, HaltonStartsFillTheWindow) {
  AttractorsRequest r;
  r.model = spec(Law::constant, "12", "0.5");
  r.nx = r.ny = 16;
  r.sampling = StartSampling::halton;
  r.certify = false;
  const AttractorsResult res = find_attractors(r, two_threads());
  ASSERT_EQ(res.theta.size(), 256u);
  const double top = res.request.v_range->second.approx();
  for (size_t i = 0; i < res.theta.size(); ++i) {
    EXPECT_GT(res.theta[i].value, 0.0);
    EXPECT_LT(res.theta[i].value, 1.0);
    EXPECT_GE(res.v[i].value, 4.0);
    EXPECT_LT(res.v[i].value, top);
  }
  EXPECT_EQ(res.theta[0].value, 0.5);  // the Halton sequence in base 2 starts 1/2, 1/4, 3/4
  EXPECT_EQ(res.theta[1].value, 0.25);
  ASSERT_EQ(res.attractors.size(), 1u);
  expect_shares_sum_to_one(res);
}

TEST(Attractors, ShareStderrIsBinomial) {
  EXPECT_DOUBLE_EQ(share_stderr(25, 100), std::sqrt(0.25 * 0.75 / 100));
  EXPECT_EQ(share_stderr(0, 100), 0.0);
  EXPECT_EQ(share_stderr(0, 0), 0.0);
}

TEST(Attractors, BadRequestsNameTheirField) {
  AttractorsRequest r;
  r.model = spec(Law::constant, "24", "0.5");
  AttractorsRequest x = r;
  x.nx = 0;
  expect_input_error([&] { find_attractors(x); }, "starts");
  x = r;
  x.cells_theta = 8;
  expect_input_error([&] { find_attractors(x); }, "cells");
  x = r;
  x.consecutive_recurrences = 0;
  expect_input_error([&] { find_attractors(x); }, "recurrences");
  x = r;
  x.precision = parse_precision("precision", "interval:64");
  expect_input_error([&] { find_attractors(x); }, "precision");
  x = r;
  x.model = spec(Law::elastic, "19");
  expect_input_error([&] { find_attractors(x); }, "v-range");
  x = r;
  x.theta_hi = *Decimal::parse("1.5");
  expect_input_error([&] { find_attractors(x); }, "theta-range");
}

}  // namespace
}  // namespace bouncer

namespace bouncer {
namespace {

TEST(AttractorsSweep, ChainsFollowTheAttractorsAcrossValues) {
  AttractorsSweepRequest s;
  s.point.model = test_support::spec(Law::veldep, "23.1", "1", "1000");
  s.point.nx = s.point.ny = 20;
  s.point.certify = false;
  s.vary = Parameter::a;
  s.lo = *Decimal::parse("23.05");
  s.hi = *Decimal::parse("23.15");
  s.values = 3;
  const AttractorsSweepResult r = sweep_attractors(s, two_threads());
  ASSERT_EQ(r.values.size(), 3u);
  EXPECT_EQ(r.values[1].text(), "23.1");
  // Periods 3 and 7 exist at every value (each value's find_attractors is checked against
  // basin above) and each is one chain: the orbit moves little over 0.1 in a.
  for (long q : {3L, 7L}) {
    int chains = 0;
    for (const AttractorChain& c : r.chains) {
      if (c.kind != AttractorKind::periodic || c.period != q) continue;
      ++chains;
      for (int i : c.index) EXPECT_GE(i, 0) << "period " << q << " is missing at a value";
    }
    EXPECT_EQ(chains, 1) << "period " << q;
  }
  // Every attractor of every value is in exactly one chain.
  for (size_t k = 0; k < r.at.size(); ++k) {
    std::vector<int> seen(r.at[k].attractors.size(), 0);
    for (const AttractorChain& c : r.chains)
      if (c.index[k] >= 0) ++seen[static_cast<size_t>(c.index[k])];
    for (int n : seen) EXPECT_EQ(n, 1);
  }
}

// continue_chains: each chain's appearance or disappearance tied to its branch's end.
// Truth independent of the code (test_continuation.cpp's header): at eps = 1/4 the period-1
// sticking cycle through the release state (1/2, 4) exists exactly for 200/9 <= a < 32 (the
// sticking threshold eps sqrt(8a) = a(1-eps)/2 (1 - sqrt(8/a)) at a = 200/9; the impact
// theta = sqrt(8/a) - 1/2 reaching the knot theta = 0 at a = 32). A sweep over a value
// below 200/9 and two above must find it absent, then present, and tie the appearance to a
// certified low border end whose enclosure holds 200/9; over 31.9, 32, 32.1 its
// disappearance to a high end holding 32. Neither depends on the number of threads.
AttractorsSweepResult sticking_sweep(const char* lo, const char* hi, int threads) {
  AttractorsSweepRequest s;
  s.point.model = test_support::spec(Law::constant, lo, "0.25");
  s.point.nx = s.point.ny = 12;
  s.point.certify = false;  // the orbits' own certificates are find_attractors' (tested above)
  s.vary = Parameter::a;
  s.lo = *Decimal::parse(lo);
  s.hi = *Decimal::parse(hi);
  s.values = 3;
  s.certify_ends = true;
  GridOptions run;
  run.threads = threads;
  return sweep_attractors(s, run);
}

const AttractorChain* sticking_chain(const AttractorsSweepResult& r, long k) {
  for (const AttractorChain& c : r.chains)
    if (c.kind == AttractorKind::sticking && c.period == k) return &c;
  return nullptr;
}

void expect_tied(const AttractorsSweepResult& r, bool appears, const mpq_class& a_star) {
  ASSERT_TRUE(r.branches.has_value());
  const AttractorChain* c = sticking_chain(r, 1);
  ASSERT_NE(c, nullptr) << "no period-1 sticking cycle";
  const std::vector<ChainTransition>& ts = r.branches->transitions[static_cast<size_t>(c->id)];
  ASSERT_EQ(ts.size(), 1u);
  const ChainTransition& t = ts[0];
  EXPECT_EQ(t.appears, appears);
  EXPECT_LE(r.values[t.before].value(), a_star);  // the closed form lies between the values
  EXPECT_GE(r.values[t.after].value(), a_star);
  ASSERT_GE(t.event, 0) << "not tied to a branch event";
  const BranchEventInfo& e = r.branches->branches[static_cast<size_t>(t.branch)].events[static_cast<size_t>(t.event)];
  EXPECT_TRUE(e.end);
  EXPECT_EQ(e.high, !appears);
  EXPECT_EQ(e.kind, "border");
  ASSERT_TRUE(e.certified) << e.reason;
  const mpq_class lo = parse_decimal("lo", e.enclosure.lo).value(), hi = parse_decimal("hi", e.enclosure.hi).value();
  EXPECT_LE(lo, a_star) << e.enclosure.lo;
  EXPECT_GE(hi, a_star) << e.enclosure.hi;
  EXPECT_LT(mpq_class(hi - lo).get_d(), 1e-25);
}

TEST(AttractorsSweep, StickingCycleAppearsAtTheCertifiedThreshold200Over9) {
  const AttractorsSweepResult r = sticking_sweep("22.1", "22.4", 2);
  const AttractorChain* c = sticking_chain(r, 1);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->index[0], -1);  // a = 22.1 < 200/9: the release orbit does not stick
  EXPECT_GE(c->index[1], 0);
  EXPECT_GE(c->index[2], 0);
  expect_tied(r, true, mpq_class(200, 9));
  // The same sweep on one thread: the same chains, branches and ties.
  const AttractorsSweepResult one = sticking_sweep("22.1", "22.4", 1);
  ASSERT_EQ(one.chains.size(), r.chains.size());
  for (size_t i = 0; i < r.chains.size(); ++i) {
    EXPECT_EQ(one.chains[i].index, r.chains[i].index);
    EXPECT_EQ(one.branches->chain_branch[i], r.branches->chain_branch[i]);
    ASSERT_EQ(one.branches->transitions[i].size(), r.branches->transitions[i].size());
    for (size_t k = 0; k < r.branches->transitions[i].size(); ++k)
      EXPECT_EQ(one.branches->transitions[i][k].event, r.branches->transitions[i][k].event);
  }
}

TEST(AttractorsSweep, StickingCycleDisappearsAtTheCertifiedKnotA32) {
  const AttractorsSweepResult r = sticking_sweep("31.9", "32.1", 2);
  expect_tied(r, false, mpq_class(32));
}

TEST(AttractorsSweep, BadRequestsNameTheirField) {
  AttractorsSweepRequest s;
  s.point.model = test_support::spec(Law::veldep, "23.1", "1", "1000");
  s.lo = *Decimal::parse("23");
  s.hi = *Decimal::parse("24");
  s.values = 1;
  test_support::expect_input_error([&] { sweep_attractors(s); }, "values");
  s.values = 3;
  s.vary = Parameter::eps;
  test_support::expect_input_error([&] { sweep_attractors(s); }, "vary");
}

}  // namespace
}  // namespace bouncer
