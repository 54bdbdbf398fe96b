// Randomized containment of the interval step (in the style of Arb's t-*.c tests), for each
// interval type of the set (Mpfi at the drawn precision, and the fast DoubleInterval): for
// random models, random boxes and a random exact point inside each box, the interval step
// either reports Undecided or its image encloses the image of the point, computed with
// MPFR at 512 bits. The same for the value part of the Dual<Mpfi> step (the Lohner
// enclosure's step), whose derivative parts must also enclose the point's Jacobian (from
// Dual<Mpfr> at 512 bits).
//
// Each draw follows the box and the point for up to 8 steps (until the interval step is
// undecided), so that later boxes are images of boxes: wider, skewed, after sticking.
//
// Draws: every model (elastic, constant eps in [0, 1], veldep with and without its collapse
// rule; downward-sticking paper or impact), every built-in wall shape, gravity a and c
// log-uniform over wide ranges, the interval precision among 53, 64, 113 and 256 bits,
// boxes of side 2^-40 ... 2^-4 anywhere in [0, 1) x [wall velocity, +200], and a dyadic
// point strictly inside (exact in every precision). The seed is fixed (override with
// BOUNCER_TEST_SEED=N); every failure names the seed and the draw.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "bouncer/analysis/jacobian.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "bouncer/verify/interval_dual.hpp"

