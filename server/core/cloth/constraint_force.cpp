#include "core/cloth/constraint_force.hpp"

#include "core/math/check.hpp"

namespace felt {
namespace {

/// What a constraint contributes at the particle's state: C, its gradient ∇C (the Jacobian J of
/// one particle), Ċ = J v and the curvature term J̇ v.
struct ConstraintValue {
  Real c = 0;
  Vec3 gradient = Vec3::Zero();
  Real c_dot = 0;
  Real j_dot_v = 0;
};

/// λ ∇C with C̈ = J̇v + J w (f + λ ∇C) = −k_s C − k_d Ċ solved for λ (Witkin's J W Jᵀ λ =
/// −J̇q̇ − J W Q − k_s C − k_d Ċ for one particle and one constraint).
Vec3 witkin_force(const ConstraintForce& constraint, const ConstraintValue& value, const Vec3& f,
                  Real inv_mass) {
  const Real jwj = inv_mass * value.gradient.squaredNorm();
  if (!(jwj > 0)) return Vec3::Zero();  // pinned, or at the centre of a sphere: no direction
  const Real lambda = -(value.j_dot_v + inv_mass * value.gradient.dot(f) +
                        constraint.stiffness * value.c + constraint.damping * value.c_dot) /
                      jwj;
  return lambda * value.gradient;
}

}  // namespace

Vec3 sphere_constraint_force(const ConstraintForce& constraint, const Vec3& x, const Vec3& v,
                             const Vec3& f, Real inv_mass) {
  // C = ½(d·d − r²) with d = x − c: ∇C = d, Ċ = d·v, J̇v = v·v (thesis 1 §5 with c = 0, r = 1)
  const Vec3 d = x - constraint.point;
  const Real r = constraint.radius;
  return witkin_force(constraint, {0.5 * (d.squaredNorm() - r * r), d, d.dot(v), v.squaredNorm()},
                      f, inv_mass);
}

Vec3 plane_constraint_force(const ConstraintForce& constraint, const Vec3& x, const Vec3& v,
                            const Vec3& f, Real inv_mass) {
  // C = n·(x − p): ∇C = n, Ċ = n·v, and a constant gradient has J̇ = 0
  const Vec3& n = constraint.normal;
  return witkin_force(constraint, {n.dot(x - constraint.point), n, n.dot(v), 0}, f, inv_mass);
}

void add_constraint_forces(std::span<const ConstraintForce> constraints,
                           std::span<const Real> inv_mass, std::span<const Vec3> x,
                           std::span<const Vec3> v, std::span<Vec3> f) {
  for (const ConstraintForce& constraint : constraints) {
    const std::uint32_t p = constraint.particle;
    FELT_CHECK(p < x.size());
    switch (constraint.kind) {
      case ConstraintForce::Kind::kSphere:
        f[p] += sphere_constraint_force(constraint, x[p], v[p], f[p], inv_mass[p]);
        break;
      case ConstraintForce::Kind::kPlane:
        f[p] += plane_constraint_force(constraint, x[p], v[p], f[p], inv_mass[p]);
        break;
    }
  }
}

}  // namespace felt
