#include "core/cloth/particle_constraint.hpp"

namespace felt {

void apply_constraints(std::span<const ParticleConstraint> constraints, ParticleState& state) {
  for (const ParticleConstraint& c : constraints) {
    Vec3& x = state.x[c.particle];
    Vec3& v = state.v[c.particle];
    const Vec3& d = c.direction;
    if (c.kind == ParticleConstraint::Kind::kPlane) {
      x -= (x - c.point).dot(d) * d;
      v -= v.dot(d) * d;
    } else {
      x = c.point + (x - c.point).dot(d) * d;
      v = v.dot(d) * d;
    }
  }
}

}  // namespace felt
