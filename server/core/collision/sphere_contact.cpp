#include "core/collision/sphere_contact.hpp"

#include "core/geometry/triangle_geometry.hpp"

namespace felt {
namespace {

// A centre closer to the surface than this fraction of the radius (squared) has no reliable
// direction from the nearest point; the face normal is used instead.
constexpr Real kOnSurfaceSq = 1e-24;

/// Unit normal of a triangle, or zero when it has no area.
Vec3 face_normal(std::span<const Vec3> positions, const Triangle& tri) {
  const Vec3 face =
      (positions[tri[1]] - positions[tri[0]]).cross(positions[tri[2]] - positions[tri[0]]);
  const Real norm = face.norm();
  return norm > 0 ? Vec3(face / norm) : Vec3::Zero();
}

}  // namespace

std::optional<SphereContact> find_sphere_contact(std::span<const Vec3> positions,
                                                 std::span<const Triangle> triangles,
                                                 const Vec3& center, Real radius) {
  std::optional<SphereContact> best;
  Real best_distance_sq = radius * radius;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    const ClosestPoint closest =
        closest_point_on_triangle(center, positions[tri[0]], positions[tri[1]], positions[tri[2]]);
    const Real distance_sq = (center - closest.point).squaredNorm();
    // written so that a NaN distance (a corrupt triangle) never wins
    if (!(distance_sq < best_distance_sq)) continue;
    if (distance_sq <= kOnSurfaceSq * radius * radius && face_normal(positions, tri).isZero()) {
      continue;  // a triangle without area through the centre gives no direction to push
    }
    best_distance_sq = distance_sq;
    best = SphereContact{static_cast<std::uint32_t>(t), closest.point, closest.barycentric,
                         Vec3::Zero(), 0};
  }
  if (!best) return best;

  const Vec3 offset = center - best->point;
  const Real distance = offset.norm();
  if (distance * distance > kOnSurfaceSq * radius * radius) {
    best->normal = offset / distance;
  } else {
    const Triangle& tri = triangles[best->triangle];
    const Vec3 face =
        (positions[tri[1]] - positions[tri[0]]).cross(positions[tri[2]] - positions[tri[0]]);
    const Real norm = face.norm();
    if (norm == 0) return std::nullopt;  // a degenerate triangle gives no direction to push
    best->normal = face / norm;
  }
  best->depth = radius - distance;
  return best;
}

}  // namespace felt
