// The replay of a chaos certificate in Arb (verify/chaos_certificate.hpp).
//
// Independence. Nothing here uses MPFI, bouncer's impact map (model/), its enclosures
// (verify/enclosure.hpp) or its covering checks (verify/covering.cpp): the map is written
// again below from the model's physics (docs/model.md) over Arb balls, the covering conditions
// are asked again, the disjointness test and the spectral-radius test are this file's own. Only
// the certificate's data types (exact rationals) are shared. The duplication is deliberate:
// a replay that called the maker's code would prove nothing about it.
//
// Images. A piece P = p + B_N r (r in a rectangle, p its centre) of N is mapped by the mean
// value form: G(P) is inside G(p) + J (B_N r), J an Arb enclosure of DG over the interval box
// X around P (forward-mode derivatives of every operation, every branch decided over all of X,
// so that G is one smooth formula on X, which is convex). In M's local coordinates:
//   y = B_M^-1 (G(p) - c_M) + (B_M^-1 J B_N) r,
// B_M^-1 exact. Unlike evaluating G on X alone, this keeps thin tilted h-sets thin.
//
// Continuity. Covering relations need G continuous on N. Every piece is checked with every
// branch decided over its closed box, and adjacent pieces share points; a question decided
// certainly on two sets with a common point has the same answer on both, so, question by
// question, every piece of N follows the same branch and G is one smooth formula on all of N.
#include "bouncer/verify/chaos_certificate.hpp"

#include <arb.h>
#include <flint/fmpq.h>

#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace bouncer {

std::string arb_library_version() {
  return std::to_string(__ARB_VERSION) + "." + std::to_string(__ARB_VERSION_MINOR) + "." +
         std::to_string(__ARB_VERSION_PATCHLEVEL);
}

const char* name(ChaosMap m) {
  switch (m) {
    case ChaosMap::impact: return "impact";
    case ChaosMap::henon: return "henon";
  }
  return "?";
}

namespace {

// The Arb precision of the replay in progress (set by replay_certificate on its thread).
thread_local slong prec = 256;

// The most evaluations of F a replay spends on refining subdivisions (io/chaos_certificate.hpp
// refuses files that ask for more at their stated subdivisions).
constexpr double kWorkBudget = 2 * 16777216.0;

// An Arb ball with value semantics.
class Ball {
 public:
  Ball() { arb_init(x_); }
  explicit Ball(const mpq_class& q) : Ball() {
    fmpq_t f;
    fmpq_init(f);
    fmpq_set_mpq(f, q.get_mpq_t());
    arb_set_fmpq(x_, f, prec);
    fmpq_clear(f);
  }
  Ball(const Ball& o) : Ball() { arb_set(x_, o.x_); }
  Ball& operator=(const Ball& o) {
    arb_set(x_, o.x_);
    return *this;
  }
  ~Ball() { arb_clear(x_); }
  arb_ptr get() { return x_; }
  arb_srcptr get() const { return x_; }
  // Widened by +-r (r >= 0 exact): the ball then contains every x + t, |t| <= r.
  Ball widened(const mpq_class& r) const {
    Ball out(*this);
    Ball e(r);
    arb_add_error(out.x_, e.x_);
    return out;
  }
  std::string text(slong digits = 12) const {
    char* s = arb_get_str(x_, digits, 0);
    std::string out(s);
    flint_free(s);
    return out;
  }

