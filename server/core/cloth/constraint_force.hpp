#pragma once
// Constraint forces (Witkin, "Constraint Dynamics", SIGGRAPH 2001 course notes; thesis 1 §5): a
// particle kept on a sphere or a plane by a force along the constraint's gradient, the bead on a
// wire of the thesis.

#include <cstdint>
#include <span>

#include "core/math/types.hpp"

namespace felt {

/// A scalar constraint C(x) = 0 on one particle. Its force is λ ∇C with λ chosen so that
/// C̈ = −k_s C − k_d Ċ: zero when the particle is on the constraint and moving along it, and a
/// damped spring pulling it back when integration has let it drift off.
struct ConstraintForce {
  enum class Kind : std::uint8_t {
    kSphere,  ///< C = ½(|x − c|² − r²)
    kPlane,   ///< C = n·(x − p)
  };
  Kind kind = Kind::kSphere;
  std::uint32_t particle = 0;
  Vec3 point = Vec3::Zero();    ///< sphere: the centre c; plane: a point p on it
  Vec3 normal = Vec3::UnitY();  ///< plane: unit normal n
  Real radius = 1;              ///< sphere: r, m
  Real stiffness = 0;           ///< k_s, 1/s²: drift feedback, C̈ += −k_s C
  Real damping = 0;             ///< k_d, 1/s: drift feedback, C̈ += −k_d Ċ
};

/// The constraint force on a particle at x with velocity v, inverse mass w > 0, that feels the
/// force f from everything else. One function per kind.
Vec3 sphere_constraint_force(const ConstraintForce& constraint, const Vec3& x, const Vec3& v,
                             const Vec3& f, Real inv_mass);
Vec3 plane_constraint_force(const ConstraintForce& constraint, const Vec3& x, const Vec3& v,
                            const Vec3& f, Real inv_mass);

/// Adds every constraint's force to f, computed from what f already holds, so call it after all
/// other forces. Pinned particles (inverse mass 0) get none. Constraints on the same particle act
/// one after another, each seeing the forces of those before it: exact when their gradients are
/// orthogonal (a sphere and a plane through its centre hold a bead on a circle); otherwise the
/// feedback terms take up the rest.
void add_constraint_forces(std::span<const ConstraintForce> constraints,
                           std::span<const Real> inv_mass, std::span<const Vec3> x,
                           std::span<const Vec3> v, std::span<Vec3> f);

}  // namespace felt
