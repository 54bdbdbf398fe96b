// The trapping region (model/trapping.hpp): its top against hand-derived formulas, the
// sharp case on the triangle, the paper's certified counterexamples at small c, and random
// impacts stepped in MPFI intervals, which must stay certainly below the top, on the
// triangle and on an asymmetric wall, for both laws. Every command takes its default
// v range from these functions (basin, scan, lyapunov, the periodic-orbit search), so these
// tests are what the four retyped copies lacked (scan's copy kept the paper's bound where
// it is not invariant).
#include <gtest/gtest.h>
#include <mpfr.h>

#include <random>
#include <string>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/trapping.hpp"
#include "bouncer/scalar/mpfi.hpp"

using namespace bouncer;

namespace {

constexpr long kBits = 128;
using TrI = ScalarTraits<Mpfi>;

ModelSpec model_spec(Law law, const std::string& a, const std::string& eps_or_c, const std::string& wall) {
  ModelSpec m;
  m.law = law;
  m.a = *Decimal::parse(a);
  m.eps = *Decimal::parse(law == Law::constant ? eps_or_c : "1");
  m.c = *Decimal::parse(law == Law::veldep ? eps_or_c : "1000");
  m.wall = parse_wall("wall", wall);
  validate(m);
  return m;
}

mpq_class q(const std::string& decimal) { return Decimal::parse(decimal)->value(); }

// lo <= x <= hi for the interval's end points, exactly.
bool encloses(const Mpfi& iv, const mpq_class& x) {
  return mpfr_cmp_q(iv.lower().get(), x.get_mpq_t()) <= 0 && mpfr_cmp_q(iv.upper().get(), x.get_mpq_t()) >= 0;
}

bool certainly_le(const Mpfi& x, const Mpfi& y) { return TrI::le(x, y) == Truth::yes; }

}  // namespace

// Constant eps: (U + eps (U + 2D)) / (1 - eps) with the wall's speeds, derived by hand:
// triangle U = D = 4 gives the paper's 4(1 + 3 eps)/(1 - eps); asymmetric:0.25 rises from
// -1 to 1 in 1/4 (U = 8) and falls back in 3/4 (D = 8/3).
TEST(Trapping, ConstantTopIsTheHandFormula) {
  for (const char* e : {"0", "0.1", "0.5", "0.82", "0.99"}) {
    SCOPED_TRACE(e);
    const mpq_class eps = q(e);
    const mpq_class tri = 4 * (1 + 3 * eps) / (1 - eps);
    const mpq_class asym = (8 + eps * (8 + mpq_class(16, 3))) / (1 - eps);
    const ModelSpec t = model_spec(Law::constant, "24", e, "triangle");
    const ModelSpec s = model_spec(Law::constant, "24", e, "asymmetric:0.25");
    EXPECT_EQ(*trapping_top_exact(t), tri);
    EXPECT_EQ(*trapping_top_exact(s), asym);
    EXPECT_TRUE(encloses(*trapping_top(make_model<Mpfi>(t, kBits)), tri));
    EXPECT_TRUE(encloses(*trapping_top(make_model<Mpfi>(s, kBits)), asym));
    // In double, bit for bit the paper's expression as the commands computed it before.
    const double d = ScalarTraits<double>::from_decimal(e, 53);
    EXPECT_EQ(*trapping_top(make_model<double>(t, 53)), (d * 3 + 1) * 4 / (1 - d));
    // The grid commands' default range: from U to the top rounded up to 4 decimals.
    const auto range = trapping_v_range(s);
    ASSERT_TRUE(range);
    EXPECT_EQ(range->first.value(), mpq_class(8));
    EXPECT_GE(range->second.value(), asym);
    EXPECT_LT(range->second.value(), asym + mpq_class(1, 10000));
  }
  EXPECT_FALSE(trapping_top_exact(model_spec(Law::constant, "24", "1", "triangle")));
  EXPECT_FALSE(trapping_top(make_model<double>(model_spec(Law::constant, "24", "1", "triangle"), 53)));
  EXPECT_FALSE(trapping_top(make_model<double>(model_spec(Law::elastic, "24", "1", "triangle"), 53)));
  EXPECT_FALSE(trapping_v_range(model_spec(Law::elastic, "24", "1", "triangle")));
}

// Sharp on the triangle: eps = 1/2, a = 96, (1/2, 20) -> (0, 20) exactly, and 20 is the top.
TEST(Trapping, ConstantTopIsReachedOnTheTriangle) {
  const ModelSpec s = model_spec(Law::constant, "96", "0.5", "triangle");
  EXPECT_EQ(*trapping_top_exact(s), mpq_class(20));
  const ImpactMap<Mpfi> map(make_model<Mpfi>(s, kBits));
  const StepResult<Mpfi> r = map.step(State<Mpfi>{TrI::from_decimal("0.5", kBits), Mpfi(20, kBits)});
  EXPECT_TRUE(encloses(r.next.v, mpq_class(20)));
}

