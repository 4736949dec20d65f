#pragma once
// Particles held in a plane or on a line (thesis 1 §5): a curtain ring on its rail, a sheet
// sliding on a wall.

#include <cstdint>
#include <span>

#include "core/integrate/particle_state.hpp"

namespace felt {

struct ParticleConstraint {
  enum class Kind : std::uint8_t { kPlane, kLine };
  Kind kind = Kind::kPlane;
  std::uint32_t particle = 0;
  Vec3 point = Vec3::Zero();       ///< on the plane or line (the particle's start)
  Vec3 direction = Vec3::UnitY();  ///< unit: the plane's normal, or the line's direction
};

/// Puts each constrained particle back on its plane or line (closest point) and removes the
/// velocity that would take it off: v ← v − (v·n) n in a plane, v ← (v·d) d on a line
/// (thesis 1 §5). Run after every substep, after anything else that moves particles.
void apply_constraints(std::span<const ParticleConstraint> constraints, ParticleState& state);

}  // namespace felt