 private:
  arb_t x_;
};

Ball operator+(const Ball& a, const Ball& b) {
  Ball z;
  arb_add(z.get(), a.get(), b.get(), prec);
  return z;
}
Ball operator-(const Ball& a, const Ball& b) {
  Ball z;
  arb_sub(z.get(), a.get(), b.get(), prec);
  return z;
}
Ball operator*(const Ball& a, const Ball& b) {
  Ball z;
  arb_mul(z.get(), a.get(), b.get(), prec);
  return z;
}
Ball operator/(const Ball& a, const Ball& b) {
  Ball z;
  arb_div(z.get(), a.get(), b.get(), prec);
  return z;
}
Ball sqrt(const Ball& a) {
  Ball z;
  arb_sqrt(z.get(), a.get(), prec);
  return z;
}
Ball exp(const Ball& a) {
  Ball z;
  arb_exp(z.get(), a.get(), prec);
  return z;
}
Ball log(const Ball& a) {
  Ball z;
  arb_log(z.get(), a.get(), prec);
  return z;
}
// Certain comparisons: true only if every point of a is below every point of b.
bool less(const Ball& a, const Ball& b) { return arb_lt(a.get(), b.get()) != 0; }
bool positive(const Ball& a) { return arb_is_positive(a.get()) != 0; }
bool negative(const Ball& a) { return arb_is_negative(a.get()) != 0; }
bool finite(const Ball& a) { return arb_is_finite(a.get()) != 0; }

// A value with its gradient with respect to the two start coordinates (forward mode).
struct Dual {
  Ball v;
  std::array<Ball, 2> d;
};

Dual constant(const Ball& c) { return {c, {Ball(mpq_class(0)), Ball(mpq_class(0))}}; }
Dual operator+(const Dual& a, const Dual& b) { return {a.v + b.v, {a.d[0] + b.d[0], a.d[1] + b.d[1]}}; }
Dual operator-(const Dual& a, const Dual& b) { return {a.v - b.v, {a.d[0] - b.d[0], a.d[1] - b.d[1]}}; }
Dual operator*(const Dual& a, const Dual& b) {
  return {a.v * b.v, {a.d[0] * b.v + a.v * b.d[0], a.d[1] * b.v + a.v * b.d[1]}};
}
Dual operator*(const Ball& s, const Dual& b) { return {s * b.v, {s * b.d[0], s * b.d[1]}}; }
Dual operator/(const Dual& a, const Dual& b) {
  const Ball q = a.v / b.v;
  return {q, {(a.d[0] - q * b.d[0]) / b.v, (a.d[1] - q * b.d[1]) / b.v}};
}
Dual sqrt(const Dual& a) {
  const Ball r = sqrt(a.v);
  const Ball two_r = Ball(mpq_class(2)) * r;
  return {r, {a.d[0] / two_r, a.d[1] / two_r}};
}
Dual exp(const Dual& a) {
  const Ball e = exp(a.v);
  return {e, {e * a.d[0], e * a.d[1]}};
}
// a^p for a > 0 (the caller has decided it) and an exact rational p.
Dual pow_positive(const Dual& a, const mpq_class& p) {
  const Ball P(p);
  const Ball y = exp(P * log(a.v));
  const Ball dy = P * y / a.v;
  return {y, {dy * a.d[0], dy * a.d[1]}};
}

// Why a map evaluation stopped (a branch not decided over the box, or a case the replay does
// not cover); the message names it.
struct NotDecided {
  std::string why;
};

// The map of a certificate, over Arb: the impact map written from docs/model.md, or Henon.
class ReplayMap {
 public:
  explicit ReplayMap(const ChaosCertificate& c) : cert_(c) {
    if (c.map == ChaosMap::henon) return;
    const ModelSpec& m = c.model;
    if (m.veldep_collapse) throw NotDecided{"the replay does not implement --veldep-collapse on"};
    const std::size_t n = m.wall.knots.size();
    for (std::size_t j = 0; j < n; ++j) {
      knot_.push_back(m.wall.knots[j].value());
      height_.push_back(m.wall.heights[j].value());
    }
    knot_.push_back(1);
    height_.push_back(height_.front());
    for (std::size_t j = 0; j < n; ++j) slope_.push_back((height_[j + 1] - height_[j]) / (knot_[j + 1] - knot_[j]));
  }

  // G = F^k on (x0, x1), both duals.
  std::array<Dual, 2> iterate(std::array<Dual, 2> x) const {
    for (int i = 0; i < cert_.k; ++i) x = cert_.map == ChaosMap::henon ? henon(x) : impact(x);
    return x;
  }

 private:
  std::array<Dual, 2> henon(const std::array<Dual, 2>& p) const {
    const Ball a(cert_.henon_a.value()), b(cert_.henon_b.value());
    return {constant(Ball(mpq_class(1))) - a * (p[0] * p[0]) + p[1], b * p[0]};
  }

