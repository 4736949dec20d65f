#include "core/math/largest_eigenvalue.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

namespace felt {
namespace {

constexpr Real kTolerance = 1e-3;

/// The largest eigenvalue by the dense symmetric solver: brute force to compare against.
Real dense_largest(const Eigen::SparseMatrix<Real>& matrix) {
  const Eigen::MatrixXd dense(matrix);
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
}

/// Within the tolerance, and from above: the estimate is used as a safe bound.
void expect_tight_upper_bound(Real estimate, Real exact) {
  EXPECT_GE(estimate, exact * (1 - 1e-12));
  EXPECT_LE(estimate, exact * (1 + kTolerance));
}

// The graph Laplacian of a path of n nodes has the eigenvalues 2 − 2 cos(kπ/n), k < n; its top
// is crowded (neighbouring eigenvalues 10⁻⁴ apart), the hard case for Lanczos.
TEST(LargestEigenvalue, PathLaplacianMatchesTheAnalyticSpectrum) {
  for (int n : {2, 7, 300, 2000}) {
    std::vector<Eigen::Triplet<Real>> triplets;
    for (int i = 0; i + 1 < n; ++i) {
      triplets.emplace_back(i, i, 1);
      triplets.emplace_back(i + 1, i + 1, 1);
      triplets.emplace_back(i, i + 1, -1);
      triplets.emplace_back(i + 1, i, -1);
    }
    Eigen::SparseMatrix<Real> laplacian(n, n);
    laplacian.setFromTriplets(triplets.begin(), triplets.end());
    const Real exact = 2 - 2 * std::cos((n - 1) * std::numbers::pi / n);
    expect_tight_upper_bound(largest_eigenvalue(laplacian, kTolerance), exact);
  }
}

// Sums of random rank-one element matrices k g gᵀ on four random nodes, like the volume terms
// of a mass-spring body, against the dense solver.
TEST(LargestEigenvalue, RandomElementMatricesMatchTheDenseSolver) {
  std::mt19937 random(11);
  std::uniform_real_distribution<Real> uniform(-1, 1);
  std::uniform_int_distribution<std::uint32_t> node(0, 79);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<Eigen::Triplet<Real>> triplets;
    for (int element = 0; element < 150; ++element) {
      std::array<std::uint32_t, 4> nodes;
      std::array<Vec3, 4> gradient;
      for (int a = 0; a < 4; ++a) {
        nodes[a] = node(random);
        gradient[a] = Vec3(uniform(random), uniform(random), uniform(random));
      }
      const Real k = 1 + 100 * std::abs(uniform(random));
      for (int a = 0; a < 4; ++a) {
        for (int b = 0; b < 4; ++b) {
          add_block(triplets, nodes[a], nodes[b], k * gradient[a] * gradient[b].transpose());
        }
      }
    }
    const Eigen::SparseMatrix<Real> matrix = block_matrix(80, triplets);
    expect_tight_upper_bound(largest_eigenvalue(matrix, kTolerance), dense_largest(matrix));
  }
}

TEST(LargestEigenvalue, ZeroAndEmptyMatricesGiveZero) {
  EXPECT_EQ(largest_eigenvalue(Eigen::SparseMatrix<Real>(0, 0)), 0);
  EXPECT_EQ(largest_eigenvalue(Eigen::SparseMatrix<Real>(12, 12)), 0);
}

// A diagonal matrix is found exactly: the Krylov space ends after as many steps as it has
// distinct eigenvalues.
TEST(LargestEigenvalue, DiagonalMatrixIsExact) {
  Eigen::SparseMatrix<Real> diagonal(6, 6);
  const Real values[] = {3, 0, 9.5, 1, 9.5, 2};
  for (int i = 0; i < 6; ++i) diagonal.insert(i, i) = values[i];
  EXPECT_NEAR(largest_eigenvalue(diagonal), 9.5, 1e-12);
}

}  // namespace
}  // namespace felt
