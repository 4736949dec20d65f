#pragma once
// Corotated linear finite elements on tetrahedra (thesis 2 §1.7 names FEM as the accurate
// alternative; Müller and Gross 2004): each element's deformation gradient F = R S is rotated
// back by the rotation R of its polar decomposition, and linear elasticity acts on the stretch
// S, so large rotations cost nothing. Masses are lumped at the nodes (the body's node masses).

#include <span>
#include <vector>

#include <Eigen/SparseCore>

#include "core/geometry/tet_mesh.hpp"
#include "core/solids/node_mask.hpp"
#include "core/solids/solid_body.hpp"

namespace felt {

class CorotatedFem {
 public:
  /// Precomputes the rest shape matrices of the positively oriented tetrahedra of `rest`.
  CorotatedFem(const TetMesh& rest, const FemMaterial& material);

  /// Adds the elastic and damping forces at positions x and velocities v to f. The elastic part
  /// is −R K (Rᵀx − x₀) per element with K the linear stiffness, computed through the first
  /// Piola–Kirchhoff stress P = R σ(S − I), which is the same thing without the 12×12 matrix.
  /// The damping stress is β σ(sym(Fᵀ Ḟ)) (P = F σ): β K v at rest, zero for any rigid motion,
  /// and without net force or torque, so it conserves momentum like the elastic part.
  /// With a mask, only the elements acting on a selected node are visited: f is then right (bit
  /// for bit) at the selected nodes only.
  void add_forces(std::span<const Vec3> x, std::span<const Vec3> v, std::span<Vec3> f,
                  NodeMask mask = {}) const;
  /// Σ V₀ (μ ‖S − I‖² + λ/2 tr(S − I)²), whose negative gradient the elastic forces are.
  Real energy(std::span<const Vec3> x) const;

  /// λ_max of the linear stiffness matrix K at rest, N/m, for the explicit step limit.
  Real largest_stiffness_eigenvalue() const { return largest_stiffness_; }
  /// K at rest (3n × 3n), for how stiff the body is at a point (solid_point_compliance).
  const Eigen::SparseMatrix<Real>& rest_stiffness() const { return rest_stiffness_; }
  /// λ_max of the damping matrix β K, N·s/m.
  Real largest_damping_eigenvalue() const { return damping_ * largest_stiffness_; }

  Real lame_mu() const { return mu_; }
  Real lame_lambda() const { return lambda_; }

 private:
  struct Element {
    Tetrahedron nodes;
    Mat3 rest_inverse;  ///< inverse of [x₁ − x₀, x₂ − x₀, x₃ − x₀] at rest
    Real rest_volume;
  };

  /// The deformation gradient of element e at positions x.
  static Mat3 deformation_gradient(const Element& e, std::span<const Vec3> x);

  Real mu_, lambda_, damping_;
  std::vector<Element> elements_;
  std::size_t node_count_;
  Eigen::SparseMatrix<Real> rest_stiffness_;
  Real largest_stiffness_ = 0;
};

}  // namespace felt
