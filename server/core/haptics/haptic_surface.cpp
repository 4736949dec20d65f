#include "core/haptics/haptic_surface.hpp"

#include <algorithm>
#include <cmath>

namespace felt {

Real HapticBody::displacement() const {
  const Real d = motion.max_displacement;
  return std::isfinite(d) ? std::max(d, Real{0}) : 0;
}

std::optional<TriangleCorners> HapticBody::triangle_at(std::uint32_t triangle, Real alpha) const {
  if (triangle >= triangles.size()) return std::nullopt;
  const Triangle& t = triangles[triangle];
  const std::size_t vertices = std::min(from.size(), to.size());
  if (t[0] >= vertices || t[1] >= vertices || t[2] >= vertices) return std::nullopt;
  const auto at = [&](std::uint32_t i) { return Vec3((1 - alpha) * from[i] + alpha * to[i]); };
  const TriangleCorners c{at(t[0]), at(t[1]), at(t[2])};
  if (!c.a.allFinite() || !c.b.allFinite() || !c.c.allFinite()) return std::nullopt;
  return c;
}

}  // namespace felt
