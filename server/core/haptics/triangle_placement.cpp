#include "core/haptics/triangle_placement.hpp"

#include <cmath>

namespace felt {
namespace {

// Below this squared sine of its angle a triangle's frame turns with rounding.
constexpr Real kFlatSinSq = 1e-14;
// A centre whose offset from the nearest point leans less than this (radians) off the face
// normal lies over the face: on a shared edge, the offset's lean is rounding.
constexpr Real kOverFace = 1e-6;

/// A triangle's orthonormal frame: first edge, its perpendicular in the plane, unit normal.
std::optional<Mat3> frame_of(const TriangleCorners& c) {
  const std::optional<Vec3> normal = unit_normal(c);
  if (!normal) return std::nullopt;
  Mat3 frame;
  frame.col(0) = (c.b - c.a).normalized();
  frame.col(2) = *normal;
  frame.col(1) = normal->cross(frame.col(0));
  return frame;
}

}  // namespace

Vec3 point_at(const TriangleCorners& c, const Vec3& barycentric) {
  return barycentric.x() * c.a + barycentric.y() * c.b + barycentric.z() * c.c;
}

std::optional<Vec3> unit_normal(const TriangleCorners& c) {
  const Vec3 ab = c.b - c.a;
  const Vec3 ac = c.c - c.a;
  const Vec3 normal = ab.cross(ac);
  if (!(normal.squaredNorm() > kFlatSinSq * ab.squaredNorm() * ac.squaredNorm())) {
    return std::nullopt;
  }
  return Vec3(normal.normalized());
}

std::optional<Placement> place(const TriangleCorners& c, const Vec3& p) {
  const std::optional<Mat3> frame = frame_of(c);
  if (!frame) return std::nullopt;
  const ClosestPoint nearest = closest_point_on_triangle(p, c.a, c.b, c.c);
  return Placement{nearest.barycentric, frame->transpose() * (p - nearest.point)};
}

std::optional<Vec3> position_of(const TriangleCorners& c, const Placement& placement) {
  const std::optional<Mat3> frame = frame_of(c);
  if (!frame) return std::nullopt;
  const Vec3 p = point_at(c, placement.barycentric) + *frame * placement.offset;
  if (!p.allFinite()) return std::nullopt;
  return p;
}

Vec3 contact_normal(const Vec3& centre, const TriangleCorners& c, const ClosestPoint& nearest) {
  const Vec3 offset = centre - nearest.point;
  const Vec3 face = (c.b - c.a).cross(c.c - c.a);
  const Real face_length = face.norm();
  if (face_length > 0) {
    const Vec3 normal = face / face_length;
    const Real height = normal.dot(offset);
    const Real across = (offset - normal * height).norm();
    if (height != 0 &&
        (nearest.barycentric.minCoeff() > 0 || across <= kOverFace * std::abs(height))) {
      return height > 0 ? normal : Vec3(-normal);
    }
  }
  const Real distance = offset.norm();
  return distance > 0 ? Vec3(offset / distance) : Vec3::Zero();
}

}  // namespace felt