  // One impact: from the particle on the wall at phase theta with velocity v to the next
  // impact. Every branch (the start's segment, in which window of the wall the gap first
  // closes, a strictly positive impact speed, no sticking) decided for the whole ball, else
  // NotDecided.
  std::array<Dual, 2> impact(const std::array<Dual, 2>& s) const {
    const Dual& theta = s[0];
    const Dual& v = s[1];
    const ModelSpec& m = cert_.model;
    const std::size_t n = slope_.size();
    std::size_t j = n;
    for (std::size_t i = 0; i < n; ++i)
      if (!less(theta.v, Ball(knot_[i])) && less(theta.v, Ball(knot_[i + 1]))) j = i;
    if (j == n) throw NotDecided{"the start's wall segment (theta = " + theta.v.text() + ")"};
    const Ball a(m.a.value());
    const Ball half_a(m.a.value() / 2);
    // Window 0: from the start to the end of its segment. The gap G and the relative
    // velocity W (particle minus wall) at the window's start; the window's length L.
    Dual G = constant(Ball(mpq_class(0)));
    Dual W = v - constant(Ball(slope_[j]));
    if (!positive(W.v)) throw NotDecided{"the start's velocity is not certainly above the wall's"};
    Dual L = constant(Ball(knot_[j + 1])) - theta;
    Dual offset = theta - constant(Ball(knot_[j]));  // the window's start within its segment
    for (long window = 0; window < 10000; ++window) {
      const Dual end_gap = G + W * L - half_a * (L * L);
      if (positive(end_gap.v)) {
        // No impact in this window (the gap is concave and positive at both ends): on to
        // the next segment; the wall is continuous, so the gap carries over.
        const std::size_t next = (j + 1) % n;
        W = W - a * L + constant(Ball(slope_[j] - slope_[next]));
        G = end_gap;
        j = next;
        L = constant(Ball(knot_[j + 1] - knot_[j]));
        offset = constant(Ball(mpq_class(0)));
        continue;
      }
      if (!negative(end_gap.v))
        throw NotDecided{"whether the impact is before or after the wall's corner at theta = " + knot_[j + 1].get_str()};
      // The gap closes once in this window: at the larger root of G + W s - (a/2) s^2.
      const Dual speed = sqrt(W * W + (Ball(mpq_class(2)) * a) * G);  // relative impact speed
      if (!positive(speed.v)) throw NotDecided{"an impact speed not certainly positive (a touchdown)"};
      const Dual root = negative(W.v) ? (Ball(mpq_class(2)) * G) / (speed - W) : (W + speed) / constant(a);
      const Dual theta_next = constant(Ball(knot_[j])) + offset + root;
      Dual e;
      if (m.law == Law::elastic) {
        e = constant(Ball(mpq_class(1)));
      } else if (m.law == Law::constant) {
        e = constant(Ball(m.eps.value()));
      } else {
        const Dual ratio = speed / constant(Ball(m.c.value()));
        e = exp(constant(Ball(mpq_class(0))) - pow_positive(ratio, mpq_class(3, 5)));
      }
      const Dual relative_after = e * speed;
      if (m.law == Law::constant) {
        // Sticking (docs/model.md): the chatter collapses before the wall turns iff the
        // relative speed after the impact is at most a(1 - eps)/2 times the time left.
        const Ball left = Ball(knot_[j + 1]) - theta_next.v;
        const Ball limit = Ball((1 - m.eps.value()) / 2) * a * left;
        if (!less(limit, relative_after.v)) throw NotDecided{"sticking not excluded after an impact"};
      }
      return {theta_next, constant(Ball(slope_[j])) + relative_after};
    }
    throw NotDecided{"no impact within 10^4 wall segments (the replay does not follow longer flights)"};
  }

