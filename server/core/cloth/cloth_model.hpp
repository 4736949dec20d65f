#pragma once
// The immutable definition of a cloth: what it is made of, not where it is now.

#include <cstdint>
#include <vector>

#include "core/cloth/spring.hpp"
#include "core/math/types.hpp"

namespace felt {

/// Rest geometry, masses, springs and surface of a cloth. Never changes while it is simulated;
/// the mutable state lives in ParticleState.
struct ClothModel {
  std::vector<Vec3> rest_positions;
  std::vector<Vec2> uv;  ///< texture coordinates, one per particle
  std::vector<Real> mass;
  std::vector<Spring> springs;
  std::vector<Triangle> triangles;

  std::size_t particle_count() const { return rest_positions.size(); }
};

}  // namespace felt
