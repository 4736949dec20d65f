#pragma once
// The velocity equation of the schemes that take a system's constant linear pair forces
// (LinearPair: the structural springs' −k l and their damping) implicitly and the rest of its
// forces explicitly — IMEX (Eberhardt et al. 2000) and the backward Euler approximations of
// Desbrun et al. 1999 and Kang et al. 2000 (thesis 1 §4.3–4.4):
//   (M − h² H − θ h D) Δv = b,   b = h (f(x, v) + h H v),   Δv = 0 for pinned particles,
// H and D the weighted graph Laplacians of the pairs' k and c (H_ij = k_ij, H_ii = −Σ_j k_ij),
// f the system's full force. θ = 1 takes the pairs' damping implicitly too (IMEX); θ = 0 drops
// ∂f/∂v as Desbrun et al. do. The matrix is constant, so it is factorized once and again only
// when h, the masses or pins, or the pairs change.

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/integrate/dynamic_system.hpp"
#include "core/integrate/particle_state.hpp"

namespace felt {

class LinearPairStep {
 public:
  using Columns = Eigen::Matrix<Real, Eigen::Dynamic, 3>;  ///< one row per particle

  explicit LinearPairStep(bool implicit_damping) : implicit_damping_(implicit_damping) {}

  /// Evaluates the system's pairs, its forces and b at `state` (time t, step h).
  void assemble(const DynamicSystem& system, const ParticleState& state, Real t, Real h);
  /// For a caller that gives the pairs and the force itself (projective dynamics, whose f
  /// changes from one iteration of a step to the next while the pairs stay): the pairs, once a
  /// step ...
  void set_pairs(std::span<const LinearPair> pairs);
  /// ... and b from the force f at each iteration.
  void assemble(std::span<const Real> inv_mass, const ParticleState& state, Real h,
                std::span<const Vec3> force);

  /// Writes the exact Δv of the assembled equation into `dv`, factorizing the matrix first
  /// when it was last factorized for other masses, pairs or h.
  void solve(std::span<const Real> inv_mass, Real h, Columns& dv);

  /// Of the last assemble(): the pairs (empty when the system has none) ...
  const std::vector<LinearPair>& pairs() const { return pairs_; }
  /// ... the full force f ...
  const std::vector<Vec3>& forces() const { return force_; }
  /// ... and b, with zero rows for pinned particles.
  const Columns& rhs() const { return rhs_; }

  /// How many times the matrix was factorized so far.
  std::int64_t factorizations() const { return factorizations_; }

 private:
  using SparseMatrix = Eigen::SparseMatrix<Real>;

  /// b from force_ and pairs_.
  void assemble_rhs(std::span<const Real> inv_mass, const ParticleState& state, Real h);
  /// True when the factorization was made for these masses, pairs and h.
  bool factorization_matches(std::span<const Real> inv_mass, Real h) const;
  void factorize(std::span<const Real> inv_mass, Real h);

  bool implicit_damping_;
  std::vector<LinearPair> pairs_;
  std::vector<Vec3> force_;
  Columns rhs_, permuted_;

  // what the factorization was made for
  std::vector<LinearPair> factored_pairs_;
  std::vector<Real> factored_inv_mass_;
  Real factored_h_ = 0;
  bool factored_ = false;

  std::vector<Eigen::Triplet<Real>> triplets_;
  SparseMatrix matrix_;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  std::int64_t factorizations_ = 0;
};

/// v += Δv, then x += h v, for every particle that is not pinned.
void apply_velocity_change(std::span<const Real> inv_mass, Real h,
                           const LinearPairStep::Columns& dv, ParticleState& state);

}  // namespace felt
