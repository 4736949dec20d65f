#pragma once
// IMEX Euler of Eberhardt et al. 2000 in Melis's corrected form (thesis 1 §4.4, eq. 4.25). The
// system's constant linear forces f_g = H x + D v (the structural springs' −k_s l and their
// damping) are implicit, the rest f_a = f − f_g (their rest-length part k_s r l̂, shear, bend,
// gravity, drag) explicit:
//   (M − h² H − h D) v(t+h) = M v(t) + h f_a(x(t), v(t)) + h H x(t),   x(t+h) = x(t) + h v(t+h)
// H and D are constant, so the matrix is factorized once and only again when h, the masses or
// pins, or the spring constants change. First order; on a linear spring it is backward Euler.

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/integrator.hpp"

namespace felt {

class ImexIntegrator final : public Integrator {
 public:
  std::string_view name() const override { return "imex"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;

  /// How many times the matrix was factorized so far.
  std::int64_t factorizations() const { return factorizations_; }

 private:
  using SparseMatrix = Eigen::SparseMatrix<Real>;
  using Columns = Eigen::Matrix<Real, Eigen::Dynamic, 3>;  ///< x, y, z components as columns

  /// True when the factorization was made for these masses, pairs and h.
  bool factorization_matches(std::span<const Real> inv_mass, Real h) const;
  void factorize(std::span<const Real> inv_mass, Real h);

  std::vector<LinearPair> pairs_;
  // what the factorization was made for
  std::vector<LinearPair> factored_pairs_;
  std::vector<Real> factored_inv_mass_;
  Real factored_h_ = 0;
  bool factored_ = false;

  std::vector<Eigen::Triplet<Real>> triplets_;
  SparseMatrix matrix_;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  std::int64_t factorizations_ = 0;

  std::vector<Vec3> force_;
  Columns rhs_, permuted_, dv_;
};

}  // namespace felt
