#pragma once
// Derivatives of a system's forces, as implicit integrators need them (Baraff & Witkin 1998,
// thesis 1 §4.3). Forces that are sums of pairwise central terms (springs) and per-particle
// terms (drag) give a sparse, symmetric structure stored here as blocks.

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/SparseCore>

#include "core/math/types.hpp"

namespace felt {

class ForceJacobian {
 public:
  /// A central force between particles i and j that depends on x_i − x_j and v_i − v_j along
  /// the unit direction l̂:
  ///   ∂f_i/∂x_i = −(axial l̂l̂ᵀ + transverse (I − l̂l̂ᵀ)),   ∂f_i/∂v_i = −damping l̂l̂ᵀ,
  /// and ∂f_j/∂x_j = ∂f_i/∂x_i = −∂f_i/∂x_j = −∂f_j/∂x_i (likewise for velocities). Stored as
  /// these scalars rather than as 3×3 blocks: a third of the memory traffic in every CG
  /// iteration.
  struct Pair {
    std::uint32_t i = 0;
    std::uint32_t j = 0;
    Vec3 direction = Vec3::UnitX();
    Real axial = 0;
    Real transverse = 0;
    Real damping = 0;

    Mat3 dx() const;
    Mat3 dv() const;
  };

  /// Empties the Jacobian for `particles` particles, keeping the storage.
  void reset(std::size_t particles);
  void add_pair(const Pair& pair) { pairs_.push_back(pair); }
  /// Adds ∂f_p/∂v_p = −c I (viscous drag).
  void add_velocity_diagonal(std::uint32_t p, Real c) { velocity_diagonal_[p] += c; }
  /// Adds ∂f_p/∂x_p = −k I (a spring to a fixed point).
  void add_position_diagonal(std::uint32_t p, Real k) { position_diagonal_[p] += k; }

  /// dfdx_y = (∂f/∂x) y and dfdv_y = (∂f/∂v) y.
  void multiply(std::span<const Vec3> y, std::span<Vec3> dfdx_y, std::span<Vec3> dfdv_y) const;

  /// The 3×3 diagonal blocks ∂f_p/∂x_p and ∂f_p/∂v_p (for preconditioners).
  void diagonal_blocks(std::span<Mat3> dx, std::span<Mat3> dv) const;

  /// K = −∂f/∂x and D = −∂f/∂v as 3n × 3n matrices whose block (a, b) is scaled by
  /// s_a s_b: with s_p = √(1/m_p), M^-½ K M^-½ and M^-½ D M^-½, symmetric, with the eigenvalues
  /// of M⁻¹K and M⁻¹D (a pinned particle, s = 0, drops out).
  void scaled_matrices(std::span<const Real> scale, Eigen::SparseMatrix<Real>& stiffness,
                       Eigen::SparseMatrix<Real>& damping) const;

  std::size_t particle_count() const { return velocity_diagonal_.size(); }
  const std::vector<Pair>& pairs() const { return pairs_; }
  /// −∂f_p/∂v_p and −∂f_p/∂x_p of each particle's own terms, as scalars (times I).
  const std::vector<Real>& velocity_diagonal() const { return velocity_diagonal_; }
  const std::vector<Real>& position_diagonal() const { return position_diagonal_; }

 private:
  std::vector<Pair> pairs_;
  std::vector<Real> velocity_diagonal_;  ///< holds −∂f_p/∂v_p as a scalar
  std::vector<Real> position_diagonal_;  ///< holds −∂f_p/∂x_p as a scalar
};

}  // namespace felt