  const ChaosCertificate& cert_;
  std::vector<mpq_class> knot_, height_, slope_;
};

using Q2 = std::array<mpq_class, 2>;
using M2 = std::array<std::array<mpq_class, 2>, 2>;

M2 inverse(const M2& B) {
  const mpq_class det = B[0][0] * B[1][1] - B[0][1] * B[1][0];
  if (det == 0) throw std::invalid_argument("singular frame");
  return {{{B[1][1] / det, -B[0][1] / det}, {-B[1][0] / det, B[0][0] / det}}};
}

// The closed parallelograms c + B [-1, 1]^2 are disjoint: some edge normal of either separates
// their projections (exact; for convex polygons these axes decide).
bool disjoint(const HSet2& a, const HSet2& b) {
  const auto reach = [](const HSet2& h, const Q2& n) {
    mpq_class r = 0;
    for (int col = 0; col < 2; ++col) r += abs(n[0] * h.B[0][col] + n[1] * h.B[1][col]);
    return std::pair<mpq_class, mpq_class>{n[0] * h.c[0] + n[1] * h.c[1], r};
  };
  for (const HSet2* h : {&a, &b})
    for (int col = 0; col < 2; ++col) {
      const Q2 normal = {-h->B[1][col], h->B[0][col]};
      const auto [ca, ra] = reach(a, normal);
      const auto [cb, rb] = reach(b, normal);
      if (ca + ra < cb - rb || cb + rb < ca - ra) return true;
    }
  return false;
}

// rho(A) >= q for the 0/1 matrix A and a rational q > 0: else q > rho(A), and then qI - A is
// a nonsingular M-matrix, whose inverse is entrywise >= 0 (Berman and Plemmons, Nonnegative
// Matrices in the Mathematical Sciences, ch. 6, condition (N38)). So rho(A) >= q exactly when
// qI - A is singular or its inverse has a negative entry (exact Gauss-Jordan).
bool spectral_radius_at_least(const std::vector<std::vector<int>>& A, const mpq_class& q) {
  const std::size_t n = A.size();
  std::vector<std::vector<mpq_class>> m(n, std::vector<mpq_class>(2 * n));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) m[i][j] = (i == j ? q : mpq_class(0)) - A[i][j];
    m[i][n + i] = 1;
  }
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    while (pivot < n && m[pivot][col] == 0) ++pivot;
    if (pivot == n) return true;  // singular: q is an eigenvalue
    std::swap(m[pivot], m[col]);
    const mpq_class p = m[col][col];
    for (mpq_class& x : m[col]) x /= p;
    for (std::size_t r = 0; r < n; ++r) {
      if (r == col || m[r][col] == 0) continue;
      const mpq_class f = m[r][col];
      for (std::size_t k = 0; k < 2 * n; ++k)
        if (m[col][k] != 0) m[r][k] -= f * m[col][k];
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = n; j < 2 * n; ++j)
      if (m[i][j] < 0) return true;
  return false;
}

// An exact decimal text ("0.0123", "-inf") as a rational; nullopt if it is not one.
std::optional<mpq_class> decimal_value(const std::string& text) {
  const auto d = Decimal::parse(text);
  if (!d) return std::nullopt;
  return d->value();
}

// The replay of one covering N => M with `pieces` per side.
class CoveringReplay {
 public:
  CoveringReplay(const ReplayMap& map, const HSet2& N, const HSet2& M, int sign)
      : map_(map), N_(N), M_(M), Minv_(inverse(M.B)), sign_(sign) {}

  // An empty string when proved, else where it failed.
  std::string check(int pieces) const {
    const mpq_class h = mpq_class(1) / pieces;  // half-width of a piece in local coordinates
    for (int i = 0; i < pieces; ++i) {
      const mpq_class mid = -1 + (2 * i + 1) * h;
      for (int edge : {-1, 1}) {
        // Left edge (-1) to the side of sign -1 ... : y_u < -1 when sign * edge < 0.
        const auto y = image(edge, 0, mid, h);
        if (!y) return last_;
        const bool ok = sign_ * edge < 0 ? less((*y)[0], Ball(mpq_class(-1))) : less(Ball(mpq_class(1)), (*y)[0]);
        if (!ok)
          return std::string(edge < 0 ? "left" : "right") + " edge piece " + std::to_string(i) + " maps to y_u = " +
                 (*y)[0].text() + ", not certainly beyond " + (sign_ * edge < 0 ? "-1" : "+1");
      }
      for (int k = 0; k < pieces; ++k) {
        const mpq_class mid_u = -1 + (2 * k + 1) * h;
        const auto y = image(mid_u, h, mid, h);
        if (!y) return last_;
        const Ball one(mpq_class(1)), minus_one(mpq_class(-1));
        const bool outside = less(one, (*y)[0]) || less((*y)[0], minus_one);
        const bool inside = less(minus_one, (*y)[1]) && less((*y)[1], one);
        if (!outside && !inside)
          return "piece (" + std::to_string(k) + ", " + std::to_string(i) + ") maps to (y_u, y_s) = (" +
                 (*y)[0].text() + ", " + (*y)[1].text() + "), which may meet the stable side";
      }
    }
    return "";
  }