// The velocity-dependent law. At c = 1000 (and 10, 1) the paper's V_c is invariant and is
// the top: 4[2 coth(2^(4/5)/c^(3/5)) - 1], computed here independently in MPFR. At c = 1/2
// and 1/10 it is not: proofs/trapping_region certifies that the states below leave it; the
// top must then hold their images, and it is 4 + h_max = 4 + c (5/3)^(5/3) e^(-5/3).
TEST(Trapping, VelocityDependentTop) {
  for (const char* c : {"1000", "10", "1"}) {
    SCOPED_TRACE(c);
    const Mpfi cc = TrI::from_decimal(c, kBits);
    const Mpfi x = exp(log(Mpfi(2, kBits)) * 4 / 5 - log(cc) * 3 / 5);
    const Mpfi coth = (exp(2 * x) + 1) / (exp(2 * x) - 1);
    const Mpfi v_c = 4 * (2 * coth - 1);
    const Mpfi top = *trapping_top(make_model<Mpfi>(model_spec(Law::veldep, "25", c, "triangle"), kBits));
    EXPECT_FALSE(TrI::lt(top, v_c) == Truth::yes || TrI::lt(v_c, top) == Truth::yes)  // the enclosures meet
        << "top " << TrI::to_string(top) << " vs V_c " << TrI::to_string(v_c);
    const double td = *trapping_top(make_model<double>(model_spec(Law::veldep, "25", c, "triangle"), 53));
    EXPECT_NEAR(td, TrI::to_double(v_c), 1e-12 * td);
  }
  struct Escape { const char *c, *a, *theta, *v; };
  for (const Escape& e : {Escape{"0.5", "25", "0.9965", "4"}, Escape{"0.1", "10", "0.9995", "4"}}) {
    SCOPED_TRACE(e.c);
    const ModelSpec s = model_spec(Law::veldep, e.a, e.c, "triangle");
    const Mpfi cc = TrI::from_decimal(e.c, kBits);
    const Mpfi five_thirds = Mpfi(5, kBits) / 3;
    const Mpfi h_max = cc * exp(log(five_thirds) * five_thirds - five_thirds);
    const Mpfi top = *trapping_top(make_model<Mpfi>(s, kBits));
    const Mpfi expected = h_max + 4;
    EXPECT_FALSE(TrI::lt(top, expected) == Truth::yes || TrI::lt(expected, top) == Truth::yes)  // the enclosures meet
        << TrI::to_string(top) << " vs 4 + h_max " << TrI::to_string(expected);
    const ImpactMap<Mpfi> map(make_model<Mpfi>(s, kBits));
    const StepResult<Mpfi> r = map.step(State<Mpfi>{TrI::from_decimal(e.theta, kBits), TrI::from_decimal(e.v, kBits)});
    EXPECT_TRUE(certainly_le(r.next.v, top)) << TrI::to_string(r.next.v) << " above " << TrI::to_string(top);
    const double td = *trapping_top(make_model<double>(s, 53));
    EXPECT_NEAR(td, TrI::to_double(h_max) + 4, 1e-12 * td);
  }
}

// Random starts in the strip {u(theta) <= v <= V}, one impact each in MPFI: the next
// velocity is certainly at most V (forward invariance), for both laws, on the triangle and
// on asymmetric walls, at small and large c. Starts are exact decimals; a step the
// intervals cannot decide is skipped, and at most a tenth may be.
TEST(Trapping, ImpactsStayBelowTheTop) {
  struct Case { Law law; const char *a, *p, *wall; };
  const Case cases[] = {
      {Law::constant, "24", "0.5", "triangle"},       {Law::constant, "10", "0.3", "asymmetric:0.25"},
      {Law::constant, "3", "0.9", "asymmetric:0.8"},  {Law::veldep, "25", "0.5", "triangle"},
      {Law::veldep, "10", "0.1", "triangle"},         {Law::veldep, "25", "1000", "triangle"},
      {Law::veldep, "25", "0.5", "asymmetric:0.25"},  {Law::veldep, "20", "1000", "asymmetric:0.7"},
  };
  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Case& k : cases) {
    SCOPED_TRACE(std::string(k.wall) + " " + k.p);
    const ModelSpec s = model_spec(k.law, k.a, k.p, k.wall);
    const Model<Mpfi> m = make_model<Mpfi>(s, kBits);
    const ImpactMap<Mpfi> map(m);
    const Mpfi top = *trapping_top(m);
    const double top_d = TrI::to_double(top);
    int decided = 0;
    const int n = 300;
    for (int i = 0; i < n; ++i) {
      const std::string th = std::to_string(unit(rng)).substr(0, 8);
      const mpq_class theta = q(th);
      const double u = wall_velocity_exact(s.wall, theta).get_d();
      // Mostly near the top (where invariance is tight), some anywhere in the strip.
      const double f = i % 3 == 0 ? unit(rng) : 1 - 0.05 * unit(rng);
      const double v = u + f * (top_d - u) - 1e-6;
      if (v < u) continue;
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.6f", v);
      if (q(buf) < wall_velocity_exact(s.wall, theta)) continue;
      try {
        const StepResult<Mpfi> r = map.step(State<Mpfi>{TrI::from_decimal(th, kBits), TrI::from_decimal(buf, kBits)});
        ++decided;
        EXPECT_TRUE(certainly_le(r.next.v, top)) << "(" << th << ", " << buf << ") -> v' " << TrI::to_string(r.next.v)
                                                 << " above the top " << TrI::to_string(top);
      } catch (const Undecided&) {
      }
    }
    EXPECT_GE(decided, n * 9 / 10);
  }
}
