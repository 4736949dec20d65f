#include "core/geometry/surface_normals.hpp"

namespace felt {

void compute_vertex_normals(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                            std::vector<Vec3>& normals) {
  normals.assign(positions.size(), Vec3::Zero());
  for (const Triangle& t : triangles) {
    // the unnormalised cross product weighs each face by its area
    const Vec3 area_normal =
        (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
    for (std::uint32_t corner : t) normals[corner] += area_normal;
  }
  for (Vec3& n : normals) {
    const Real norm = n.norm();
    if (norm > 0) n /= norm;
  }
}

FaceNormal face_normal(std::span<const Vec3> positions, const Triangle& triangle) {
  FaceNormal n;
  n.area = (positions[triangle[1]] - positions[triangle[0]])
               .cross(positions[triangle[2]] - positions[triangle[0]]);
  const Real norm = n.area.norm();
  if (norm > 0) n.unit = n.area / norm;
  return n;
}

}  // namespace felt
