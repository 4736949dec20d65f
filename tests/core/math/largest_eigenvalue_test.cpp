#include "core/math/largest_eigenvalue.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "core/solids/generalized_mass_spring.hpp"

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

// The lattice the voxelizer made of an OBJ surface with one vertex 1.9 km from the rest (found
// by fuzzing, tests/fuzz/crashes/obj_reader/): two cubic cells of 474 m, 1.4 km apart, five
// tetrahedra each. Lanczos on its mass-spring stiffness reached α of 5·10⁴ beside β of 3·10⁻⁴,
// and Eigen's tridiagonal solver, given them unscaled, did not converge: the scene's load
// failed a check and took the server down. Two identical cells have the spectrum of one.
TEST(LargestEigenvalue, TwoCellsFarApartHaveTheLargestEigenvalueOfOne) {
  const Real x[] = {-237.55056525000009, 236.9265432499999};
  const Real y[] = {-232.86236575000021, 241.61474274999978};
  const Real z[] = {-2.9084339999999429, 471.56867450000004, 1895, 2369.4771084999998};
  TetMesh two;
  for (const Real zk : z) {
    for (const Real yj : y) {
      for (const Real xi : x) two.nodes.emplace_back(xi, yj, zk);
    }
  }
  for (const std::uint32_t first : {0u, 8u}) {
    for (const Tetrahedron& t :
         {Tetrahedron{1, 2, 4, 7}, Tetrahedron{0, 1, 2, 4}, Tetrahedron{3, 1, 7, 2},
          Tetrahedron{5, 1, 4, 7}, Tetrahedron{6, 2, 7, 4}}) {
      two.tets.push_back({first + t[0], first + t[1], first + t[2], first + t[3]});
    }
  }
  TetMesh one{{two.nodes.begin(), two.nodes.begin() + 8}, {two.tets.begin(), two.tets.begin() + 5}};
  const GeneralizedMassSpring both(two, build_topology(two), MassSpringMaterial{});
  const GeneralizedMassSpring single(one, build_topology(one), MassSpringMaterial{});
  EXPECT_NEAR(both.largest_stiffness_eigenvalue(), single.largest_stiffness_eigenvalue(),
              kTolerance * single.largest_stiffness_eigenvalue());
  EXPECT_GT(single.largest_stiffness_eigenvalue(), 0);
}

}  // namespace
}  // namespace felt
