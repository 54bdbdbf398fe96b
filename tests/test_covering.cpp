// Covering relations and the entropy bound (verify/covering.hpp), on maps whose answer is
// known exactly.
//
// 1. The linear horseshoe (Smale's, piecewise linear):
//        F(x, y) = (3x, y/3)          for x < 1/2,
//        F(x, y) = (3 - 3x, 1 - y/3)  for x > 1/2  (undecided over boxes meeting x = 1/2).
//    Its invariant set in [0, 1]^2 is C x C (C the middle-thirds Cantor set), on which F is
//    conjugate to the full shift on two symbols: h_top = log 2 there. The h-sets
//    N_0 = [-1/30, 11/30] x [-1/10, 11/10] and N_1 = [19/30, 31/30] x [-1/10, 11/10] (slightly
//    wider than [0, 1/3] and [2/3, 1], so that the edges map strictly outside, as covering
//    relations need) hold the same invariant set (a point with x < 0 or x > 1 has x -> -inf),
//    and all four coverings N_i => N_j hold: N_0 with sign +1, N_1 with sign -1 (it flips x).
//    So the bound is log(rho([[1,1],[1,1]])) = log 2 exactly, rounded down: it must be within
//    1e-12 of log 2 and never above it. With N_0 = [0, 1/3] x [0, 1] exactly, the image of the
//    left edge lies ON N_0's left edge (y_u = -1): not a covering, and the check must say so.
// 2. The same horseshoe seen through the shear S = [[1, 1/4], [1/2, 1]]: G = S F S^-1 with
//    h-sets S N_i (tilted parallelograms, B = S B_i). G covers S N_j exactly when F covers
//    N_j, so the same four coverings and bound must come out, now through real local
//    coordinates (B^-1 not diagonal) and boxes that over-enclose the tilted pieces.
// 3. The Henon map H(x, y) = (1 - a x^2 + y, b x) at a = 6, b = 0.3: for
//    a > (5 + 2 sqrt 5)(1 + |b|)^2 / 4 (about 4.01 here) its non-wandering set is a
//    horseshoe conjugate to the full 2-shift (Devaney and Nitecki, "Shift automorphisms in
//    the Henon mapping", Comm. Math. Phys. 67 (1979) 137-146): h_top = log 2. The strips
//    N_+ = [3/20, 3/5] x [-1/5, 1/5] and N_- = -N_+ cover each other and themselves.
// 4. Maps that must fail, each for its stated reason: a contraction (edges not stretched
//    across: left_edge), an expansion in both directions (leaves through the stable side:
//    stable_side), a translation (both edges on one side: same_side), an h-set across the
//    horseshoe's branch line (undecided), a singular B.
// 5. Transition matrices of known spectral radius: the golden-mean shift [[1,1],[1,0]]
//    (rho = (1 + sqrt 5)/2), reducible ones, a single cycle (rho = 1: no horseshoe).
// 6. The bouncer itself (verify/covering_impact.hpp): the velocity-dependent model at
//    c = 1000, a = 27 has a period-2 saddle (`bouncer periodic --model veldep --c 1000 --a 27
//    --period 2`: the point (0.0905229578316182, 10.85655768412576), multipliers -2.87 and
//    -0.27, eigenvectors about (0.013129, -0.999914) and (0.0517543, -0.99866)). A small
//    h-set along them covers itself under F^2 with sign -1 (the unstable multiplier is
//    negative: the edges swap sides); with the two directions swapped it does not (the
//    image of an edge stays across M's unstable extent), and tied to a branch the h-set is
//    not on, every box is refused. Given on parallelograms (Lohner started from each piece
//    itself), the same covering is proved with one piece per side, and a thin h-set (10^-3
//    along the unstable direction, 10^-6 along the stable one, about 3 degrees apart) is
//    proved where the boxes around its pieces wrap far beyond it and fail (b).
#include <gtest/gtest.h>

#include <cmath>

#include "bouncer/scalar/mpfi.hpp"
#include "bouncer/verify/covering.hpp"
#include "bouncer/verify/covering_impact.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

