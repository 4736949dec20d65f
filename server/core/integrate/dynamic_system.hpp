#pragma once

#include <span>
#include <vector>

#include "core/integrate/distance_constraint.hpp"
#include "core/integrate/force_jacobian.hpp"
#include "core/integrate/linear_pair.hpp"
#include "core/math/types.hpp"

namespace felt {

/// What an integrator needs from a body: its masses and its force function. Integrators never
/// see springs or meshes, so any body (cloth, solid, a test oscillator) can use any of them.
class DynamicSystem {
 public:
  virtual ~DynamicSystem() = default;

  /// Inverse masses; 0 marks a particle that does not move (a pin).
  virtual std::span<const Real> inv_mass() const = 0;

  /// Writes into `f` the total force on every particle in state (x, v) at time t.
  virtual void compute_forces(std::span<const Vec3> x, std::span<const Vec3> v, Real t,
                              std::span<Vec3> f) const = 0;

  /// Fills `jacobian` with ∂f/∂x and ∂f/∂v at (x, v). Systems that cannot return false, and
  /// implicit integrators then refuse them.
  virtual bool compute_jacobian(std::span<const Vec3> /*x*/, std::span<const Vec3> /*v*/,
                                ForceJacobian& /*jacobian*/) const {
    return false;
  }

  /// Replaces `pairs` with the constant, linear part of the forces that an IMEX scheme treats
  /// implicitly (see LinearPair). The rest of compute_forces is then explicit. False when the
  /// system has none.
  virtual bool linear_force_pairs(std::vector<LinearPair>& pairs) const {
    pairs.clear();
    return false;
  }

  /// Replaces `constraints` with the springs a position-based integrator (XPBD) enforces as
  /// compliant distance constraints instead of as forces, in classes that share no particle.
  /// False when the system has none.
  virtual bool distance_constraints(ConstraintClasses& constraints) const {
    constraints.clear();
    return false;
  }

  /// compute_forces without the forces of the springs distance_constraints returns.
  virtual void compute_forces_besides_constraints(std::span<const Vec3> x, std::span<const Vec3> v,
                                                  Real t, std::span<Vec3> f) const {
    compute_forces(x, v, t, f);
  }
};

}  // namespace felt
