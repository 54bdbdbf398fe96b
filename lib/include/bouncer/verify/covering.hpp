// Covering relations in the plane and the entropy bound they give (issue 26, first slice):
// the mathematics of a computer-assisted proof of chaos as typed library calls, for any map
// given as an interval box map. No model, certificate file or command here (later steps).
//
// h-sets. An h-set in the plane with one unstable and one stable direction is the
// parallelogram N = c + B [-1, 1]^2, c a point and B an invertible 2x2 matrix whose first
// column is the unstable direction and second the stable one, both exact rationals. A point p
// has the local coordinates (x_u, x_s) = B^-1 (p - c) (B^-1 exact, applied in interval
// arithmetic). Its left edge is x_u = -1, its right edge x_u = +1 (the exit set N^-), its
// bottom and top x_s = -1, +1 (the entry set N^+).
//
// Covering relation N => M (Zgliczynski and Gidea, "Covering relations for multidimensional
// dynamical systems", J. Differential Equations 202 (2004) 32-58: their sufficient
// condition for u = 1; CAPD's capd/covrel/HSet2D.h checkCoveringRelation2D checks the same
// conditions on grids of the edges and the set, with the left edge to the left only). With (y_u, y_s) the local coordinates of M and F continuous on N, F
// covers M when
//   * (a) F(left edge of N) lies in {y_u < -1} and F(right edge) in {y_u > 1}
//     (sign +1), or the other way round (sign -1);
//   * (b) F(N) does not meet M^+ = {|y_u| <= 1, |y_s| >= 1}: every point of F(N) has
//     |y_u| > 1 or |y_s| < 1 (CAPD's `across`).
// (b) also gives the paper's first condition, that F of a horizontal segment
// [-1, 1] x {q0} lies in the interior of {y_u < -1} u M u {y_u > 1}: where such a point has
// |y_u| <= 1 it has |y_s| < 1. The paper's conclusion: N covers M with degree `sign`, and for
// a chain of coverings N_0 => N_1 => ... every sequence of h-sets the chain allows (for
// ever, and periodically) is followed by a true orbit of F.
//
// check_covering verifies (a) and (b) by interval enclosures: it cuts N's edges into n pieces
// and N into n x n pieces (uniform in local coordinates), maps each piece with F, takes the
// image to M's local coordinates, and asks each condition of every piece's image, certainly
// (outward-rounded MPFI at `bits`). F is given either on boxes (BoxMap2: the interval box
// around the piece, whose corners wrap a tilted piece) or on parallelograms (SetMap2: the
// piece itself as c + B r, and its image as one, taken to M's coordinates as
// B_M^-1 (c' - c_M) + (B_M^-1 B') r' with both products exact: no wrapping, which thin
// h-sets along nearly parallel directions need). It tries
// n = 1, 4, 16, ... up to max_pieces; a condition once proved at some n is not asked again.
// The map may refuse a box (std::nullopt: a branch of a piecewise map not decided over it):
// then the covering is not proved. Continuity of F on N is the caller's part of the
// statement (a piecewise map is continuous on N where one branch is decided over all of N).
//
// Entropy. If N_1..N_m are pairwise disjoint h-sets and A is the 0/1 matrix of proved
// coverings N_i => N_j of G = F^k, then G restricted to the invariant set of orbits that
// follow A is semiconjugate onto the subshift of finite type of A (Zgliczynski and Gidea,
// Theorem on chains of coverings; disjointness makes the itinerary map well defined), so
// h_top(F) >= h_top(G)/k >= log(rho(A))/k. rho(A) is bounded below by the Collatz-Wielandt
// quotient min_i (A' x)_i / x_i of a positive rational vector x on the principal submatrix A'
// of one strongly connected component (rho(A) >= rho(A')), computed exactly, and its log
// rounded down with MPFR. What this proves: an invariant set of F (inside the h-sets) on which
// F has at least this entropy, with every symbolic itinerary of A realised. What it does not:
// that an attractor is that set, or that typical orbits are chaotic.
#pragma once

#include <gmpxx.h>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bouncer/scalar/mpfi.hpp"
#include "bouncer/verify/enclosure.hpp"