constexpr long kBits = 128;

Mpfi q(long num, long den = 1) { return enclose(mpq_class(num, den), mpq_class(num, den), kBits); }

bool certainly_below(const Mpfi& x, long num, long den) {
  return mpfr_cmp_q(&x.get()->right, mpq_class(num, den).get_mpq_t()) < 0;
}
bool certainly_above(const Mpfi& x, long num, long den) {
  return mpfr_cmp_q(&x.get()->left, mpq_class(num, den).get_mpq_t()) > 0;
}

// Case 1: the linear horseshoe.
std::optional<Box2> horseshoe(const Box2& p) {
  if (certainly_below(p[0], 1, 2)) return Box2{p[0] * 3, p[1] / 3};
  if (certainly_above(p[0], 1, 2)) return Box2{3 - p[0] * 3, 1 - p[1] / 3};
  return std::nullopt;
}

std::vector<HSet2> horseshoe_sets() {
  return {hset_rectangle(mpq_class(-1, 30), mpq_class(11, 30), mpq_class(-1, 10), mpq_class(11, 10)),
          hset_rectangle(mpq_class(19, 30), mpq_class(31, 30), mpq_class(-1, 10), mpq_class(11, 10))};
}

// log 2 and the bound's text, compared at 256 bits: the bound must be <= log 2 (its text read
// rounded up is <= the lower end of log 2's enclosure) and log 2 - bound < tol.
void expect_bound_below(const std::string& bound, const Mpfi& truth, double tol) {
  Mpfr b(256);
  ASSERT_EQ(mpfr_set_str(b.get(), bound.c_str(), 10, MPFR_RNDU), 0) << bound;
  Mpfr lo = truth.lower();
  EXPECT_LE(mpfr_cmp(b.get(), lo.get()), 0) << "bound " << bound << " above the truth";
  Mpfr gap(256);
  mpfr_sub(gap.get(), truth.upper().get(), b.get(), MPFR_RNDU);
  EXPECT_LT(mpfr_get_d(gap.get(), MPFR_RNDU), tol) << bound;
}

Mpfi log2_256() { return log(Mpfi(2, 256)); }

TEST(Covering, LinearHorseshoeProvesAllFourCoveringsAndLog2) {
  const auto sets = horseshoe_sets();
  const HorseshoeResult r = check_horseshoe(horseshoe, sets, 1);
  ASSERT_TRUE(r.disjoint);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const CoveringResult& c = r.coverings[i][j];
      EXPECT_TRUE(c.proved) << i << " => " << j << ": " << c.message;
      EXPECT_EQ(c.failure, CoveringFailure::none);
      EXPECT_EQ(c.sign, i == 0 ? 1 : -1) << i << " => " << j;
      EXPECT_EQ(r.matrix[i][j], 1);
    }
  EXPECT_TRUE(r.entropy.horseshoe);
  EXPECT_EQ(r.entropy.quotient, 2);
  expect_bound_below(r.entropy.bound, log2_256(), 1e-12);
  EXPECT_LE(r.entropy.bound_double, std::log(2.0));
}

// The linear horseshoe on parallelograms: the piece's box (c + B r in intervals) mapped, and
// its image handed back as the parallelogram 0 + I r'.
std::optional<Parallelogram> horseshoe_on_sets(const Parallelogram& p) {
  Box2 box;
  auto pt = [](const Mpfr& x) { return Mpfi(x, x); };
  for (int i = 0; i < 2; ++i) box[i] = pt(p.c[i]) + pt(p.B[i][0]) * p.r[0] + pt(p.B[i][1]) * p.r[1];
  const auto y = horseshoe(box);
  if (!y) return std::nullopt;
  Parallelogram out;
  for (int i = 0; i < 2; ++i) {
    out.c[i] = Mpfr(0, kBits);
    for (int j = 0; j < 2; ++j) out.B[i][j] = Mpfr(i == j ? 1 : 0, kBits);
    out.r[i] = (*y)[i];
  }
  return out;
}

