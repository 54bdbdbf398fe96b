// The Krawczyk operator for systems with a sparse Jacobian (internal to verify/): the
// multiple-shooting proofs of periodic orbits (periodic_certify.cpp) and of border
// collisions, period doublings and folds (border_collision.cpp) share it.
//
// For f: R^n -> R^n, a box Y, a point y^ (usually its centre), an interval enclosure
// A of f's Jacobian over hull(Y, y^) and any point matrix C,
//     K(Y) = y^ - C f(y^) - C F_z (Z - z^) + (I - C A)(Y - y^)
// (F_z the derivative in a free parameter z over the same box, optional). If K(Y) lies in
// the interior of Y, then for every z in Z exactly one y in Y has f(y; z) = 0, and it lies in
// K(Y) (periodic_certify.hpp has the argument). C only decides whether it contracts, never
// whether the conclusion holds, so C is computed in double.
#pragma once

#include <cstddef>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "bouncer/scalar/mpfi.hpp"

namespace bouncer::detail {

// A large system: from this many unknowns (shooting over periods above 200) the LU of the
// preconditioner, (2Q)^3 flops, is computed once per problem (border_collision.cpp), and
// K(Y)'s n^2 products with C are enclosed in double intervals instead of MPFI
// (sparse_krawczyk.cpp says why that is sound and what it costs).
constexpr size_t kLargeSystem = 401;

// Why the operator could not be formed (a singular midpoint matrix, a non-finite image).
struct KrawczykFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An interval matrix kept by columns, with only the structurally nonzero entries of each
// column (row, value); entries of one row may repeat (they add).
using SparseColumns = std::vector<std::vector<std::pair<size_t, Mpfi>>>;

// C, an approximate inverse of mid(A). n <= 3 (a composed map, whose entries grow like the
// product of Q steps' derivatives): Gauss-Jordan at the working precision, C in thin
// intervals. Larger n (shooting: each entry one step's derivative): LU in double after
// equilibration by powers of two, C a double matrix (exact point values; the products with
// intervals are MPFI's, outward rounded). 8 n^2 bytes: 38 MB for a period-1096 orbit.
class Preconditioner {
 public:
  Preconditioner() = default;
  Preconditioner(const SparseColumns& A, long bits);
  size_t size() const { return n_; }
  // out = C[r][c] * x, enclosed.
  void mul(size_t r, size_t c, const Mpfi& x, Mpfi& out) const;
  // The double matrix, row-major (n > 3), or null (n <= 3).
  const std::vector<double>* doubles() const { return fast_.empty() ? nullptr : &fast_; }

 private:
  size_t n_ = 0;
  std::vector<std::vector<Mpfi>> precise_;  // n <= 3
  std::vector<double> fast_;                // n > 3, row-major
};

// K(Y) as above. Fz may be null (no free parameter, or one already inside f and A as an
// interval). Throws KrawczykFailure when an image component is not finite.
std::vector<Mpfi> krawczyk_image(const Preconditioner& C, const std::vector<Mpfr>& yhat, const std::vector<Mpfi>& f,
                                 const SparseColumns& A, const std::vector<Mpfi>* Fz, const Mpfi& dz,
                                 const std::vector<Mpfi>& Y, long bits);

// Epsilon inflation (Rump) around y^ with residual f = f(y^): boxes y^ +- r, r from the
// residual's size and a few ulps of y^, grown (to max(2 |K - y^|, 2 r)) until K(Y) lies in
// the interior of Y (at most 24 times); then Y <- K(Y) n Y, which keeps the unique zero,
// until no component's width halves (at most `rounds` times). `image` is K over a box.
// Throws KrawczykFailure when no box maps into itself or an intersection is empty.
struct InflationProof {
  std::vector<Mpfi> Y0, K0;  // K(Y0) in the interior of Y0
  std::vector<Mpfi> Y;       // the zero, enclosed (tightened)
  int inflations = 0;
};
InflationProof prove_by_inflation(const std::vector<Mpfr>& yhat, const std::vector<Mpfi>& f,
                                  const std::function<std::vector<Mpfi>(const std::vector<Mpfi>&)>& image, long bits,
                                  int rounds);

}  // namespace bouncer::detail