namespace bouncer {

// An h-set c + B [-1, 1]^2 in the plane: B's first column the unstable direction, the second
// the stable one; exact rationals (see the header comment).
struct HSet2 {
  // The centre c = (c[0], c[1]).
  std::array<mpq_class, 2> c;
  // B[row][column]: column 0 the unstable direction, column 1 the stable one.
  std::array<std::array<mpq_class, 2>, 2> B;
};

// The axis-parallel h-set [x_lo, x_hi] x [y_lo, y_hi], unstable along x (first coordinate).
HSet2 hset_rectangle(const mpq_class& x_lo, const mpq_class& x_hi, const mpq_class& y_lo, const mpq_class& y_hi);

// A box in the plane: two intervals (first and second coordinate).
using Box2 = std::array<Mpfi, 2>;

// A map given by interval enclosures: the box's image enclosure, or nullopt when it cannot
// decide (a branch of a piecewise map undecided over the box).
using BoxMap2 = std::function<std::optional<Box2>(const Box2&)>;

// A map given by enclosures of parallelograms: a piece c + B r of an h-set (c, B points, r an
// interval vector; the set contains the exact piece) to a parallelogram c' + B' r' containing
// its image (e.g. Lohner's enclosure, verify/enclosure.hpp), or nullopt as BoxMap2.
using SetMap2 = std::function<std::optional<Parallelogram>(const Parallelogram&)>;

// How hard check_covering tries.
struct CoveringOptions {
  // MPFI precision of every interval evaluation (and of the boxes handed to the map).
  long bits = 128;
  // The finest subdivision tried: pieces per side n = 1, 4, 16, ... up to this.
  int max_pieces = 64;
};

// Which condition of a covering failed (or none: proved).
enum class CoveringFailure {
  // Proved, or not tried.
  none,
  // B of N or of M is singular (det B = 0): not an h-set.
  singular_hset,
  // The map refused a box (nullopt): a branch undecided over it (or not the map's branch).
  undecided,
  // (a): a piece of the left edge's image is not certainly on one side of M (y_u < -1 or y_u > 1).
  left_edge,
  // (a): a piece of the right edge's image is not certainly on one side of M.
  right_edge,
  // (a): the edges' images are certainly on sides of M, but both on the same side (or the
  // pieces of one edge on different sides): F does not stretch N across M.
  same_side,
  // (b): an image box meets M^+ = {|y_u| <= 1, |y_s| >= 1}: it may leave through M's stable side.
  stable_side,
};

// The name of a failure ("none", "singular_hset", "undecided", "left_edge", "right_edge",
// "same_side", "stable_side").
const char* name(CoveringFailure f);

// The answer of check_covering.
struct CoveringResult {
  // The covering N => M is proved (conditions (a) and (b) of the header comment).
  bool proved = false;
  // +1: left edge to the left of M, right edge to the right; -1: swapped; 0: not proved.
  int sign = 0;
  // The condition that failed at the finest subdivision tried (none when proved).
  CoveringFailure failure = CoveringFailure::none;
  // The pieces per side of the last subdivision tried (the one that proved it, or the finest).
  int pieces = 0;
  // The number of boxes mapped over all subdivisions tried.
  long boxes = 0;
  // Where it failed: the piece of N in N's local coordinates, [x_u_lo, x_u_hi] x [x_s_lo, x_s_hi].
  std::array<mpq_class, 4> piece;
  // Its image box in M's local coordinates (y_u, y_s) (not set for undecided, singular_hset).
  std::optional<Box2> image;
  // A sentence: what was proved, or which condition failed where.
  std::string message;
};

// Checks the covering relation N => M under F (see the header comment). Never guesses: a
// condition not certainly true at the finest subdivision makes `proved` false and says which.
CoveringResult check_covering(const BoxMap2& F, const HSet2& N, const HSet2& M, const CoveringOptions& options = {});

// The same with F given on parallelograms (SetMap2; the header comment says why).
CoveringResult check_covering(const SetMap2& F, const HSet2& N, const HSet2& M, const CoveringOptions& options = {});

// The interval box c + B [x_u] x [x_s] of a piece of N given in local coordinates, at `bits`.
Box2 hset_box(const HSet2& N, const mpq_class& xu_lo, const mpq_class& xu_hi, const mpq_class& xs_lo,
              const mpq_class& xs_hi, long bits);

// The local coordinates B^-1 (p - c) of a box p in the h-set M (B^-1 exact, applied in
// interval arithmetic); nullopt if B is singular.
std::optional<Box2> hset_local(const HSet2& M, const Box2& p);

// The piece c + B [x_u] x [x_s] of N as a parallelogram c' + B' r containing it: c' the piece's
// centre and B' N's frame rounded to `bits`, r their exact difference from the piece (exact
// rationals) rounded outward.
Parallelogram hset_piece(const HSet2& N, const mpq_class& xu_lo, const mpq_class& xu_hi, const mpq_class& xs_lo,
                         const mpq_class& xs_hi, long bits);

// The local coordinates in M of a parallelogram c' + B' r': B^-1 (c' - c) + (B^-1 B') r', the
// two products exact (c', B' are exact binary fractions), then applied to r' in intervals;
// nullopt if B is singular or c', B' are not finite.
std::optional<Box2> hset_local(const HSet2& M, const Parallelogram& p);

// Whether the closed parallelograms of two h-sets are certainly disjoint (exact rational
// separating-axis test on the four edge normals).
bool hsets_disjoint(const HSet2& a, const HSet2& b);

// A certified lower bound on log(spectral radius of A) / k.
struct EntropyBound {
  // rho(A) > 1 is proved (the bound below is > 0): the coverings contain two distinct cycles
  // through one h-set, a horseshoe. Decided exactly from the graph of A (a strongly connected
  // component with more edges than vertices), not from the rounded bound.
  bool horseshoe = false;
  // The Collatz-Wielandt quotient q <= rho(A), an exact rational (0 when A has no cycle).
  mpq_class quotient;
  // The h-sets of the strongly connected component that gives q (0-based indices).
  std::vector<int> component;
  // log(q) / k rounded down, as an exact decimal text (digits below, rounded down); "-inf" when q = 0.
  std::string bound;
  // The same bound as a double rounded down (for tests and tables).
  double bound_double = 0;
};

// From a square 0/1 transition matrix A (A[i][j] = 1: N_i => N_j proved for F^k, k >= 1), the
// bound h_top(F) >= log(rho(A)) / k (header comment: this needs the h-sets pairwise disjoint,
// see hsets_disjoint). The quotient is exact; its log and the division by k are rounded down
// at `bits`; the text has `digits` significant digits, rounded down.
EntropyBound entropy_lower_bound(const std::vector<std::vector<int>>& A, int k, long bits = 128, int digits = 20);

// A horseshoe from h-sets: every covering N_i => N_j of G = F^k (G the given map) checked,
// the h-sets' disjointness checked, and the entropy bound of the proved ones.
struct HorseshoeResult {
  // coverings[i][j]: the check of N_i => N_j.
  std::vector<std::vector<CoveringResult>> coverings;
  // The 0/1 matrix of proved coverings.
  std::vector<std::vector<int>> matrix;
  // All pairs of h-sets certainly disjoint (needed for the entropy bound).
  bool disjoint = false;
  // The bound from `matrix` when `disjoint`; otherwise none (horseshoe false, bound_double
  // -inf, bound a sentence saying why).
  EntropyBound entropy;
};

// Checks every covering N_i => N_j under G = F^k (G given; k only divides the entropy) and
// bounds the entropy from the proved ones when the h-sets are pairwise disjoint.
HorseshoeResult check_horseshoe(const BoxMap2& G, const std::vector<HSet2>& sets, int k,
                                const CoveringOptions& options = {});

// One covering to check: N_from => N_to (0-based indices into the h-sets).
struct CoveringEdge {
  // The h-set covered from.
  int from = 0;
  // The h-set covered.
  int to = 0;
};

// Checks the listed coverings N_from => N_to only, each under maps[from] (one map per source
// h-set: for a piecewise map, G = F^k on the branch of N_from, so that G is continuous on
// each h-set; all of them the same G = F^k where the sets are on its branches), and bounds the
// entropy from the proved ones when the h-sets are pairwise disjoint. coverings[i][j] of an
// unlisted pair is not proved ("not checked"). The theorem of the header comment applies:
// every maps[i] must be G on N_i for one G.
HorseshoeResult check_horseshoe(const std::vector<SetMap2>& maps, const std::vector<HSet2>& sets,
                                const std::vector<CoveringEdge>& edges, int k, const CoveringOptions& options = {});

}  // namespace bouncer
