#pragma once
// The linearized length constraints of a set of springs, solved together (Goldenthal, Harmon,
// Fattal, Bercovier & Grinspun 2007, "Efficient simulation of inextensible cloth", §4):
// C_k(x) = |x_j − x_i| − target_k, whose gradient J has the row (−n_k at i, n_k at j), n_k the
// spring's direction. Given r, the correction δ = −W Jᵀ μ with (J W Jᵀ + ε D) μ = r (W the
// inverse masses, D the diagonal of J W Jᵀ) is the smallest change in the mass norm that takes
// J δ to −r: with r = C a Newton step of the positions onto C = 0 (fast projection, eq. 8-9), with
// r = J v the velocities' components along the springs removed. ε keeps the matrix
// positive-definite where the springs are redundant (a grid's structural and shear springs
// outnumber its particles' degrees of freedom), and it only shrinks a correction: applied to
// velocities it removes kinetic energy, ½ vᵀ M v falls by μᵀ (J W Jᵀ) μ + 2 ε μᵀ D μ.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/cloth/cloth_model.hpp"

namespace felt {

class SpringConstraintSolve {
 public:
  /// Relative regularization ε of the diagonal.
  static constexpr Real kRegularization = 1e-8;

  /// Takes the springs (indices into model.springs, each with a free end) at positions x and
  /// factorizes J W Jᵀ + ε D (sparse LDLᵀ, its ordering reused while the springs stay the same).
  /// Returns false when the factorization fails.
  bool factorize(const ClothModel& model, std::span<const Real> inv_mass,
                 std::span<const std::uint32_t> springs, std::span<const Vec3> x);

  /// y += −W Jᵀ μ, (J W Jᵀ + ε D) μ = r, r one entry per spring of the last factorize().
  void correct(const ClothModel& model, std::span<const Real> inv_mass, const Eigen::VectorXd& r,
               std::span<Vec3> y);

  /// The direction n_k of each spring at the last factorize().
  const std::vector<Vec3>& directions() const { return directions_; }

 private:
  using SparseMatrix = Eigen::SparseMatrix<Real>;

  std::vector<std::uint32_t> springs_;
  std::vector<Vec3> directions_;
  // the springs at each particle, compressed: those of p are at [first_[p], first_[p + 1])
  std::vector<std::uint32_t> first_;
  std::vector<std::uint32_t> incident_;  ///< 2 k for spring k's end i, 2 k + 1 for its end j
  std::vector<Eigen::Triplet<Real>> triplets_;
  SparseMatrix matrix_;
  /// on the heap: Eigen's solvers cannot be moved, and a world moves its cloths' limiters
  std::unique_ptr<Eigen::SimplicialLDLT<SparseMatrix>> ldlt_;
  std::vector<std::uint32_t> analyzed_springs_;  ///< the springs the ordering was made for
  bool analyzed_ = false;
  Eigen::VectorXd mu_;
};

}  // namespace felt
