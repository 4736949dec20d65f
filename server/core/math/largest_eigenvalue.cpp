#include "core/math/largest_eigenvalue.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

#include "core/math/check.hpp"

namespace felt {
namespace {

// Lanczos steps between two looks at the Ritz values, and at most: the top of a body's spectrum
// is found in a few dozen (a 5×5×5 lattice in about 40).
constexpr Eigen::Index kStepsPerCheck = 10;
constexpr Eigen::Index kMaxSteps = 400;

// β below this fraction of the largest |α| or β seen ends the Krylov space: T's eigenvalues
// are then the matrix's own (those the start vector reaches, which is all of them).
constexpr Real kBreakdown = 1e-13;

Eigen::VectorXd start_vector(Eigen::Index n) {
  std::minstd_rand random(20070101);  // the standard fixes minstd_rand's sequence
  Eigen::VectorXd q(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto r = static_cast<Real>(random() - std::minstd_rand::min());
    q[i] = 2 * r / static_cast<Real>(std::minstd_rand::max() - std::minstd_rand::min()) - 1;
  }
  return q.normalized();
}

}  // namespace

void add_block(std::vector<Eigen::Triplet<Real>>& triplets, std::uint32_t a, std::uint32_t b,
               const Mat3& block) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (block(r, c) != 0) triplets.emplace_back(3 * a + r, 3 * b + c, block(r, c));
    }
  }
}

Eigen::SparseMatrix<Real> block_matrix(std::size_t node_count,
                                       const std::vector<Eigen::Triplet<Real>>& triplets) {
  const auto size = static_cast<Eigen::Index>(3 * node_count);
  Eigen::SparseMatrix<Real> matrix(size, size);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  return matrix;
}

Real largest_eigenvalue(const Eigen::SparseMatrix<Real>& matrix, Real relative_tolerance) {
  FELT_CHECK(matrix.rows() == matrix.cols());
  FELT_CHECK(relative_tolerance > 0);
  const Eigen::Index n = matrix.rows();
  if (n == 0) return 0;
  const Eigen::Index max_steps = std::min(n, kMaxSteps);

  // three-term Lanczos without reorthogonalization: lost orthogonality only repeats converged
  // Ritz values, it never moves the largest one above λ_max
  Eigen::VectorXd q = start_vector(n);
  Eigen::VectorXd previous = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd w(n);
  Eigen::VectorXd alpha(max_steps), beta(max_steps);
  Real scale = 0;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz;
  for (Eigen::Index k = 0; k < max_steps; ++k) {
    w.noalias() = matrix * q;
    if (k > 0) w -= beta[k - 1] * previous;
    alpha[k] = q.dot(w);
    w -= alpha[k] * q;
    beta[k] = w.norm();
    scale = std::max({scale, std::abs(alpha[k]), beta[k]});

    if (scale == 0) return 0;  // A q = 0 for a q that is not: A is zero
    const bool breakdown = !(beta[k] > kBreakdown * scale);
    const Eigen::Index size = k + 1;
    if (breakdown || size == max_steps || size % kStepsPerCheck == 0) {
      // the Ritz values are the eigenvalues of the tridiagonal T = tridiag(β, α, β), scaled to
      // a largest entry of 1 as Eigen's compute() scales a dense matrix: its QL iteration
      // deflates an off-diagonal against a threshold that assumes such a scale, and unscaled
      // (α up to 5·10⁴, β down to 3·10⁻⁴, a lattice's two cells 1.4 km apart) it never converged
      const Eigen::VectorXd diagonal = alpha.head(size) / scale;
      const Eigen::VectorXd off_diagonal = beta.head(size - 1) / scale;
      ritz.computeFromTridiagonal(diagonal, off_diagonal, Eigen::ComputeEigenvectors);
      FELT_CHECK(ritz.info() == Eigen::Success);
      const Real theta = scale * ritz.eigenvalues()[size - 1];  // ascending
      // ‖A y − θ y‖ of the Ritz vector y = Q s is β_k |s_k|
      const Real residual = beta[k] * std::abs(ritz.eigenvectors()(size - 1, size - 1));
      if (breakdown || size == max_steps || residual <= relative_tolerance * theta) {
        return std::max(Real{0}, theta + residual);
      }
    }
    previous.swap(q);
    q = w / beta[k];
  }
  check_failed("unreachable: the loop returns at its last step");
}

}  // namespace felt