TEST(Covering, HorseshoeOverListedEdgesChecksOnlyThem) {
  // Three of the four coverings listed, one map per source set: the golden-mean graph
  // 0 => 0, 0 => 1, 1 => 0 (rho = (1 + sqrt 5)/2), 1 => 1 not checked.
  const auto sets = horseshoe_sets();
  const std::vector<SetMap2> maps{horseshoe_on_sets, horseshoe_on_sets};
  const HorseshoeResult r = check_horseshoe(maps, sets, {{0, 0}, {0, 1}, {1, 0}}, 1, {kBits, 4});
  ASSERT_TRUE(r.disjoint);
  EXPECT_TRUE(r.coverings[0][0].proved) << r.coverings[0][0].message;
  EXPECT_TRUE(r.coverings[0][1].proved) << r.coverings[0][1].message;
  EXPECT_TRUE(r.coverings[1][0].proved) << r.coverings[1][0].message;
  EXPECT_EQ(r.coverings[1][0].sign, -1);
  EXPECT_FALSE(r.coverings[1][1].proved);
  EXPECT_EQ(r.coverings[1][1].boxes, 0);
  EXPECT_EQ(r.coverings[1][1].message, "not checked");
  EXPECT_EQ(r.matrix, (std::vector<std::vector<int>>{{1, 1}, {1, 0}}));
  EXPECT_TRUE(r.entropy.horseshoe);
  EXPECT_LE(r.entropy.bound_double, std::log((1 + std::sqrt(5.0)) / 2));
  EXPECT_GT(r.entropy.bound_double, std::log((1 + std::sqrt(5.0)) / 2) - 1e-9);
  // Overlapping sets: no bound, whatever the coverings.
  std::vector<HSet2> overlapping = sets;
  overlapping[1] = hset_rectangle(mpq_class(1, 3), mpq_class(31, 30), mpq_class(-1, 10), mpq_class(11, 10));
  const HorseshoeResult o = check_horseshoe(maps, overlapping, {{0, 0}}, 1, {kBits, 4});
  EXPECT_FALSE(o.disjoint);
  EXPECT_FALSE(o.entropy.horseshoe);
}

TEST(Covering, HorseshoeOnTheUnitStripsIsNotACoveringEdgesOnTheBoundary) {
  // F maps N_0's left edge x = 0 onto x = 0: y_u = -1 exactly, not < -1.
  const HSet2 n0 = hset_rectangle(0, mpq_class(1, 3), 0, 1);
  const CoveringResult c = check_covering(horseshoe, n0, n0, {kBits, 16});
  EXPECT_FALSE(c.proved);
  EXPECT_EQ(c.failure, CoveringFailure::left_edge) << c.message;
  EXPECT_EQ(c.piece[0], -1);
  EXPECT_EQ(c.piece[1], -1);
  ASSERT_TRUE(c.image.has_value());
  EXPECT_TRUE((*c.image)[0].contains(Mpfr(-1, kBits))) << c.message;
  EXPECT_EQ(c.pieces, 16);
}

// Case 2: the horseshoe through the shear S.
const mpq_class kS[2][2] = {{1, mpq_class(1, 4)}, {mpq_class(1, 2), 1}};

Box2 apply(const mpq_class (&M)[2][2], const Box2& p) {
  Box2 out;
  for (int r = 0; r < 2; ++r)
    out[r] = enclose(M[r][0], M[r][0], kBits) * p[0] + enclose(M[r][1], M[r][1], kBits) * p[1];
  return out;
}

std::optional<Box2> sheared_horseshoe(const Box2& p) {
  // S^-1 = (8/7) [[1, -1/4], [-1/2, 1]]
  const mpq_class Sinv[2][2] = {{mpq_class(8, 7), mpq_class(-2, 7)}, {mpq_class(-4, 7), mpq_class(8, 7)}};
  const auto f = horseshoe(apply(Sinv, p));
  if (!f) return std::nullopt;
  return apply(kS, *f);
}

