// Jacobians by automatic differentiation (Dual<double>, Dual<Mpfr>) against independent
// truth: central finite differences of the Mpfr map at 256 bits, the exact zero Jacobian of
// sticking steps, and the measure identity of the impact map
//     det J = g'(s) (v0 - u0) / s,   s = relative impact speed, g(s) = relative speed out
// (constant eps: g'(s) = eps, s = (v1 - u1)/eps, so det J = eps^2 (v0 - u0)/(v1 - u1)),
// which follows from the flight preserving (v - u) dtheta dv.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "bouncer/analysis/jacobian.hpp"
#include "test_support.hpp"

using namespace bouncer;
using bouncer::test_support::spec;

namespace {

constexpr long kBits = 256;

Mpfr mp(const std::string& s) { return ScalarTraits<Mpfr>::from_decimal(s, kBits); }

struct Fd {
  bool ok = false;  // all four evaluations took the same branch as the centre
  double J[2][2];
};

// Central differences of P^q in Mpfr at 256 bits, h = 2^-90 (truncation error ~ h^2).
Fd finite_differences(const ImpactMap<Mpfr>& map, const State<Mpfr>& s, int q) {
  Mpfr h(1, kBits);
  mpfr_div_2si(h.get(), h.get(), 90, MPFR_RNDN);
  auto run = [&](const State<Mpfr>& x0, std::vector<std::pair<int, long long>>& branch) {
    State<Mpfr> x = x0;
    for (int i = 0; i < q; ++i) {
      StepResult<Mpfr> r = map.step(x);
      branch.emplace_back(r.segment * 8 + static_cast<int>(r.kind) * 2 + (r.corner ? 1 : 0), r.periods);
      x = r.next;
    }
    return x;
  };
  Fd fd;
  std::vector<std::pair<int, long long>> b0;
  run(s, b0);
  State<Mpfr> pts[4] = {{s.theta + h, s.v}, {s.theta - h, s.v}, {s.theta, s.v + h}, {s.theta, s.v - h}};
  State<Mpfr> out[4];
  for (int k = 0; k < 4; ++k) {
    std::vector<std::pair<int, long long>> b;
    out[k] = run(pts[k], b);
    if (b != b0) return fd;
  }
  auto diff = [&](const Mpfr& p, const Mpfr& m) { return Mpfr((p - m) / (2 * h)).to_double(); };
  fd.J[0][0] = diff(out[0].theta, out[1].theta);
  fd.J[1][0] = diff(out[0].v, out[1].v);
  fd.J[0][1] = diff(out[2].theta, out[3].theta);
  fd.J[1][1] = diff(out[2].v, out[3].v);
  fd.ok = true;
  return fd;
}

struct Case {
  Law law;
  std::string a, eps;
};

const std::vector<Case>& cases() {
  static const std::vector<Case> c{{Law::elastic, "20", "1"},    {Law::elastic, "19", "1"},
                                   {Law::constant, "19", "0.9"}, {Law::constant, "24", "0.5"},
                                   {Law::veldep, "25", "1"},     {Law::veldep, "27", "1"}};
  return c;
}

// Start states on both wall segments, short and long flights (indirect collisions).
const std::vector<std::pair<std::string, std::string>>& starts() {
  static const std::vector<std::pair<std::string, std::string>> s{
      {"0.1", "7"}, {"0.3", "9"}, {"0.45", "13.5"}, {"0.6", "2"}, {"0.8", "30"}, {"0.25", "55.5"}, {"0.9", "-1.5"}};
  return s;
}


}  // namespace

