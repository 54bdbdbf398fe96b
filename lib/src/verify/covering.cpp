// Covering relations in the plane and the entropy bound (verify/covering.hpp says what is
// proved and the reference).
#include "bouncer/verify/covering.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bouncer/scalar/decimal.hpp"
#include "bouncer/scalar/traits.hpp"
#include "bouncer/verify/enclosure.hpp"

namespace bouncer {

namespace {

using Mat2 = std::array<std::array<mpq_class, 2>, 2>;

mpq_class det(const Mat2& B) { return B[0][0] * B[1][1] - B[0][1] * B[1][0]; }

std::optional<Mat2> inverse(const Mat2& B) {
  const mpq_class d = det(B);
  if (d == 0) return std::nullopt;
  Mat2 R;
  R[0][0] = B[1][1] / d;
  R[0][1] = -B[0][1] / d;
  R[1][0] = -B[1][0] / d;
  R[1][1] = B[0][0] / d;
  return R;
}

Mpfi point(const mpq_class& q, long bits) { return enclose(q, q, bits); }

// Certainly < -1: -1; certainly > 1: +1; else 0 (also for NaN).
int side(const Mpfi& yu) {
  if (yu.has_nan()) return 0;
  if (mpfr_cmp_si(&yu.get()->right, -1) < 0) return -1;
  if (mpfr_cmp_si(&yu.get()->left, 1) > 0) return 1;
  return 0;
}

// Certainly -1 < y_s < 1.
bool inside_stable(const Mpfi& ys) {
  if (ys.has_nan()) return false;
  return mpfr_cmp_si(&ys.get()->left, -1) > 0 && mpfr_cmp_si(&ys.get()->right, 1) < 0;
}

std::string text(const Mpfi& x) { return ScalarTraits<Mpfi>::to_string(x); }

std::string piece_text(const std::array<mpq_class, 4>& p) {
  auto one = [](const mpq_class& lo, const mpq_class& hi) {
    return lo == hi ? "= " + exact_decimal(lo) : "in [" + exact_decimal(lo) + ", " + exact_decimal(hi) + "]";
  };
  return "x_u " + one(p[0], p[1]) + ", x_s " + one(p[2], p[3]);
}

// The ends of the k-th of n equal pieces of [-1, 1].
std::pair<mpq_class, mpq_class> cut(int k, int n) {
  mpq_class lo(2 * k, n), hi(2 * (k + 1), n);
  lo -= 1;
  hi -= 1;
  lo.canonicalize();
  hi.canonicalize();
  return {lo, hi};
}

// One condition's check at one subdivision: the first failing piece, if any.
struct Failure {
  CoveringFailure kind = CoveringFailure::none;
  std::array<mpq_class, 4> piece;
  std::optional<Box2> image;
};

}  // namespace

const char* name(CoveringFailure f) {
  switch (f) {
    case CoveringFailure::none: return "none";
    case CoveringFailure::singular_hset: return "singular_hset";
    case CoveringFailure::undecided: return "undecided";
    case CoveringFailure::left_edge: return "left_edge";
    case CoveringFailure::right_edge: return "right_edge";
    case CoveringFailure::same_side: return "same_side";
    case CoveringFailure::stable_side: return "stable_side";
  }
  return "?";
}

HSet2 hset_rectangle(const mpq_class& x_lo, const mpq_class& x_hi, const mpq_class& y_lo, const mpq_class& y_hi) {
  HSet2 h;
  h.c[0] = (x_lo + x_hi) / 2;
  h.c[1] = (y_lo + y_hi) / 2;
  h.B[0][0] = (x_hi - x_lo) / 2;
  h.B[0][1] = 0;
  h.B[1][0] = 0;
  h.B[1][1] = (y_hi - y_lo) / 2;
  return h;
}

Box2 hset_box(const HSet2& N, const mpq_class& xu_lo, const mpq_class& xu_hi, const mpq_class& xs_lo,
              const mpq_class& xs_hi, long bits) {
  // c_i + B_i0 x_u + B_i1 x_s is linear: its range over the rectangle is exact in rationals.
  Box2 out{Mpfi(bits), Mpfi(bits)};
  for (int i = 0; i < 2; ++i) {
    const mpq_class a = N.B[i][0] * xu_lo, b = N.B[i][0] * xu_hi;
    const mpq_class c = N.B[i][1] * xs_lo, d = N.B[i][1] * xs_hi;
    const mpq_class lo = N.c[i] + std::min(a, b) + std::min(c, d);
    const mpq_class hi = N.c[i] + std::max(a, b) + std::max(c, d);
    out[i] = enclose(lo, hi, bits);
  }
  return out;
}

std::optional<Box2> hset_local(const HSet2& M, const Box2& p) {
  const auto inv = inverse(M.B);
  if (!inv) return std::nullopt;
  const long bits = std::max(p[0].bits(), p[1].bits());
  const Mpfi d0 = p[0] - point(M.c[0], bits);
  const Mpfi d1 = p[1] - point(M.c[1], bits);
  Box2 y{Mpfi(bits), Mpfi(bits)};
  for (int r = 0; r < 2; ++r) y[r] = point((*inv)[r][0], bits) * d0 + point((*inv)[r][1], bits) * d1;
  return y;
}

namespace {

// check_covering over `image_of(piece, bits)`: the image of a piece of N in M's local
// coordinates, or nullopt.
template <class ImageOf>
CoveringResult check_covering_with(const ImageOf& image_of, const HSet2& N, const HSet2& M, const CoveringOptions& options) {
  CoveringResult result;
  if (det(N.B) == 0 || det(M.B) == 0) {
    result.failure = CoveringFailure::singular_hset;
    result.message = std::string("not an h-set: B of ") + (det(N.B) == 0 ? "N" : "M") + " is singular";
    return result;
  }
  const long bits = options.bits;
  const int max_pieces = std::max(1, options.max_pieces);
  bool left_done = false, right_done = false, across_done = false;
  int left_side = 0, right_side = 0;

  // The image of a piece of N in M's local coordinates (nullopt: the map refused it).
  auto image = [&](const std::array<mpq_class, 4>& p) -> std::optional<Box2> {
    ++result.boxes;
    return image_of(p, bits);
  };
  // Condition (a) on one edge (x_u = xu) at n pieces: the common side, or the failure.
  auto edge = [&](const mpq_class& xu, int n, CoveringFailure kind, int& side_out) -> Failure {
    int common = 0;
    for (int j = 0; j < n; ++j) {
      const auto [lo, hi] = cut(j, n);
      const std::array<mpq_class, 4> p{xu, xu, lo, hi};
      const auto y = image(p);
      if (!y) return {CoveringFailure::undecided, p, std::nullopt};
      const int s = side((*y)[0]);
      if (s == 0) return {kind, p, y};
      if (common != 0 && s != common) return {CoveringFailure::same_side, p, y};
      common = s;
    }
    side_out = common;
    return {};
  };
  // Condition (b) at n x n pieces.
  auto across = [&](int n) -> Failure {
    for (int i = 0; i < n; ++i) {
      const auto [ulo, uhi] = cut(i, n);
      for (int j = 0; j < n; ++j) {
        const auto [slo, shi] = cut(j, n);
        const std::array<mpq_class, 4> p{ulo, uhi, slo, shi};
        const auto y = image(p);
        if (!y) return {CoveringFailure::undecided, p, std::nullopt};
        if (side((*y)[0]) == 0 && !inside_stable((*y)[1])) return {CoveringFailure::stable_side, p, y};
      }
    }
    return {};
  };

  Failure last;
  for (int n = 1;; n = std::min(4 * n, max_pieces)) {
    result.pieces = n;
    last = {};
    if (!left_done) {
      Failure f = edge(mpq_class(-1), n, CoveringFailure::left_edge, left_side);
      if (f.kind == CoveringFailure::none) left_done = true; else last = f;
    }
    if (!right_done) {
      Failure f = edge(mpq_class(1), n, CoveringFailure::right_edge, right_side);
      if (f.kind == CoveringFailure::none) right_done = true; else if (last.kind == CoveringFailure::none) last = f;
    }
    if (left_done && right_done && left_side == right_side) {
      // Both edges certainly on one side of M: no subdivision changes that.
      result.failure = CoveringFailure::same_side;
      result.piece = {mpq_class(-1), mpq_class(1), mpq_class(-1), mpq_class(1)};
      result.message = std::string("not a covering: the images of both edges of N lie certainly ") +
                       (left_side < 0 ? "left of M (y_u < -1)" : "right of M (y_u > 1)") +
                       ": F does not stretch N across M";
      return result;
    }
    if (!across_done) {
      Failure f = across(n);
      if (f.kind == CoveringFailure::none) across_done = true; else if (last.kind == CoveringFailure::none) last = f;
    }
    if (left_done && right_done && across_done) {
      result.proved = true;
      result.sign = left_side < 0 ? 1 : -1;
      std::ostringstream s;
      s << "N => M proved, sign " << (result.sign > 0 ? "+1" : "-1") << " (left edge to the "
        << (result.sign > 0 ? "left" : "right") << " of M), at up to " << n << " pieces per side, "
        << result.boxes << " boxes, " << bits << " bits";
      result.message = s.str();
      return result;
    }
    if (n >= max_pieces) break;
  }
  result.failure = last.kind;
  result.piece = last.piece;
  result.image = last.image;
  std::ostringstream s;
  s << "not proved at " << result.pieces << " pieces per side (" << result.boxes << " boxes, " << bits
    << " bits): ";
  const std::string where = piece_text(last.piece);
  const std::string img = last.image ? " has y_u " + text((*last.image)[0]) + ", y_s " + text((*last.image)[1]) : "";
  switch (last.kind) {
    case CoveringFailure::undecided:
      s << "the map gave no image of the box of N's piece " << where << " (a branch undecided over it, or not the map's branch)";
      break;
    case CoveringFailure::left_edge:
    case CoveringFailure::right_edge:
      s << "condition (a): the image of the " << (last.kind == CoveringFailure::left_edge ? "left" : "right")
        << " edge's piece " << where << img << ", not certainly < -1 or > 1";
      break;
    case CoveringFailure::same_side:
      s << "condition (a): pieces of one edge map to both sides of M; the piece " << where << img;
      break;
    case CoveringFailure::stable_side:
      s << "condition (b): the image of N's piece " << where << img
        << ", which may meet M's entry set {|y_u| <= 1, |y_s| >= 1}";
      break;
    default:
      break;
  }
  result.message = s.str();
  return result;
}

// check_covering_with for F given on the pieces of N as `piece_of` hands them over (hset_box:
// the box around the piece; hset_piece: the piece itself), its images taken to M's local
// coordinates (hset_local of a box or of a parallelogram).
template <class Map, class PieceOf>
CoveringResult check_mapped(const Map& F, PieceOf piece_of, const HSet2& N, const HSet2& M, const CoveringOptions& options) {
  return check_covering_with(
      [&](const std::array<mpq_class, 4>& p, long bits) -> std::optional<Box2> {
        const auto y = F(piece_of(N, p[0], p[1], p[2], p[3], bits));
        if (!y) return std::nullopt;
        return hset_local(M, *y);
      },
      N, M, options);
}

}  // namespace

CoveringResult check_covering(const BoxMap2& F, const HSet2& N, const HSet2& M, const CoveringOptions& options) {
  return check_mapped(F, hset_box, N, M, options);
}

CoveringResult check_covering(const SetMap2& F, const HSet2& N, const HSet2& M, const CoveringOptions& options) {
  return check_mapped(F, hset_piece, N, M, options);
}

namespace {

// The exact rational value of a finite MPFR number (nullopt for NaN or infinity).
std::optional<mpq_class> exact(const Mpfr& x) {
  if (!mpfr_number_p(x.get())) return std::nullopt;
  mpq_class q;
  mpfr_get_q(q.get_mpq_t(), x.get());
  return q;
}

Mpfr rounded(const mpq_class& q, long bits) {
  Mpfr r(bits);
  mpfr_set_q(r.get(), q.get_mpq_t(), MPFR_RNDN);
  return r;
}

}  // namespace

Parallelogram hset_piece(const HSet2& N, const mpq_class& xu_lo, const mpq_class& xu_hi, const mpq_class& xs_lo,
                         const mpq_class& xs_hi, long bits) {
  Parallelogram out;
  const mpq_class mu = (xu_lo + xu_hi) / 2, ms = (xs_lo + xs_hi) / 2;
  std::array<mpq_class, 2> centre;
  Mat2 Bp;
  for (int i = 0; i < 2; ++i) {
    centre[i] = N.c[i] + N.B[i][0] * mu + N.B[i][1] * ms;
    out.c[i] = rounded(centre[i], bits);
    for (int j = 0; j < 2; ++j) {
      out.B[i][j] = rounded(N.B[i][j], bits);
      Bp[i][j] = *exact(out.B[i][j]);
    }
  }
  // r = Bp^-1 (c_N - c') + Bp^-1 B_N x over the piece's x: affine, so its exact range.
  const auto inv = inverse(Bp);
  if (!inv) {
    for (auto& r : out.r) r = Mpfi(bits);  // NaN: the piece cannot be represented
    return out;
  }
  std::array<mpq_class, 2> d0;
  for (int i = 0; i < 2; ++i) d0[i] = N.c[i] - *exact(out.c[i]);
  const mpq_class lo[2] = {xu_lo, xs_lo}, hi[2] = {xu_hi, xs_hi};
  for (int i = 0; i < 2; ++i) {
    mpq_class base = (*inv)[i][0] * d0[0] + (*inv)[i][1] * d0[1];
    mpq_class rlo = base, rhi = base;
    for (int j = 0; j < 2; ++j) {
      const mpq_class k = (*inv)[i][0] * N.B[0][j] + (*inv)[i][1] * N.B[1][j];
      const mpq_class a = k * lo[j], b = k * hi[j];
      rlo += std::min(a, b);
      rhi += std::max(a, b);
    }
    out.r[i] = enclose(rlo, rhi, bits);
  }
  return out;
}

std::optional<Box2> hset_local(const HSet2& M, const Parallelogram& p) {
  const auto inv = inverse(M.B);
  if (!inv) return std::nullopt;
  const long bits = std::max(p.r[0].bits(), p.r[1].bits());
  std::array<mpq_class, 2> c;
  Mat2 B;
  for (int i = 0; i < 2; ++i) {
    const auto ci = exact(p.c[i]);
    if (!ci) return std::nullopt;
    c[i] = *ci - M.c[i];
    for (int j = 0; j < 2; ++j) {
      const auto bij = exact(p.B[i][j]);
      if (!bij) return std::nullopt;
      B[i][j] = *bij;
    }
  }
  Box2 y{Mpfi(bits), Mpfi(bits)};
  for (int r = 0; r < 2; ++r) {
    const mpq_class e = (*inv)[r][0] * c[0] + (*inv)[r][1] * c[1];
    y[r] = point(e, bits);
    for (int j = 0; j < 2; ++j) {
      const mpq_class k = (*inv)[r][0] * B[0][j] + (*inv)[r][1] * B[1][j];
      y[r] += point(k, bits) * p.r[j];
    }
  }
  return y;
}

bool hsets_disjoint(const HSet2& a, const HSet2& b) {
  auto vertices = [](const HSet2& h) {
    std::vector<std::array<mpq_class, 2>> v;
    for (int su : {-1, 1})
      for (int ss : {-1, 1}) v.push_back({h.c[0] + su * h.B[0][0] + ss * h.B[0][1], h.c[1] + su * h.B[1][0] + ss * h.B[1][1]});
    return v;
  };
  const auto va = vertices(a), vb = vertices(b);
  auto range = [](const std::vector<std::array<mpq_class, 2>>& v, const mpq_class& n0, const mpq_class& n1) {
    mpq_class lo = v[0][0] * n0 + v[0][1] * n1, hi = lo;
    for (const auto& p : v) {
      const mpq_class t = p[0] * n0 + p[1] * n1;
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    return std::pair{lo, hi};
  };
  // Separating-axis test: two convex polygons are disjoint iff the projections on one of
  // their edges' normals are (closed sets: strictly).
  for (const HSet2* h : {&a, &b}) {
    for (int col = 0; col < 2; ++col) {
      const mpq_class n0 = -h->B[1][col], n1 = h->B[0][col];
      if (n0 == 0 && n1 == 0) continue;
      const auto [alo, ahi] = range(va, n0, n1);
      const auto [blo, bhi] = range(vb, n0, n1);
      if (ahi < blo || bhi < alo) return true;
    }
  }
  return false;
}

EntropyBound entropy_lower_bound(const std::vector<std::vector<int>>& A, int k, long bits, int digits) {
  EntropyBound out;
  const int m = static_cast<int>(A.size());
  // Reachability (transitive closure; m is the number of h-sets, small).
  std::vector<std::vector<char>> reach(m, std::vector<char>(m, 0));
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) reach[i][j] = A[i][j] != 0;
  for (int via = 0; via < m; ++via)
    for (int i = 0; i < m; ++i)
      if (reach[i][via])
        for (int j = 0; j < m; ++j)
          if (reach[via][j]) reach[i][j] = 1;
  std::vector<int> done(m, 0);
  out.quotient = 0;
  for (int i = 0; i < m; ++i) {
    if (done[i] || !reach[i][i]) continue;  // not on a cycle: a trivial component
    std::vector<int> comp;
    for (int j = 0; j < m; ++j)
      if (reach[i][j] && reach[j][i]) {
        comp.push_back(j);
        done[j] = 1;
      }
    const int c = static_cast<int>(comp.size());
    long edges = 0;
    for (int a : comp)
      for (int b : comp) edges += A[a][b] != 0;
    if (edges > c) out.horseshoe = true;  // strongly connected and not one simple cycle: rho > 1
    // The Perron vector of the component's submatrix A', by power iteration on A' + I
    // (primitive, so it converges; same eigenvector), in doubles.
    std::vector<double> x(c, 1.0);
    for (int it = 0; it < 2000; ++it) {
      std::vector<double> y(x);
      for (int r = 0; r < c; ++r)
        for (int s = 0; s < c; ++s)
          if (A[comp[r]][comp[s]]) y[r] += x[s];
      const double top = *std::max_element(y.begin(), y.end());
      double change = 0;
      for (int r = 0; r < c; ++r) {
        change = std::max(change, std::fabs(y[r] / top - x[r]));
        x[r] = y[r] / top;
      }
      if (change == 0) break;
    }
    // Exact from here: x as rationals (doubles are exact rationals), every entry > 0, and
    // q = min_r (A' x)_r / x_r <= rho(A') <= rho(A) (Collatz-Wielandt).
    std::vector<mpq_class> xq(c);
    for (int r = 0; r < c; ++r) xq[r] = (std::isfinite(x[r]) && x[r] > 0) ? mpq_class(x[r]) : mpq_class(1);
    mpq_class q;
    for (int r = 0; r < c; ++r) {
      mpq_class ax = 0;
      for (int s = 0; s < c; ++s)
        if (A[comp[r]][comp[s]]) ax += xq[s];
      const mpq_class t = ax / xq[r];
      if (r == 0 || t < q) q = t;
    }
    if (out.component.empty() || q > out.quotient) {
      out.quotient = q;
      out.component = comp;
    }
  }
  if (out.quotient <= 0) {
    out.bound = "-inf";
    out.bound_double = -INFINITY;
    return out;
  }
  // log is increasing: log of q rounded down, rounded down, is <= log q; so is its quotient
  // by k rounded down.
  Mpfr v(bits);
  mpfr_set_q(v.get(), out.quotient.get_mpq_t(), MPFR_RNDD);
  mpfr_log(v.get(), v.get(), MPFR_RNDD);
  mpfr_div_si(v.get(), v.get(), std::max(1, k), MPFR_RNDD);
  out.bound = mpfr_to_string_digits(v.get(), MPFR_RNDD, static_cast<size_t>(std::max(1, digits)));
  out.bound_double = mpfr_get_d(v.get(), MPFR_RNDD);
  return out;
}

namespace {

// The disjointness of all pairs and the entropy bound of the proved coverings in `out`.
void finish_horseshoe(HorseshoeResult& out, const std::vector<HSet2>& sets, int k, const CoveringOptions& options) {
  const size_t m = sets.size();
  out.disjoint = true;
  for (size_t i = 0; i < m && out.disjoint; ++i)
    for (size_t j = i + 1; j < m; ++j)
      if (!hsets_disjoint(sets[i], sets[j])) {
        out.disjoint = false;
        break;
      }
  if (out.disjoint) {
    out.entropy = entropy_lower_bound(out.matrix, k, options.bits);
  } else {
    out.entropy.bound = "not proved: the h-sets are not certainly disjoint";
    out.entropy.bound_double = -INFINITY;
  }
}

}  // namespace

HorseshoeResult check_horseshoe(const BoxMap2& G, const std::vector<HSet2>& sets, int k, const CoveringOptions& options) {
  HorseshoeResult out;
  const size_t m = sets.size();
  out.coverings.assign(m, std::vector<CoveringResult>(m));
  // Row by row: assign(m, std::vector<int>(m, 0)) draws GCC 12's false -Wfree-nonheap-object
  // at -O3 (the temporary row's inlined destructor).
  out.matrix.resize(m);
  for (std::vector<int>& row : out.matrix) row.assign(m, 0);
  for (size_t i = 0; i < m; ++i)
    for (size_t j = 0; j < m; ++j) {
      out.coverings[i][j] = check_covering(G, sets[i], sets[j], options);
      out.matrix[i][j] = out.coverings[i][j].proved ? 1 : 0;
    }
  finish_horseshoe(out, sets, k, options);
  return out;
}

HorseshoeResult check_horseshoe(const std::vector<SetMap2>& maps, const std::vector<HSet2>& sets,
                                const std::vector<CoveringEdge>& edges, int k, const CoveringOptions& options) {
  HorseshoeResult out;
  const size_t m = sets.size();
  CoveringResult unchecked;
  unchecked.message = "not checked";
  out.coverings.assign(m, std::vector<CoveringResult>(m, unchecked));
  out.matrix.assign(m, std::vector<int>(m, 0));
  for (const CoveringEdge& e : edges) {
    if (e.from < 0 || e.to < 0 || static_cast<size_t>(e.from) >= m || static_cast<size_t>(e.to) >= m ||
        static_cast<size_t>(e.from) >= maps.size())
      continue;
    CoveringResult& c = out.coverings[e.from][e.to];
    c = check_covering(maps[e.from], sets[e.from], sets[e.to], options);
    out.matrix[e.from][e.to] = c.proved ? 1 : 0;
  }
  finish_horseshoe(out, sets, k, options);
  return out;
}

}  // namespace bouncer
