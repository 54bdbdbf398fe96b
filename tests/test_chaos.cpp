// certify_chaos (verify/chaos.hpp): a horseshoe of the bouncer found from the model alone and
// proved with MPFI, checked here against facts that do not come from the search:
//
// 1. Velocity-dependent model, c = 1000, a = 27 (issue 26's case): a positive bound, below
//    the per-collision Lyapunov exponent's neighbourhood (about 0.11; assert < 0.2), with
//    pairwise disjoint h-sets (hsets_disjoint, re-asked here), every covering of the
//    certificate proved again by an independent call of check_covering (the certificate's
//    numbers only, the map rebuilt from the spec and the branch at each set's centre) with
//    its stated sign, the stated bound equal to entropy_lower_bound of the certificate's own
//    transition matrix, and the chain's graph: N_0 => N_0, N_0 => N_1, ..., N_m => N_0.
//    The saddle it starts from is the period-2 orbit of `bouncer periodic` (multipliers
//    -2.87 and -0.27).
// 2. a = 20: the attractor is a stable period-2 focus (complex multipliers of modulus 0.85)
//    and Newton finds no saddle of period 1..4: no proof, and the message says so.
// 3. a = 25, the "non-chaotic" case: its attractor is a stable period-3 cycle
//    (checked here by Newton: both multipliers inside the unit circle), and yet the map has a
//    horseshoe: the period-2 saddle (multipliers -3.78, -0.21) has a transverse homoclinic
//    orbit, so h_top > 0 on a non-attracting invariant set (transient chaos). A horseshoe is
//    a statement about an invariant set, not about the attractor (covering.hpp says so); the
//    proof is asserted, with the same re-checks as case 1.
#include <gtest/gtest.h>

#include <set>

#include "bouncer/analysis/periodic.hpp"
#include "bouncer/verify/chaos.hpp"
#include "bouncer/verify/covering.hpp"
#include "bouncer/verify/covering_impact.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

// The re-checks of a proved result that need nothing from the search but the certificate.
void expect_certificate_holds(const ModelSpec& spec, const ChaosSearchResult& r) {
  const ChaosCertificate& c = r.certificate;
  const int n = static_cast<int>(c.sets.size());
  ASSERT_GE(n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) EXPECT_TRUE(hsets_disjoint(c.sets[i], c.sets[j])) << i << " " << j;
  std::vector<std::vector<int>> A(n, std::vector<int>(n, 0));
  for (const CertifiedCovering& e : c.coverings) {
    ASSERT_TRUE(e.from >= 0 && e.from < n && e.to >= 0 && e.to < n);
    const auto branch = impact_branch(spec, c.k, c.bits, c.sets[e.from].c[0], c.sets[e.from].c[1]);
    ASSERT_EQ(branch.size(), static_cast<size_t>(c.k));
    EXPECT_EQ(branch_text(branch), e.branch);
    const CoveringResult again = check_covering(impact_set_map(spec, branch, c.bits), c.sets[e.from], c.sets[e.to],
                                                {c.bits, std::max(64, e.pieces)});
    EXPECT_TRUE(again.proved) << e.from << " => " << e.to << ": " << again.message;
    EXPECT_EQ(again.sign, e.sign) << e.from << " => " << e.to;
    A[e.from][e.to] = 1;
  }
  // The chain: 0 => 0, 0 => 1, i => i + 1, (n - 1) => 0.
  EXPECT_EQ(A[0][0], 1);
  for (int i = 0; i + 1 < n; ++i) EXPECT_EQ(A[i][i + 1], 1) << i;
  EXPECT_EQ(A[n - 1][0], 1);
  const EntropyBound e = entropy_lower_bound(A, c.k, c.bits);
  EXPECT_TRUE(e.horseshoe);
  EXPECT_EQ(e.bound, c.entropy_bound);
  EXPECT_EQ(e.quotient, c.quotient);
  // A chain of n sets with the self-loop has rho = the root of x^n = x^(n-1) + 1 > 1; extra
  // coverings only raise it: the bound is at least log of that root / k, rounded (the quotient
  // is a lower bound of rho, so compare with a little slack).
  double lo = 1, hi = 2;
  for (int it = 0; it < 200; ++it) {
    const double x = (lo + hi) / 2;
    (std::pow(x, n) - std::pow(x, n - 1) - 1 < 0 ? lo : hi) = x;
  }
  EXPECT_GE(e.bound_double, std::log(lo) / c.k * (1 - 1e-6));
}