 private:
  // M's local coordinates of the image of the piece of N with centre (cu, cs) and
  // half-widths (hu, hs) in N's local coordinates (mean value form, header comment).
  std::optional<std::array<Ball, 2>> image(const mpq_class& cu, const mpq_class& hu, const mpq_class& cs,
                                           const mpq_class& hs) const {
    Q2 p;
    for (int r = 0; r < 2; ++r) p[r] = N_.c[r] + N_.B[r][0] * cu + N_.B[r][1] * cs;
    std::array<Dual, 2> X, P;
    for (int r = 0; r < 2; ++r) {
      const mpq_class radius = abs(N_.B[r][0]) * hu + abs(N_.B[r][1]) * hs;
      X[r] = constant(Ball(p[r]).widened(radius));
      P[r] = constant(Ball(p[r]));
      X[r].d[r] = P[r].d[r] = Ball(mpq_class(1));
    }
    std::array<Dual, 2> GX, GP;
    try {
      GX = map_.iterate(X);
      GP = map_.iterate(P);
    } catch (const NotDecided& e) {
      last_ = "a branch is not decided over a piece of N: " + e.why;
      return std::nullopt;
    }
    for (const Dual& d : GX)
      if (!finite(d.v) || !finite(d.d[0]) || !finite(d.d[1])) {
        last_ = "the image of a piece is not finite";
        return std::nullopt;
      }
    // y = Minv (G(p) - c_M) + (Minv J B_N) r, r = (+-hu, +-hs).
    const Ball r[2] = {Ball(mpq_class(0)).widened(hu), Ball(mpq_class(0)).widened(hs)};
    std::array<Ball, 2> y;
    for (int row = 0; row < 2; ++row) {
      Ball acc = Ball(Minv_[row][0]) * (GP[0].v - Ball(M_.c[0])) + Ball(Minv_[row][1]) * (GP[1].v - Ball(M_.c[1]));
      for (int col = 0; col < 2; ++col) {
        // (Minv J B_N)[row][col]
        Ball coef(mpq_class(0));
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j) coef = coef + Ball(Minv_[row][i]) * GX[i].d[j] * Ball(N_.B[j][col]);
        acc = acc + coef * r[col];
      }
      y[row] = acc;
    }
    return y;
  }

  const ReplayMap& map_;
  const HSet2& N_;
  const HSet2& M_;
  M2 Minv_;
  int sign_;
  mutable std::string last_;
};

// The exact end points of a ball.
std::array<mpq_class, 2> bounds(const Ball& b) {
  std::array<mpq_class, 2> out;
  arf_t e;
  arf_init(e);
  fmpq_t f;
  fmpq_init(f);
  for (int side = 0; side < 2; ++side) {
    if (side == 0) arb_get_lbound_arf(e, b.get(), prec);
    else arb_get_ubound_arf(e, b.get(), prec);
    arf_get_fmpq(f, e);
    fmpq_get_mpq(out[side].get_mpq_t(), f);
  }
  fmpq_clear(f);
  arf_clear(e);
  return out;
}

// Sets the thread's Arb precision for a scope, and at its end frees FLINT's caches of this
// thread (Arb keeps constants such as log 2 per thread; a worker thread that ends without
// flint_cleanup would leak them; they are recomputed when next needed).
struct PrecisionScope {
  explicit PrecisionScope(long bits) : saved(prec) { prec = bits; }
  ~PrecisionScope() {
    prec = saved;
    flint_cleanup();
  }
  slong saved;
};

}  // namespace

std::optional<std::array<std::array<mpq_class, 2>, 2>> replay_iterate(const ChaosCertificate& c, const mpq_class& x0,
                                                                       const mpq_class& x1, long bits) {
  const PrecisionScope scope(bits);
  try {
    const ReplayMap map(c);
    const auto y = map.iterate({constant(Ball(x0)), constant(Ball(x1))});
    if (!finite(y[0].v) || !finite(y[1].v)) return std::nullopt;
    return std::array<std::array<mpq_class, 2>, 2>{bounds(y[0].v), bounds(y[1].v)};
  } catch (const NotDecided&) {
    return std::nullopt;
  }
}

