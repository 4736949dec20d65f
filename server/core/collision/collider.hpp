#pragma once
// Static shapes a scene declares for cloth to rest on: a floor, a ball, a table, a rail
// (thesis 1 lists cloth–object collision as missing).

#include <cstdint>
#include <span>

#include "core/integrate/particle_state.hpp"

namespace felt {

struct Collider {
  enum class Shape : std::uint8_t { kPlane, kSphere, kBox, kCapsule };
  Shape shape = Shape::kPlane;
  Vec3 center = Vec3::Zero();   ///< plane: a point on it; sphere, box: the centre; capsule: end a
  Vec3 normal = Vec3::UnitY();  ///< plane: unit normal pointing to the free side
  Vec3 half_extents = Vec3::Ones();  ///< box (axis-aligned)
  Vec3 end = Vec3::Zero();           ///< capsule: end b
  Real radius = 1;                   ///< sphere, capsule
  Real friction = 0.3;               ///< Coulomb coefficient μ between the cloth and this shape
};

/// Signed distance from p to the collider's surface (negative inside) and the unit direction
/// that increases it fastest (the outward normal).
struct SignedDistance {
  Real distance = 0;
  Vec3 normal = Vec3::UnitY();
};
SignedDistance signed_distance(const Collider& collider, const Vec3& p);

/// Moves every free particle closer than `thickness` to a collider out to that distance, and
/// turns its velocity into a sliding one: the approaching normal component is removed and the
/// tangential one reduced by μ times the removed normal speed (Coulomb friction as a velocity
/// impulse, Bridson et al. 2002). Returns how many particle contacts it resolved.
std::size_t resolve_collisions(std::span<const Collider> colliders, std::span<const Real> inv_mass,
                               Real thickness, ParticleState& state);

}  // namespace felt
