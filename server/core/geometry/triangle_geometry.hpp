#pragma once

#include "core/math/types.hpp"

namespace felt {

/// The point of a triangle nearest to a query point, with its barycentric coordinates
/// (point = u·a + v·b + w·c).
struct ClosestPoint {
  Vec3 point;
  Vec3 barycentric;
};

/// Nearest point of triangle (a, b, c) to p, by Voronoi regions (Ericson, Real-Time Collision
/// Detection, §5.1.5). A triangle without area (collinear or coinciding corners, up to
/// rounding) gives the nearest point of its edges.
ClosestPoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace felt
