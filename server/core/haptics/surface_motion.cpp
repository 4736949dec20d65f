#include "core/haptics/surface_motion.hpp"

#include <algorithm>
#include <cmath>

namespace felt {

SurfaceMotion SurfaceMotion::then(std::span<const Vec3> from, std::span<const Vec3> to) const {
  Real largest_sq = 0;
  for (std::size_t i = 0; i < to.size(); ++i) {
    largest_sq = std::max(largest_sq, (to[i] - from[i]).squaredNorm());
  }
  return moved(std::sqrt(largest_sq));
}

}  // namespace felt