namespace bouncer {
namespace {

constexpr unsigned long kDefaultSeed = 20240917;
constexpr int kDraws = 1000;
constexpr int kStepsPerDraw = 8;
constexpr long kTruthBits = 512;

unsigned long seed() {
  const char* s = std::getenv("BOUNCER_TEST_SEED");
  return s ? std::strtoul(s, nullptr, 10) : kDefaultSeed;
}

// A decimal with `digits` significant digits (as a user would type it).
std::string decimal_text(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

mpq_class dyadic(const mpz_class& n, unsigned k) {
  mpq_class q(n, mpz_class(1) << k);
  q.canonicalize();
  return q;
}

// Does the interval x hold the 512-bit point p?
bool holds(const Mpfi& x, const Mpfr& p) { return x.contains(p); }
bool holds(const DoubleInterval& x, const Mpfr& p) {
  return !x.has_nan() && mpfr_cmp_d(p.get(), x.lower()) >= 0 && mpfr_cmp_d(p.get(), x.upper()) <= 0;
}

Mpfr exact_mpfr(const mpq_class& q) {
  Mpfr r(kTruthBits);
  EXPECT_EQ(mpfr_set_q(r.get(), q.get_mpq_t(), MPFR_RNDN), 0) << "the point must be exact at 512 bits";
  return r;
}

struct Draw {
  ModelSpec spec;
  long bits;
  mpq_class th_lo, th_hi, v_lo, v_hi, th, v;
  std::string text;  // for failure messages
};

Draw draw(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  auto uniform_int = [&rng](long lo, long hi) { return std::uniform_int_distribution<long>(lo, hi)(rng); };
  Draw d;
  ModelSpec& m = d.spec;
  const long law = uniform_int(0, 2);
  m.law = law == 0 ? Law::elastic : law == 1 ? Law::constant : Law::veldep;
  m.a = parse_decimal("a", decimal_text(std::exp(std::log(0.5) + U(rng) * std::log(4000.0)), 6));
  m.eps = law == 1 ? parse_decimal("eps", decimal_text(std::round(U(rng) * 10000) / 10000, 4)) : Decimal::from_int(1);
  m.c = parse_decimal("c", decimal_text(std::exp(U(rng) * std::log(5000.0)), 5));
  m.veldep_collapse = m.law == Law::veldep && uniform_int(0, 1) == 1;
  m.downward = uniform_int(0, 1) ? DownwardSticking::paper : DownwardSticking::impact;
  const long shape = uniform_int(0, 2);
  const std::string wall = shape == 0 ? "triangle" : shape == 1 ? "sawtooth"
                                                    : "asymmetric:" + decimal_text(0.05 + 0.9 * U(rng), 3);
  m.wall = parse_wall("wall", wall);
  validate(m);
  const long bit_choices[] = {53, 64, 113, 256};
  d.bits = bit_choices[uniform_int(0, 3)];

  // Box: theta in [th_lo, th_lo + 2^-kt] within [0, 1), v from the highest wall velocity
  // over it upwards (so that every point of the box is above the wall).
  const unsigned kt = static_cast<unsigned>(uniform_int(4, 40)), kv = static_cast<unsigned>(uniform_int(4, 40));
  const mpz_class span = (mpz_class(1) << 52) - (mpz_class(1) << (52 - kt));
  mpz_class n = mpz_class(static_cast<unsigned long>(U(rng) * 4503599627370496.0));  // < 2^52
  n = n % span;
  d.th_lo = dyadic(n, 52);
  d.th_hi = d.th_lo + dyadic(1, kt);
  mpq_class u_max = wall_velocity_exact(m.wall, d.th_lo);
  const int j_lo = wall_segment_exact(m.wall, d.th_lo), j_hi = wall_segment_exact(m.wall, d.th_hi);
  for (int j = j_lo; j <= j_hi; ++j) u_max = std::max(u_max, wall_velocity_exact(m.wall, m.wall.knots[j].value()));
  // Relative speed log-uniform in [2^-12, 200]: slow impacts, sticking and chatter as well.
  const double rel = std::exp(std::log(0x1p-12) + U(rng) * (std::log(200.0) - std::log(0x1p-12)));
  const mpq_class scaled = (u_max + mpq_class(rel)) * mpq_class(mpz_class(1) << 40);
  mpz_class vn;
  mpz_cdiv_q(vn.get_mpz_t(), scaled.get_num_mpz_t(), scaled.get_den_mpz_t());  // rounded up
  d.v_lo = dyadic(vn, 40);
  d.v_hi = d.v_lo + dyadic(1, kv);
  // The point: strictly inside, on a grid of 2^-20 of the box side.
  const long it = uniform_int(1, (1L << 20) - 1), iv = uniform_int(1, (1L << 20) - 1);
  d.th = d.th_lo + dyadic(it, kt + 20);
  d.v = d.v_lo + dyadic(iv, kv + 20);

  std::ostringstream os;
  os << "model " << name(m.law) << " a=" << m.a.text() << " eps=" << m.eps.text() << " c=" << m.c.text()
     << " collapse=" << (m.veldep_collapse ? "on" : "off") << " downward=" << name(m.downward) << " wall=" << wall
     << " interval:" << d.bits << "; box theta in [" << d.th_lo.get_d() << " + 2^-" << kt << "], v in [" << d.v_lo.get_d()
     << " + 2^-" << kv << "]; point theta=" << d.th.get_str() << " v=" << d.v.get_str();
  d.text = os.str();
  return d;
}

template <class S>
void random_boxes_enclose_the_512_bit_image_of_a_point() {
  using SD = Dual<S>;
  const unsigned long s = seed();
  std::mt19937_64 rng(s);
  int decided = 0, undecided = 0, collapse_disagreements = 0, derivative_checks = 0;
  int decided_by_law[3] = {0, 0, 0}, by_kind[3] = {0, 0, 0};
  for (int i = 0; i < kDraws; ++i) {
    const Draw d = draw(rng);
    const Model<Mpfr> mp = make_model<Mpfr>(d.spec, kTruthBits);
    const Model<S> mi = make_model<S>(d.spec, d.bits);
    const Model<SD> md = convert_model<SD>(mi, [](const S& x) { return SD(x); });
    const ImpactMap<Mpfr> map_p(mp);
    const ImpactMap<Dual<Mpfr>> map_pd(dual_model(mp));
    const ImpactMap<S> map_i(mi);
    const ImpactMap<SD> map_d(md);
    State<Mpfr> point{exact_mpfr(d.th), exact_mpfr(d.v)};
    State<S> box{enclose_as<S>(d.th_lo, d.th_hi, d.bits), enclose_as<S>(d.v_lo, d.v_hi, d.bits)};
    ASSERT_TRUE(holds(box.theta, point.theta) && holds(box.v, point.v));
    // A few steps of the same box and point: the later boxes are images, wider and skewed.
    for (int n = 0; n < kStepsPerDraw; ++n) {
      SCOPED_TRACE("seed " + std::to_string(s) + ", draw " + std::to_string(i) + ", step " + std::to_string(n) + ": " +
                   d.text);
      // The point at 512 bits, and its Jacobian from the same step in Dual<Mpfr>.
      StepResult<Mpfr> rp;
      StepResult<Dual<Mpfr>> rpd;
      try {
        rp = map_p.step(point);
        rpd = map_pd.step(State<Dual<Mpfr>>{Dual<Mpfr>::variable(point.theta, 0), Dual<Mpfr>::variable(point.v, 1), point.knot});
      } catch (const Undecided& u) {
        // A 512-bit point step only stops at the walk limit (flights of 2^24 segments).
        ASSERT_EQ(u.reason, Reason::walk_limit) << u.what();
        break;
      }
      // The box in Mpfi and in Dual<Mpfi> (seeded: d/dtheta0, d/dv0).
      StepResult<S> ri;
      try {
        ri = map_i.step(box);
      } catch (const Undecided&) {
        ++undecided;
        break;
      }
      StepResult<SD> rd;
      try {
        rd = map_d.step(State<SD>{SD::variable(box.theta, 0), SD::variable(box.v, 1), box.knot});
      } catch (const Undecided& u) {
        ADD_FAILURE() << "the interval step decided but its dual step (same values) did not: " << u.what();
        return;
      }
      // With the veldep collapse rule, ending a chatter is decided by a bound being
      // certainly below the time left, which the box may not certify where the point does:
      // the interval step then goes on bouncing, also exact dynamics, but another image.
      if (d.spec.law == Law::veldep && d.spec.veldep_collapse && ri.kind != rp.kind) {
        ++collapse_disagreements;
        break;
      }
      ++decided;
      ++decided_by_law[static_cast<int>(d.spec.law)];
      ++by_kind[static_cast<int>(rp.kind)];
      EXPECT_EQ(ri.kind, rp.kind);
      EXPECT_EQ(ri.periods, rp.periods);
      EXPECT_EQ(ri.segment, rp.segment);
      using Tr = ScalarTraits<S>;
      EXPECT_TRUE(holds(ri.next.theta, rp.next.theta)) << "theta " << Tr::to_string(ri.next.theta) << " misses " << rp.next.theta;
      EXPECT_TRUE(holds(ri.next.v, rp.next.v)) << "v " << Tr::to_string(ri.next.v) << " misses " << rp.next.v;
      EXPECT_TRUE(holds(ri.tau, rp.tau)) << "tau " << Tr::to_string(ri.tau) << " misses " << rp.tau;
      EXPECT_EQ(rd.kind, rp.kind);
      EXPECT_TRUE(holds(rd.next.theta.v, rp.next.theta)) << "dual theta " << Tr::to_string(rd.next.theta.v);
      EXPECT_TRUE(holds(rd.next.v.v, rp.next.v)) << "dual v " << Tr::to_string(rd.next.v.v);
      // The derivative enclosures hold the point's Jacobian (when they are bounded: a value
      // enclosure cut at 0 under a square root leaves them unbounded, which holds anything).
      using DTr = ScalarTraits<SD>;
      if (DTr::derivatives_finite(rd.next.theta) && DTr::derivatives_finite(rd.next.v)) {
        ++derivative_checks;
        for (int k = 0; k < 2; ++k) {
          EXPECT_TRUE(holds(rd.next.theta.d[k], rpd.next.theta.d[k]))
              << "d theta1/d x" << k << ": " << Tr::to_string(rd.next.theta.d[k]) << " misses " << rpd.next.theta.d[k];
          EXPECT_TRUE(holds(rd.next.v.d[k], rpd.next.v.d[k]))
              << "d v1/d x" << k << ": " << Tr::to_string(rd.next.v.d[k]) << " misses " << rpd.next.v.d[k];
        }
      }
      if (::testing::Test::HasFailure()) {
        ADD_FAILURE() << "first failing draw; rerun with BOUNCER_TEST_SEED=" << s;
        return;
      }
      point = rp.next;
      box = ri.next;
    }
  }
  // The test must not pass vacuously: many steps are decided, in every model and of every
  // kind, and some are not (the boxes reach the limits of the interval step).
  std::printf("%s, seed %lu: %d draws of up to %d steps: %d steps decided (elastic %d, constant %d, veldep %d; "
              "impact %d, sticking %d, ride %d), %d undecided, %d veldep-collapse disagreements, "
              "%d Jacobians checked\n",
              ScalarTraits<S>::family, s, kDraws, kStepsPerDraw, decided, decided_by_law[0], decided_by_law[1], decided_by_law[2], by_kind[0],
              by_kind[1], by_kind[2], undecided, collapse_disagreements, derivative_checks);
  EXPECT_GE(decided, kDraws);
  for (int law = 0; law < 3; ++law) EXPECT_GE(decided_by_law[law], kDraws / 5) << "law " << law;
  EXPECT_GE(by_kind[static_cast<int>(EventKind::sticking)], 10);
  EXPECT_GE(undecided, kDraws / 20);
  EXPECT_GE(derivative_checks, decided / 2);
}

TEST(IntervalContainment, RandomBoxesEncloseThe512BitImageOfAPoint) {
  random_boxes_enclose_the_512_bit_image_of_a_point<Mpfi>();
}

TEST(IntervalContainment, DoubleIntervalRandomBoxesEncloseThe512BitImageOfAPoint) {
  random_boxes_enclose_the_512_bit_image_of_a_point<DoubleInterval>();
}

}  // namespace
}  // namespace bouncer