TEST(Chaos, VeldepA27ProvesAHorseshoe) {
  const ModelSpec spec = test_support::spec(Law::veldep, "27", "1", "1000");
  const ChaosSearchResult r = certify_chaos(spec);
  ASSERT_TRUE(r.proved) << r.message;
  EXPECT_EQ(r.orbit.period, 2);
  EXPECT_NEAR(r.orbit.lambda_u, -2.8708355909245, 1e-9);
  EXPECT_NEAR(r.orbit.lambda_s, -0.2675171961402, 1e-9);
  EXPECT_TRUE(r.disjoint);
  EXPECT_GT(r.entropy.bound_double, 0);
  EXPECT_LT(r.entropy.bound_double, 0.2);
  EXPECT_EQ(r.certificate.k, 2);
  EXPECT_EQ(r.certificate.map, ChaosMap::impact);
  EXPECT_EQ(r.certificate.entropy_bound, r.entropy.bound);
  EXPECT_EQ(static_cast<int>(r.certificate.sets.size()), r.orbit.m + 1);
  for (const ChaosCovering& c : r.coverings) EXPECT_FALSE(c.result.message.empty());
  expect_certificate_holds(spec, r);
}

TEST(Chaos, VeldepA20HasNoSaddle) {
  const ModelSpec spec = test_support::spec(Law::veldep, "20", "1", "1000");
  const ChaosSearchResult r = certify_chaos(spec);
  EXPECT_FALSE(r.proved);
  EXPECT_EQ(r.orbit.period, 0);
  EXPECT_NE(r.message.find("no saddle periodic orbit found"), std::string::npos) << r.message;
  EXPECT_TRUE(r.certificate.coverings.empty());
}

TEST(Chaos, VeldepA25StablePeriod3CoexistsWithAHorseshoe) {
  const ModelSpec spec = test_support::spec(Law::veldep, "25", "1", "1000");
  // The attractor: a stable period-3 cycle (`bouncer periodic --period 3`).
  const Model<double> model = make_model<double>(spec, 53);
  const PeriodicOrbit<double> cycle = search_periodic<double>(model, 3);
  ASSERT_TRUE(cycle.converged);
  EXPECT_EQ(cycle.minimal_period, 3);
  EXPECT_LT(cycle.multipliers.modulus(0), 1);
  // And a horseshoe at the period-2 saddle: positive entropy on a non-attracting set.
  const ChaosSearchResult r = certify_chaos(spec);
  ASSERT_TRUE(r.proved) << r.message;
  EXPECT_EQ(r.orbit.period, 2);
  EXPECT_NEAR(r.orbit.lambda_u, -3.7808639219546, 1e-9);
  EXPECT_GT(r.entropy.bound_double, 0);
  EXPECT_LT(r.entropy.bound_double, 0.2);
  expect_certificate_holds(spec, r);
}

TEST(Chaos, TooFewIteratesForTheReturnSaysWhy) {
  // With too few iterates allowed for the return, the search stops and says where.
  const ModelSpec spec = test_support::spec(Law::veldep, "27", "1", "1000");
  ChaosSearchOptions o;
  o.max_return = 8;
  const ChaosSearchResult r = certify_chaos(spec, o);
  EXPECT_FALSE(r.proved);
  EXPECT_EQ(r.orbit.period, 2);
  EXPECT_NE(r.message.find("no homoclinic return found"), std::string::npos) << r.message;
}

// With --veldep-collapse on the interval step bounces where a point of a box may stick: no
// proof is attempted, and the message says why.
TEST(Chaos, VeldepCollapseOnIsNotAttempted) {
  ModelSpec spec = test_support::spec(Law::veldep, "27", "1", "1000");
  spec.veldep_collapse = true;
  const ChaosSearchResult r = certify_chaos(spec);
  EXPECT_FALSE(r.proved);
  EXPECT_NE(r.message.find("veldep-collapse"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace bouncer