ReplayResult replay_certificate(const ChaosCertificate& c, long bits) {
  ReplayResult out;
  out.bits = bits;
  const PrecisionScope scope(bits);

  const std::size_t m = c.sets.size();
  for (std::size_t i = 0; i < m; ++i) {
    const auto& B = c.sets[i].B;
    if (B[0][0] * B[1][1] - B[0][1] * B[1][0] == 0) out.problems.push_back("h-set " + std::to_string(i) + " has a singular frame");
  }
  out.disjoint = out.problems.empty();
  for (std::size_t i = 0; i < m && out.disjoint; ++i)
    for (std::size_t j = i + 1; j < m; ++j)
      if (!disjoint(c.sets[i], c.sets[j])) {
        out.disjoint = false;
        out.problems.push_back("h-sets " + std::to_string(i) + " and " + std::to_string(j) + " may intersect");
        break;
      }

  std::optional<ReplayMap> map;
  try {
    map.emplace(c);
  } catch (const NotDecided& e) {
    out.problems.push_back(e.why);
  }
  std::vector<std::vector<int>> A(m, std::vector<int>(m, 0));
  double work = 0;  // evaluations of F so far
  for (std::size_t e = 0; e < c.coverings.size(); ++e) {
    const CertifiedCovering& cov = c.coverings[e];
    ReplayedCovering r;
    const std::string label = "covering " + std::to_string(cov.from) + " => " + std::to_string(cov.to);
    if (!map || cov.from < 0 || cov.to < 0 || std::size_t(cov.from) >= m || std::size_t(cov.to) >= m ||
        (cov.sign != 1 && cov.sign != -1) || !out.disjoint) {
      r.message = label + ": not checked";
    } else {
      const CoveringReplay replay(*map, c.sets[cov.from], c.sets[cov.to], cov.sign);
      // The stated subdivision, then 4 and 16 times finer (at most 256 per side): the mean
      // value form here is not the maker's enclosure, and its Jacobian's width over a piece
      // shrinks with the piece, so it may need more pieces.
      int used = cov.pieces;
      std::string why = replay.check(used);
      // Finer only within the budget of 2^24 evaluations of F per replay (as the file's limit).
      const auto cost = [&](double n) { return double(c.k) * (n * n + 2 * n); };
      work += cost(used);
      for (int finer = 0; finer < 2 && !why.empty() && used * 4 <= 256 && work + cost(4.0 * used) <= kWorkBudget; ++finer) {
        why = replay.check(used *= 4);
        work += cost(used);
      }
      r.proved = why.empty();
      const std::string pieces = std::to_string(used) + (used == 1 ? " piece" : " pieces") + " per side";
      r.message = label + (r.proved ? ": proved with " + pieces : ": not proved with " + pieces + ": " + why);
      if (r.proved) A[cov.from][cov.to] = 1;
    }
    if (!r.proved) out.problems.push_back(r.message);
    out.coverings.push_back(std::move(r));
  }

  // The stated bound: q <= rho(A) of the coverings proved here, and bound <= log(q) / k.
  const auto stated = decimal_value(c.entropy_bound);
  if (!stated) {
    out.problems.push_back("the stated bound '" + c.entropy_bound + "' is not a decimal");
  } else if (c.quotient <= 1 || c.k < 1) {
    out.problems.push_back("the stated quotient is not above 1: no entropy is claimed");
  } else if (!spectral_radius_at_least(A, c.quotient)) {
    out.problems.push_back("the stated quotient " + c.quotient.get_str() +
                           " is above the spectral radius of the coverings proved by the replay");
  } else {
    const Ball bound = log(Ball(c.quotient)) / Ball(mpq_class(c.k));
    out.recomputed_bound = bound.text(30);
    out.bound_holds = arb_le(Ball(*stated).get(), bound.get()) != 0;
    if (!out.bound_holds)
      out.problems.push_back("the stated bound " + c.entropy_bound + " is not certainly below log(" +
                             c.quotient.get_str() + ")/" + std::to_string(c.k) + " = " + out.recomputed_bound + " at " +
                             std::to_string(bits) + " bits (more bits may decide it)");
  }
  out.valid = out.problems.empty() && out.disjoint && out.bound_holds && !c.coverings.empty();
  if (out.valid) out.problems.push_back("valid");
  return out;
}

}  // namespace bouncer