HSet2 sheared(const HSet2& h) {
  HSet2 out;
  for (int r = 0; r < 2; ++r) {
    out.c[r] = kS[r][0] * h.c[0] + kS[r][1] * h.c[1];
    for (int col = 0; col < 2; ++col) out.B[r][col] = kS[r][0] * h.B[0][col] + kS[r][1] * h.B[1][col];
  }
  return out;
}

TEST(Covering, TiltedHSetsOfTheShearedHorseshoe) {
  std::vector<HSet2> sets;
  for (const HSet2& h : horseshoe_sets()) sets.push_back(sheared(h));
  ASSERT_NE(sets[0].B[1][0], 0);  // really tilted: the unstable direction is not an axis
  const HorseshoeResult r = check_horseshoe(sheared_horseshoe, sets, 1);
  ASSERT_TRUE(r.disjoint);
  int most_pieces = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      EXPECT_TRUE(r.coverings[i][j].proved) << i << " => " << j << ": " << r.coverings[i][j].message;
      EXPECT_EQ(r.coverings[i][j].sign, i == 0 ? 1 : -1);
      most_pieces = std::max(most_pieces, r.coverings[i][j].pieces);
    }
  // The wrapped boxes of tilted pieces need subdivision: the escalation is exercised.
  EXPECT_GT(most_pieces, 1);
  expect_bound_below(r.entropy.bound, log2_256(), 1e-12);
}

TEST(Covering, LocalCoordinatesInvertTheFrame) {
  // A point c + B x maps back to x (exact here: small rationals at 128 bits).
  const HSet2 h = sheared(horseshoe_sets()[1]);
  const Box2 p = hset_box(h, mpq_class(1, 4), mpq_class(1, 4), mpq_class(-3, 8), mpq_class(-3, 8), kBits);
  const auto y = hset_local(h, p);
  ASSERT_TRUE(y.has_value());
  EXPECT_TRUE((*y)[0].contains(q(1, 4)));
  EXPECT_TRUE((*y)[1].contains(q(-3, 8)));
  EXPECT_LT(mpfr_get_d((*y)[0].width().get(), MPFR_RNDU), 1e-30);
}

TEST(Covering, DisjointnessIsExact) {
  const auto sets = horseshoe_sets();
  EXPECT_TRUE(hsets_disjoint(sets[0], sets[1]));
  EXPECT_TRUE(hsets_disjoint(sheared(sets[0]), sheared(sets[1])));
  EXPECT_FALSE(hsets_disjoint(sets[0], sets[0]));
  // Touching closed sets are not disjoint: [0, 1] and [1, 2] share the edge x = 1.
  EXPECT_FALSE(hsets_disjoint(hset_rectangle(0, 1, 0, 1), hset_rectangle(1, 2, 0, 1)));
  // Two tilted squares whose bounding boxes overlap but which a diagonal axis separates.
  HSet2 a, b;
  a.c = {0, 0};
  a.B = {{{mpq_class(1, 2), mpq_class(-1, 2)}, {mpq_class(1, 2), mpq_class(1, 2)}}};  // a diamond of radius 1
  b = a;
  b.c = {mpq_class(11, 10), mpq_class(11, 10)};  // along (1, 1): a reaches x + y = 1, b starts at 1.2
  EXPECT_TRUE(hsets_disjoint(a, b));
  b.c = {mpq_class(1, 2), mpq_class(1, 2)};
  EXPECT_FALSE(hsets_disjoint(a, b));
}

// Case 3: Henon at a = 6, b = 3/10.
std::optional<Box2> henon(const Box2& p) {
  return Box2{1 - q(6) * (p[0] * p[0]) + p[1], q(3, 10) * p[0]};
}

