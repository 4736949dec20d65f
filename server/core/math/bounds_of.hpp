#pragma once
// The box around a set of points: what the health checks, the voxelizer, the solids' collision
// detection and the solid loader measure a body's extent with.

#include <span>

#include "core/math/types.hpp"

namespace felt {

/// The smallest axis-aligned box that holds every point of `points`; empty (isEmpty()) for none.
inline Eigen::AlignedBox<Real, 3> bounds_of(std::span<const Vec3> points) {
  Eigen::AlignedBox<Real, 3> box;
  for (const Vec3& p : points) box.extend(p);
  return box;
}

}  // namespace felt
