#pragma once
// Where a point lies relative to one triangle, as the god-object's stages read it: its
// placement (the barycentric coordinates of the triangle's nearest point and the offset from it
// in the triangle's frame), which carries the proxy with a moving surface, and the direction it
// lies in from the triangle (the contact normal).

#include <optional>

#include "core/collision/sphere_sweep.hpp"
#include "core/geometry/triangle_geometry.hpp"
#include "core/math/types.hpp"

namespace felt {

/// A point relative to a triangle: the barycentric coordinates of the triangle's point nearest
/// to it and the offset from that point in the triangle's frame (first edge, its perpendicular
/// in the plane, the unit normal).
struct Placement {
  Vec3 barycentric;
  Vec3 offset;
};

/// The point of the triangle with these barycentric coordinates.
Vec3 point_at(const TriangleCorners& c, const Vec3& barycentric);

/// Unit normal of a triangle, or none when it is too thin to have a reliable one.
std::optional<Vec3> unit_normal(const TriangleCorners& c);

/// Where `p` lies relative to the triangle; none when the triangle is too thin for a frame.
std::optional<Placement> place(const TriangleCorners& c, const Vec3& p);

/// The point at `placement` relative to the triangle; none when it has no frame or the point is
/// not finite.
std::optional<Vec3> position_of(const TriangleCorners& c, const Placement& placement);

/// Unit vector from the triangle's point nearest to `centre` toward it: the face normal on the
/// centre's side when the centre lies over the face (exact however near the centre is, where
/// the direction from the nearest point would carry its rounding), else the direction from an
/// edge or a corner. Zero when the centre is on the triangle.
Vec3 contact_normal(const Vec3& centre, const TriangleCorners& c, const ClosestPoint& nearest);

}  // namespace felt