TEST(Covering, HenonFullHorseshoeAtA6) {
  const std::vector<HSet2> sets = {
      hset_rectangle(mpq_class(3, 20), mpq_class(3, 5), mpq_class(-1, 5), mpq_class(1, 5)),
      hset_rectangle(mpq_class(-3, 5), mpq_class(-3, 20), mpq_class(-1, 5), mpq_class(1, 5))};
  const HorseshoeResult r = check_horseshoe(henon, sets, 1);
  ASSERT_TRUE(r.disjoint);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_TRUE(r.coverings[i][j].proved) << i << " => " << j << ": " << r.coverings[i][j].message;
  EXPECT_TRUE(r.entropy.horseshoe);
  expect_bound_below(r.entropy.bound, log2_256(), 1e-12);
}

// Case 4: failures.
TEST(Covering, ContractionDoesNotStretchAcross) {
  const HSet2 n = hset_rectangle(-1, 1, -1, 1);
  const BoxMap2 half = [](const Box2& p) -> std::optional<Box2> { return Box2{p[0] / 2, p[1] / 2}; };
  const CoveringResult c = check_covering(half, n, n);
  EXPECT_FALSE(c.proved);
  EXPECT_EQ(c.failure, CoveringFailure::left_edge) << c.message;
  EXPECT_EQ(c.sign, 0);
  EXPECT_EQ(c.pieces, 64);
  ASSERT_TRUE(c.image.has_value());
  EXPECT_TRUE((*c.image)[0].contains(q(-1, 2)));
}

TEST(Covering, ExpansionLeavesThroughTheStableSide) {
  const HSet2 n = hset_rectangle(-1, 1, -1, 1);
  const BoxMap2 triple = [](const Box2& p) -> std::optional<Box2> { return Box2{p[0] * 3, p[1] * 3}; };
  const CoveringResult c = check_covering(triple, n, n);
  EXPECT_FALSE(c.proved);
  EXPECT_EQ(c.failure, CoveringFailure::stable_side) << c.message;
  // The failing piece maps into the strip |y_u| <= 1: its x_u meets [-1/3, 1/3], and its
  // image reaches |y_s| >= 1.
  EXPECT_LE(c.piece[0], mpq_class(1, 3));
  EXPECT_GE(c.piece[1], mpq_class(-1, 3));
  ASSERT_TRUE(c.image.has_value());
  EXPECT_FALSE(certainly_above((*c.image)[1], -1, 1) && certainly_below((*c.image)[1], 1, 1));
}

TEST(Covering, TranslationPutsBothEdgesOnOneSide) {
  const HSet2 n = hset_rectangle(-1, 1, -1, 1);
  const BoxMap2 shift = [](const Box2& p) -> std::optional<Box2> { return Box2{p[0] * 3 + 10, p[1] / 2}; };
  const CoveringResult c = check_covering(shift, n, n);
  EXPECT_FALSE(c.proved);
  EXPECT_EQ(c.failure, CoveringFailure::same_side) << c.message;
  EXPECT_EQ(c.pieces, 1);  // decided at once: no subdivision changes it
}

TEST(Covering, UndecidedBranchIsNotAProof) {
  // N = [3/10, 11/20] x [0, 1] reaches over the branch line x = 1/2. Its edges map to x = 9/10
  // and x = 27/20, on either side of M = [1, 6/5] x [-1/10, 11/10], so (a) holds; (b) needs
  // the pieces of N, and those meeting x = 1/2 are undecided at every subdivision.
  const HSet2 across_the_line = hset_rectangle(mpq_class(3, 10), mpq_class(11, 20), 0, 1);
  const HSet2 m = hset_rectangle(1, mpq_class(6, 5), mpq_class(-1, 10), mpq_class(11, 10));
  const CoveringResult c = check_covering(horseshoe, across_the_line, m, {kBits, 16});
  EXPECT_FALSE(c.proved);
  EXPECT_EQ(c.failure, CoveringFailure::undecided) << c.message;
  EXPECT_EQ(c.pieces, 16);
  const mpq_class line(3, 5);  // x = 1/2 in N's local coordinates: x_u = (x - 17/40) / (1/8)
  EXPECT_LE(c.piece[0], line);
  EXPECT_GE(c.piece[1], line);
}