// One step and five steps, all three models: Dual<Mpfr> at 256 bits agrees with the
// finite differences to ~1e-40 (FD truncation error ~ h^2 = 2^-180 times curvature), and
// Dual<double> to ~1e-9 (the conditioning of double).
TEST(Jacobian, AutomaticDifferentiationMatchesFiniteDifferences) {
  int compared = 0, skipped = 0;
  for (const Case& c : cases()) {
    const ModelSpec m = spec(c.law, c.a, c.eps);
    const ImpactMap<Mpfr> map(make_model<Mpfr>(m, kBits));
    const TangentMap<Mpfr> tm_mp(make_model<Mpfr>(m, kBits));
    const TangentMap<double> tm_d(make_model<double>(m, 53));
    for (const auto& [th, v] : starts()) {
      for (int q : {1, 5}) {
        const State<Mpfr> s{mp(th), mp(v)};
        const Fd fd = finite_differences(map, s, q);
        if (!fd.ok) {
          ++skipped;
          continue;
        }
        const LinearOrbit<Mpfr> ad = tm_mp.steps(s, q);
        const LinearOrbit<double> add = tm_d.steps(State<double>{std::stod(th), std::stod(v)}, q);
        const Mpfr* J[2][2] = {{&ad.J.a11, &ad.J.a12}, {&ad.J.a21, &ad.J.a22}};
        const double Jd[2][2] = {{add.J.a11, add.J.a12}, {add.J.a21, add.J.a22}};
        double scale = 1;
        for (auto& row : fd.J)
          for (double x : row) scale = std::max(scale, std::fabs(x));
        for (int i = 0; i < 2; ++i)
          for (int k = 0; k < 2; ++k) {
            const std::string what = std::string(name(c.law)) + " a=" + c.a + " (" + th + ", " + v + ") q=" +
                                     std::to_string(q) + " J" + std::to_string(i) + std::to_string(k);
            EXPECT_LE(std::fabs(J[i][k]->to_double() - fd.J[i][k]), 1e-40 * scale) << what;
            EXPECT_LE(std::fabs(Jd[i][k] - fd.J[i][k]), 1e-8 * scale) << what << " (double)";
          }
        // The end states of the dual map are those of the plain map.
        State<Mpfr> x = s;
        for (int i = 0; i < q; ++i) x = map.step(x).next;
        EXPECT_TRUE(x.theta == ad.points.back().theta && x.v == ad.points.back().v);
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, 60) << "skipped (branch change within h): " << skipped;
}

// The measure identity det J = g'(s) (v0 - u0) / s for every impact step (not a corner).
TEST(Jacobian, DeterminantIsTheMeasureRatio) {
  int checked = 0;
  for (const Case& c : cases()) {
    const ModelSpec m = spec(c.law, c.a, c.eps);
    const Model<double> md = make_model<double>(m, 53);
    const TangentMap<double> tm(md);
    const double cc = 1000, eps = md.eps;
    State<double> s{0.3, 9};
    for (int n = 0; n < 200; ++n) {
      const LinearStep<double> st = tm.step(s);
      const double u0 = md.wall.velocity[md.wall.segment_of(s.theta)];
      const double u1 = md.wall.velocity[st.segment];
      const double out = st.next.v - u1;  // relative speed after the impact
      double g_prime, speed;
      if (c.law == Law::veldep) {
        // invert g(s) = s exp(-(s/c)^(3/5)) (increasing for s < c (5/3)^(5/3)) by bisection
        double lo = out, hi = out * 10 + 1;
        for (int i = 0; i < 200; ++i) {
          const double mid = 0.5 * (lo + hi);
          (mid * std::exp(-std::pow(mid / cc, 0.6)) < out ? lo : hi) = mid;
        }
        speed = 0.5 * (lo + hi);
        const double x = std::pow(speed / cc, 0.6);
        g_prime = std::exp(-x) * (1 - 0.6 * x);
      } else {
        g_prime = eps;
        speed = out / eps;
      }
      const double det = st.J.a11 * st.J.a22 - st.J.a12 * st.J.a21;
      if (st.kind == EventKind::impact && out > 1e-3) {
        EXPECT_NEAR(det, g_prime * (s.v - u0) / speed, 1e-9 * std::max(1.0, std::fabs(det)))
            << name(c.law) << " a=" << c.a << " step " << n;
        ++checked;
      }
      s = st.next;
    }
  }
  EXPECT_GE(checked, 600);
}

// Sticking: the release state does not depend on the input, J == 0 exactly; the finite
// differences agree (the perturbed collisions release at the same (1/2, 4)).
TEST(Jacobian, StickingStepHasZeroJacobian) {
  const ModelSpec m = spec(Law::constant, "30", "0.3");
  const TangentMap<Mpfr> tm(make_model<Mpfr>(m, kBits));
  const ImpactMap<Mpfr> map(make_model<Mpfr>(m, kBits));
  // From (0.2, 5) on the rising segment: relative speed 1, flight 2/30, out 0.3 below the
  // collapse threshold a(1-eps)/2 (1/2 - theta) ~ 2.4: collapse, ride, release at (1/2, 4).
  const State<Mpfr> s{mp("0.2"), mp("5")};
  const LinearStep<Mpfr> st = tm.step(s);
  ASSERT_EQ(st.kind, EventKind::sticking);
  EXPECT_TRUE(st.contracted);
  for (const Mpfr* x : {&st.J.a11, &st.J.a12, &st.J.a21, &st.J.a22}) EXPECT_EQ(mpfr_zero_p(x->get()), 1);
  EXPECT_TRUE(st.next.theta == mp("0.5") && st.next.v == mp("4"));
  const Fd fd = finite_differences(map, s, 1);
  ASSERT_TRUE(fd.ok);
  for (auto& row : fd.J)
    for (double x : row) EXPECT_EQ(x, 0.0);
}

// Closed-form eigenvalues: they satisfy the characteristic polynomial, real and complex.
TEST(Jacobian, EigenvaluesSolveTheCharacteristicPolynomial) {
  const std::vector<Mat2<double>> ms{{1, 0.0625, 0, 0.25}, {2, 1, -3, 0.5}, {0, 1, -1, 0}, {1e8, 1, 1, 1e-8}, {-4, 2, 3, 7}};
  for (const Mat2<double>& m : ms) {
    const Eigen2<double> e = eigenvalues(m);
    const double tr = m.a11 + m.a22, det = m.a11 * m.a22 - m.a12 * m.a21;
    for (int i = 0; i < 2; ++i) {
      const std::complex<double> l(e.re[i], e.im[i]);
      const std::complex<double> p = l * l - tr * l + det;
      EXPECT_LE(std::abs(p), 1e-12 * std::max({1.0, std::abs(l) * std::abs(l), std::fabs(det)}));
    }
    EXPECT_GE(e.modulus(0), e.modulus(1));
    EXPECT_NEAR(e.complex ? e.modulus(0) * e.modulus(1) : e.re[0] * e.re[1], std::fabs(det) * (e.complex ? 1 : (det < 0 ? -1 : 1)),
                1e-12 * std::max(1.0, std::fabs(det)));
  }
  const Eigen2<double> r = eigenvalues(Mat2<double>{1, 0.0625, 0, 0.25});
  EXPECT_FALSE(r.complex);
  EXPECT_DOUBLE_EQ(r.re[0], 1);
  EXPECT_DOUBLE_EQ(r.re[1], 0.25);
  const Eigen2<double> c = eigenvalues(Mat2<double>{0, 1, -1, 0});
  EXPECT_TRUE(c.complex);
  EXPECT_DOUBLE_EQ(c.im[0], 1);
  EXPECT_DOUBLE_EQ(c.im[1], -1);
}

// The dual map is the plain map on values: along long orbits (impacts, sticking, the
// downward-sticking "impact" convention, veldep collapse) the states agree bit for bit,
// in every analysis scalar (Newton's line search, analysis/periodic.cpp, relies on it:
// it tries steps with the plain map and differentiates only the one it accepts).
// This also guards dual_model(), which must copy every field of Model.
TEST(Jacobian, DualMapFollowsThePlainMapBitForBit) {
  std::vector<ModelSpec> specs{spec(Law::elastic, "20"), spec(Law::constant, "19", "0.9"),
                               spec(Law::constant, "20", "0.3"), spec(Law::veldep, "27"),
                               spec(Law::veldep, "14", "1", "1")};
  ModelSpec down = spec(Law::constant, "20", "0.3");
  down.downward = DownwardSticking::impact;
  specs.push_back(down);
  ModelSpec collapse = spec(Law::veldep, "14", "1", "1");
  collapse.veldep_collapse = true;
  specs.push_back(collapse);
  for_each_scalar<AnalysisScalars>([&](auto tag) {
    using T = typename decltype(tag)::type;
    using Tr = ScalarTraits<T>;
    const long bits = Tr::fixed_bits > 0 ? Tr::fixed_bits : 128;  // Mpfr: the two-limb precision
    const bool is_double = std::is_same_v<T, double>;
    // The exact printed value (every digit the type holds): equal texts, equal numbers.
    const auto same = [](const T& p, const T& q) { return Tr::to_string(p) == Tr::to_string(q); };
    for (size_t i = 0; i < specs.size(); ++i) {
      const ImpactMap<T> map(make_model<T>(specs[i], bits));
      const TangentMap<T> tm(map.model());
      State<T> x = make_state<T>(InitialCondition{*Decimal::parse("0.3"), *Decimal::parse("9")}, bits), y = x;
      int sticking = 0;
      for (int n = 0; n < (is_double ? 3000 : 600); ++n) {
        const StepResult<T> r = map.step(x);
        const LinearStep<T> l = tm.step(y);
        ASSERT_TRUE(same(r.next.theta, l.next.theta)) << Tr::family << " model " << i << " step " << n;
        ASSERT_TRUE(same(r.next.v, l.next.v)) << Tr::family << " model " << i << " step " << n;
        ASSERT_EQ(r.kind, l.kind);
        ASSERT_EQ(r.next.knot, l.next.knot);
        ASSERT_EQ(l.contracted, r.kind != EventKind::impact);
        sticking += r.kind == EventKind::sticking;
        x = r.next;
        y = l.next;
      }
      if (i == 2 || i == 5) {
        EXPECT_GT(sticking, 0) << Tr::family << " model " << i;
      }
    }
  });
}

// Dual<Mpfr>'s in-place forms (operator*=, make_nonneg, clamp_into_segment, blank) give the
// bits of the operator forms they replace (ScalarTraits<Dual<Mpfr>>::nonneg and ::clamp,
// `x = x * y`): for constant and varying operands, an operand that is the target itself,
// negative and clamped values; at 128 bits (two limbs) and 300 (beyond four).
TEST(Jacobian, DualMpfrInPlaceFormsMatchTheOperators) {
  using D = Dual<Mpfr>;
  using Tr = ScalarTraits<D>;
  for (const long bits : {128L, 300L}) {
    const auto num = [bits](const char* s) { return ScalarTraits<Mpfr>::from_decimal(s, bits); };
    const auto same = [](const D& x, const D& y) {
      for (const auto& [p, q] : {std::pair{&x.v, &y.v}, std::pair{&x.d[0], &y.d[0]}, std::pair{&x.d[1], &y.d[1]}})
        if (p->bits() != q->bits() || !(mpfr_equal_p(p->get(), q->get()) || (mpfr_nan_p(p->get()) && mpfr_nan_p(q->get()))) ||
            mpfr_signbit(p->get()) != mpfr_signbit(q->get()))
          return false;
      return true;
    };
    const std::vector<D> xs{D(num("3.1"), num("-0.7"), num("1e-5")), D(num("-2.25"), num("0.1"), num("-7.3")),
                            D(num("0.3")), D::variable(num("1.7"), 1), D(num("1e20"), num("3"), num("0"))};
    for (const D& x : xs) {
      for (const D& y : xs) {
        D a = x;
        a *= y;
        EXPECT_TRUE(same(a, x * y)) << bits << " bits: " << x << " * " << y;
      }
      D self = x;
      self *= self;
      EXPECT_TRUE(same(self, x * x)) << bits << " bits: " << x << " squared";
      D n = x;
      make_nonneg(n);
      EXPECT_TRUE(same(n, Tr::nonneg(x))) << bits << " bits: nonneg " << x;
      for (const auto& [lo, hi] : {std::pair{"-1", "1"}, std::pair{"0.5", "4"}, std::pair{"-3", "-2.5"}}) {
        D c = x;
        clamp_into_segment(c, D(num(lo)), D(num(hi)));
        EXPECT_TRUE(same(c, Tr::clamp(x, D(num(lo)), D(num(hi))))) << bits << " bits: clamp " << x;
      }
    }
    const D b = blank<D>(bits);
    for (const Mpfr* p : {&b.v, &b.d[0], &b.d[1]}) EXPECT_EQ(p->bits(), bits);
  }
}
