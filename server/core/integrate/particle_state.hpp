#pragma once

#include <vector>

#include "core/math/types.hpp"

namespace felt {

/// The mutable state of a particle system, structure of arrays.
struct ParticleState {
  std::vector<Vec3> x;  ///< positions, m
  std::vector<Vec3> v;  ///< velocities, m/s

  std::size_t size() const { return x.size(); }
};

}  // namespace felt