TEST(Covering, SingularHSet) {
  HSet2 flat = hset_rectangle(0, 1, 0, 1);
  flat.B[1][1] = 0;
  const CoveringResult c = check_covering(horseshoe, flat, horseshoe_sets()[0]);
  EXPECT_FALSE(c.proved);
  EXPECT_EQ(c.failure, CoveringFailure::singular_hset);
}

// Case 5: transition matrices.
TEST(Covering, GoldenMeanShift) {
  const EntropyBound e = entropy_lower_bound({{1, 1}, {1, 0}}, 1);
  EXPECT_TRUE(e.horseshoe);
  // q <= phi exactly: (2q - 1)^2 <= 5 with 2q - 1 >= 0.
  const mpq_class t = 2 * e.quotient - 1;
  EXPECT_GE(t, 0);
  EXPECT_LE(t * t, 5);
  const Mpfi phi = (sqrt(Mpfi(5, 256)) + 1) / 2;
  expect_bound_below(e.bound, log(phi), 1e-9);
}

TEST(Covering, PowerOfTheMapDividesTheBound) {
  // Full 2-shift of F^2: h_top(F) >= log(2) / 2.
  const EntropyBound e = entropy_lower_bound({{1, 1}, {1, 1}}, 2);
  expect_bound_below(e.bound, log2_256() / 2, 1e-12);
}

