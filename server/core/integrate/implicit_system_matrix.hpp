#pragma once
// The matrix of a backward Euler step, A = M − h ∂f/∂v − h² ∂f/∂x (Baraff & Witkin 1998,
// eq. 15; thesis 1 §4.3), assembled once per step from a ForceJacobian and multiplied in every
// conjugate-gradient iteration. Stored as structure of arrays with the two derivatives folded
// into two scalars per pair: a product reads 48 bytes a pair and writes one vector, where
// multiplying both Jacobians read 56 and wrote two (issue 29, item 3).

#include <cstdint>
#include <span>
#include <vector>

#include "core/integrate/force_jacobian.hpp"
#include "core/math/types.hpp"

namespace felt {

class ImplicitSystemMatrix {
 public:
  /// A for a step of length h of particles of inverse masses `inv_mass` (0: pinned, its row
  /// left to the solver's filter) whose forces have the derivatives `jacobian`.
  void assemble(const ForceJacobian& jacobian, std::span<const Real> inv_mass, Real h);

  /// out = A y.
  void multiply(std::span<const Vec3> y, std::span<Vec3> out) const;

  /// The diagonal of A, per particle and component (a Jacobi preconditioner inverts it).
  void diagonal(std::span<Vec3> out) const;

 private:
  // per pair (i, j) with unit direction l̂: A_ij = −(along l̂l̂ᵀ + across I), A_ii += the same
  // with + (along = h² (axial − transverse) + h damping, across = h² transverse)
  std::vector<std::uint32_t> i_, j_;
  std::vector<Vec3> direction_;
  std::vector<Real> along_, across_;
  std::vector<Real> particle_;  ///< m + h c_v + h² k_x: mass, drag and anchors, times I
};

}  // namespace felt
