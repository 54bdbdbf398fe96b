// The Krawczyk operator for sparse systems (sparse_krawczyk.hpp).
#include "sparse_krawczyk.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "bouncer/scalar/interval_double.hpp"
#include "bouncer/scalar/traits.hpp"

namespace bouncer::detail {

namespace {
Mpfi thin(const Mpfr& x) { return Mpfi(x, x); }
}  // namespace

Preconditioner::Preconditioner(const SparseColumns& cols, long bits) : n_(cols.size()) {
  const size_t n = n_;
  if (n > 3) {
    const auto N = static_cast<Eigen::Index>(n);
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(N, N);
    for (size_t c = 0; c < n; ++c)
      for (const auto& [r, v] : cols[c]) M(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) += v.mid().to_double();
    // Equilibrated by powers of two (exact): rows, then columns, to largest entry in [1, 2).
    // The determinant row of a period doubling or fold carries the product of Q steps'
    // derivatives (1e-14 beside the orbit rows' O(1) for a contracting period 82), which
    // alone makes LU in double lose the inverse. inv(M) = T inv(S M T) S for diagonal S, T.
    Eigen::VectorXd S = Eigen::VectorXd::Ones(N), T = S;
    const auto power = [](double largest) { return largest > 0 && std::isfinite(largest) ? std::ldexp(1.0, -std::ilogb(largest)) : 1.0; };
    for (Eigen::Index r = 0; r < N; ++r) {
      S(r) = power(M.row(r).cwiseAbs().maxCoeff());
      M.row(r) *= S(r);
    }
    for (Eigen::Index c = 0; c < N; ++c) {
      T(c) = power(M.col(c).cwiseAbs().maxCoeff());
      M.col(c) *= T(c);
    }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
    const Eigen::MatrixXd inv = T.asDiagonal() * lu.inverse() * S.asDiagonal();
    if (!inv.allFinite()) throw KrawczykFailure("the midpoint Jacobian of the system is singular");
    // (An ill-conditioned C is not unsound: the Krawczyk operator then fails to contract.)
    fast_.resize(n * n);
    for (size_t r = 0; r < n; ++r)
      for (size_t c = 0; c < n; ++c) fast_[r * n + c] = inv(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
    return;
  }
  std::vector<std::vector<Mpfi>> A(n, std::vector<Mpfi>(n, Mpfi(0, bits)));
  for (size_t c = 0; c < n; ++c)
    for (const auto& [r, v] : cols[c]) A[r][c] += v;
  for (auto& row : A)
    for (Mpfi& x : row) x = thin(x.mid());
  std::vector<std::vector<Mpfi>> B(n, std::vector<Mpfi>(n, Mpfi(0, bits)));
  for (size_t i = 0; i < n; ++i) B[i][i] = Mpfi(1, bits);
  for (size_t c = 0; c < n; ++c) {
    size_t piv = c;
    for (size_t r = c + 1; r < n; ++r)
      if (std::fabs(A[r][c].mid().to_double()) > std::fabs(A[piv][c].mid().to_double())) piv = r;
    std::swap(A[c], A[piv]);
    std::swap(B[c], B[piv]);
    if (ScalarTraits<Mpfi>::is_zero(A[c][c]) != Truth::no) throw KrawczykFailure("the midpoint Jacobian of the system is singular");
    const Mpfi d = A[c][c];
    for (size_t k = 0; k < n; ++k) {
      A[c][k] /= d;
      B[c][k] /= d;
    }
    for (size_t r = 0; r < n; ++r) {
      if (r == c) continue;
      const Mpfi f = A[r][c];
      for (size_t k = 0; k < n; ++k) {
        A[r][k] -= f * A[c][k];
        B[r][k] -= f * B[c][k];
      }
    }
  }
  for (auto& row : B)
    for (Mpfi& x : row) x = thin(x.mid());
  precise_ = std::move(B);
}

void Preconditioner::mul(size_t r, size_t c, const Mpfi& x, Mpfi& out) const {
  if (!fast_.empty())
    mpfi_mul_d(out.get(), x.get(), fast_[r * n_ + c]);
  else
    mpfi_mul(out.get(), precise_[r][c].get(), x.get());
}

namespace {

// The outward double enclosure of an MPFI interval (each end rounded outward; beyond the
// double range an end is +-inf, and the image is then not finite: a failure, never a proof).
DoubleInterval to_double(const Mpfi& x) {
  return DoubleInterval(mpfr_get_d(x.lower().get(), MPFR_RNDD), mpfr_get_d(x.upper().get(), MPFR_RNDU));
}
Mpfi to_mpfi(const DoubleInterval& x, long bits) {
  Mpfi r(bits);
  mpfi_interv_d(r.get(), x.lower(), x.upper());
  return r;
}

// The double preconditioner's form (n > 3). Only y^ needs the working precision: C f(y^),
// C F_z and (I - C A)(Y - y^) are enclosed in double intervals (scalar/interval_double.hpp:
// each operation rounded outward, its argument written and tested against MPFR), then
// added to y^ in MPFI. They are small (f(y^) is a residual at the working precision, Y - y^
// the box's radius), so double's relative accuracy costs nothing the proof could see: for a
// period-1096 orbit at 64 bits, |C f| ~ 1e-19 and |M (Y - y^)| ~ 1e-20 are enclosed to
// ~1e-35 and ~1e-36. The n^2 products cost nanoseconds instead of MPFI's ~100 ns. Only for
// large systems (kLargeSystem): on a smaller one (the period-37 grazing end at a = 21.5036,
// veldep c = 1000, whose knot margin vanishes with the border) the double products left
// the branch side's boxes too wide for a second margin's sign, which MPFI's products decide.
std::vector<Mpfi> image_in_doubles(const std::vector<double>& c, const std::vector<Mpfr>& yhat, const std::vector<Mpfi>& f,
                                   const SparseColumns& A, const std::vector<Mpfi>* Fz, const Mpfi& dz,
                                   const std::vector<Mpfi>& Y) {
  const size_t n = yhat.size();
  std::vector<DoubleInterval> fd(n), D(n);
  bool thin_box = true;
  for (size_t i = 0; i < n; ++i) {
    fd[i] = to_double(f[i]);
    const Mpfi d = Y[i] - Mpfi(yhat[i], yhat[i]);
    D[i] = to_double(d);
    if (!mpfi_is_zero(d.get())) thin_box = false;
  }
  std::vector<std::vector<std::pair<size_t, DoubleInterval>>> Ad(n);
  for (size_t col = 0; col < n; ++col)
    for (const auto& [r, v] : A[col]) Ad[col].emplace_back(r, to_double(v));
  std::vector<Mpfi> K;
  K.reserve(n);
  for (size_t r = 0; r < n; ++r) {
    const double* row = &c[r * n];
    DoubleInterval sum;  // -C f + (I - C A) D, then the free parameter's term
    for (size_t k = 0; k < n; ++k) sum -= DoubleInterval(row[k], row[k]) * fd[k];
    for (size_t col = 0; col < n && !thin_box; ++col) {
      DoubleInterval m(r == col ? 1L : 0L);
      for (const auto& [l, v] : Ad[col]) m -= DoubleInterval(row[l], row[l]) * v;
      sum += m * D[col];
    }
    Mpfi k(yhat[r], yhat[r]);
    k += to_mpfi(sum, 53);
    if (Fz) {
      DoubleInterval cz;
      for (size_t k2 = 0; k2 < n; ++k2) cz += DoubleInterval(row[k2], row[k2]) * to_double((*Fz)[k2]);
      k -= to_mpfi(cz, 53) * dz;
    }
    if (k.has_nan() || !k.bounded()) throw KrawczykFailure("the Krawczyk image is not finite");
    K.push_back(k);
  }
  return K;
}

}  // namespace

std::vector<Mpfi> krawczyk_image(const Preconditioner& C, const std::vector<Mpfr>& yhat, const std::vector<Mpfi>& f,
                                 const SparseColumns& A, const std::vector<Mpfi>* Fz, const Mpfi& dz,
                                 const std::vector<Mpfi>& Y, long bits) {
  if (C.doubles() && yhat.size() >= kLargeSystem) return image_in_doubles(*C.doubles(), yhat, f, A, Fz, dz, Y);
  const size_t n = yhat.size();
  std::vector<Mpfi> D;  // Y - y^
  bool thin_box = true;  // Y = y^ (Newton): (I - C A) (Y - y^) = 0
  for (size_t c = 0; c < n; ++c) {
    D.push_back(Mpfi(Y[c] - thin(yhat[c])));
    if (!mpfi_is_zero(D.back().get())) thin_box = false;
  }
  std::vector<Mpfi> K;
  K.reserve(n);
  Mpfi t(bits), M(bits);  // scratch
  for (size_t r = 0; r < n; ++r) {
    Mpfi k = thin(yhat[r]);
    for (size_t c = 0; c < n; ++c) {
      C.mul(r, c, f[c], t);
      mpfi_sub(k.get(), k.get(), t.get());
    }
    if (Fz) {
      Mpfi cz(0, bits);
      for (size_t c = 0; c < n; ++c) {
        C.mul(r, c, (*Fz)[c], t);
        mpfi_add(cz.get(), cz.get(), t.get());
      }
      k -= cz * dz;
    }
    for (size_t c = 0; c < n && !thin_box; ++c) {
      mpfi_set_si(M.get(), r == c ? 1 : 0);
      for (const auto& [l, v] : A[c]) {
        C.mul(r, l, v, t);
        mpfi_sub(M.get(), M.get(), t.get());
      }
      mpfi_mul(t.get(), M.get(), D[c].get());
      mpfi_add(k.get(), k.get(), t.get());
    }
    if (k.has_nan() || !k.bounded()) throw KrawczykFailure("the Krawczyk image is not finite");
    K.push_back(k);
  }
  return K;
}

InflationProof prove_by_inflation(const std::vector<Mpfr>& yhat, const std::vector<Mpfi>& f,
                                  const std::function<std::vector<Mpfi>(const std::vector<Mpfi>&)>& image, long bits,
                                  int rounds) {
  Mpfi fsum(0, bits);
  for (const Mpfi& x : f) fsum += abs(x);
  std::vector<Mpfr> r;
  for (const Mpfr& v : yhat) {
    Mpfi ulps = abs(thin(v)) + 1;
    mpfi_mul_2si(ulps.get(), ulps.get(), -(bits - 8));
    r.push_back(Mpfi(ulps + fsum).upper());
  }
  for (int it = 0; it < 24; ++it) {
    std::vector<Mpfi> Y;
    for (size_t i = 0; i < yhat.size(); ++i) Y.push_back(Mpfi(Mpfr(yhat[i] - r[i]), Mpfr(yhat[i] + r[i])));
    const std::vector<Mpfi> K = image(Y);
    bool in = true;
    for (size_t i = 0; i < K.size() && in; ++i) in = mpfi_is_strictly_inside(K[i].get(), Y[i].get()) > 0;
    if (in) {
      InflationProof p{Y, K, {}, it};
      for (size_t i = 0; i < K.size(); ++i) p.Y.push_back(intersect(K[i], Y[i]));
      for (int t = 0; t < rounds; ++t) {
        const std::vector<Mpfi> KT = image(p.Y);
        bool shrank = false;
        for (size_t i = 0; i < KT.size(); ++i) {
          const Mpfi N = intersect(KT[i], p.Y[i]);
          if (N.has_nan()) throw KrawczykFailure("K(B) n B is empty while tightening (an enclosure is inconsistent)");
          Mpfr half = p.Y[i].width();
          mpfr_div_2ui(half.get(), half.get(), 1, MPFR_RNDN);
          if (mpfr_less_p(N.width().get(), half.get())) shrank = true;
          p.Y[i] = N;
        }
        if (!shrank) break;
      }
      return p;
    }
    for (size_t i = 0; i < yhat.size(); ++i) {
      Mpfr grown(bits);
      grown = abs(K[i] - thin(yhat[i])).upper() * 2;
      Mpfr doubled(bits);
      doubled = r[i] * 2;
      r[i] = mpfr_greater_p(grown.get(), doubled.get()) ? grown : doubled;
    }
  }
  throw KrawczykFailure("the Krawczyk operator did not map any small box around the Newton point into itself");
}

}  // namespace bouncer::detail