TEST(Covering, ReducibleMatricesAndCycles) {
  // A zero row and a transient set do not spoil the bound of the component {0, 1}.
  const EntropyBound a = entropy_lower_bound({{1, 1, 1}, {1, 1, 0}, {0, 0, 0}}, 1);
  EXPECT_TRUE(a.horseshoe);
  EXPECT_EQ(a.quotient, 2);
  EXPECT_EQ(a.component, (std::vector<int>{0, 1}));
  // One cycle (a periodic orbit): rho = 1, bound 0, no horseshoe.
  const EntropyBound b = entropy_lower_bound({{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, 1);
  EXPECT_FALSE(b.horseshoe);
  EXPECT_EQ(b.quotient, 1);
  EXPECT_EQ(b.bound, "0");
  // Two self-loops joined one way: rho = 1 (Jordan block), no horseshoe.
  const EntropyBound c = entropy_lower_bound({{1, 1}, {0, 1}}, 1);
  EXPECT_FALSE(c.horseshoe);
  EXPECT_EQ(c.quotient, 1);
  // No cycle at all.
  const EntropyBound d = entropy_lower_bound({{0, 1}, {0, 0}}, 1);
  EXPECT_FALSE(d.horseshoe);
  EXPECT_EQ(d.bound, "-inf");
}

TEST(Covering, OverlappingHSetsGiveNoEntropy) {
  std::vector<HSet2> sets = horseshoe_sets();
  sets[1] = hset_rectangle(mpq_class(1, 3), mpq_class(31, 30), mpq_class(-1, 10), mpq_class(11, 10));
  const HorseshoeResult r = check_horseshoe(horseshoe, sets, 1, {kBits, 4});
  EXPECT_FALSE(r.disjoint);
  EXPECT_FALSE(r.entropy.horseshoe);
}

// Case 6: the period-2 saddle of the velocity-dependent bouncer at c = 1000, a = 27.
mpq_class dec(const char* text) { return Decimal::parse(text)->value(); }

HSet2 period2_hset() {
  HSet2 n;
  n.c = {dec("0.0905229578316182"), dec("10.85655768412576")};
  n.B = {{{dec("0.000013129"), dec("0.0000517543")}, {dec("-0.000999914"), dec("-0.00099866")}}};
  return n;
}

TEST(Covering, VeldepPeriod2SaddleCoversItselfUnderF2) {
  const ModelSpec spec = test_support::spec(Law::veldep, "27", "1", "1000");
  const HSet2 n = period2_hset();
  const auto branch = impact_branch(spec, 2, kBits, n.c[0], n.c[1]);
  ASSERT_EQ(branch.size(), 2u);
  EXPECT_EQ(branch_text(branch), "I1+0 I0+1");
  const CoveringResult c = check_covering(impact_box_map(spec, branch, kBits), n, n, {kBits, 16});
  EXPECT_TRUE(c.proved) << c.message;
  EXPECT_EQ(c.sign, -1);
  // The naive box enclosure wraps too much for (b) at this subdivision; Lohner's does not.
  const CoveringResult naive =
      check_covering(impact_box_map(spec, branch, kBits, EnclosureMethod::naive), n, n, {kBits, 16});
  EXPECT_FALSE(naive.proved);
  // A single periodic orbit: one self-covering, rho = 1, no horseshoe.
  const EntropyBound e = entropy_lower_bound({{1}}, 2);
  EXPECT_FALSE(e.horseshoe);
  EXPECT_EQ(e.bound, "0");
}

TEST(Covering, PiecesAsParallelogramsRoundTrip) {
  // A piece of a tilted h-set as c + B r, taken back to the h-set's local coordinates:
  // it contains the piece and is no wider than it by more than the rounding.
  const HSet2 h = sheared(horseshoe_sets()[1]);
  const mpq_class lo[2] = {mpq_class(-1, 4), mpq_class(1, 2)}, hi[2] = {mpq_class(1, 8), mpq_class(1, 2)};
  const auto y = hset_local(h, hset_piece(h, lo[0], hi[0], lo[1], hi[1], kBits));
  ASSERT_TRUE(y.has_value());
  for (int i = 0; i < 2; ++i) {
    EXPECT_TRUE((*y)[i].contains(enclose(lo[i], hi[i], kBits))) << i;
    const Mpfr w = (*y)[i].width();
    mpq_class wq;
    mpfr_get_q(wq.get_mpq_t(), w.get());
    EXPECT_LT(wq - (hi[i] - lo[i]), mpq_class(1, 1000000000) / mpq_class("1000000000000000000000")) << i;
  }
}

TEST(Covering, VeldepPeriod2SaddleOnParallelograms) {
  const ModelSpec spec = test_support::spec(Law::veldep, "27", "1", "1000");
  HSet2 n = period2_hset();
  const auto branch = impact_branch(spec, 2, kBits, n.c[0], n.c[1]);
  const CoveringResult c = check_covering(impact_set_map(spec, branch, kBits), n, n);
  EXPECT_TRUE(c.proved) << c.message;
  EXPECT_EQ(c.sign, -1);
  EXPECT_EQ(c.pieces, 1);
  // Thin: the stable column 1000 times shorter.
  for (int i = 0; i < 2; ++i) n.B[i][1] /= 1000;
  const CoveringResult thin = check_covering(impact_set_map(spec, branch, kBits), n, n);
  EXPECT_TRUE(thin.proved) << thin.message;
  const CoveringResult boxed = check_covering(impact_box_map(spec, branch, kBits), n, n, {kBits, 16});
  EXPECT_FALSE(boxed.proved);
  EXPECT_EQ(boxed.failure, CoveringFailure::stable_side) << boxed.message;
}

TEST(Covering, VeldepPeriod2SaddleWrongFrameOrBranchFails) {
  const ModelSpec spec = test_support::spec(Law::veldep, "27", "1", "1000");
  HSet2 swapped = period2_hset();
  std::swap(swapped.B[0][0], swapped.B[0][1]);
  std::swap(swapped.B[1][0], swapped.B[1][1]);
  const auto branch = impact_branch(spec, 2, kBits, swapped.c[0], swapped.c[1]);
  const CoveringResult c = check_covering(impact_box_map(spec, branch, kBits), swapped, swapped, {kBits, 16});
  EXPECT_FALSE(c.proved);
  EXPECT_EQ(c.failure, CoveringFailure::left_edge) << c.message;
  auto other = branch;
  other[0].periods += 1;
  const HSet2 n = period2_hset();
  const CoveringResult u = check_covering(impact_box_map(spec, other, kBits), n, n, {kBits, 4});
  EXPECT_EQ(u.failure, CoveringFailure::undecided) << u.message;
}

}  // namespace
}  // namespace bouncer
