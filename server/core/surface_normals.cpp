#include "core/surface_normals.hpp"

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

void compute_corner_normals(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                            std::span<const std::uint32_t> face_offset,
                            std::span<const std::uint32_t> face_index, Real cos_crease,
                            std::vector<Vec3>& face_normals,
                            std::vector<std::array<Vec3, 3>>& corner_normals) {
  face_normals.resize(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    face_normals[f] = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
  }
  corner_normals.resize(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Vec3 own = face_normals[f].normalized();
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = triangles[f][k];
      Vec3 sum = Vec3::Zero();
      for (std::uint32_t i = face_offset[v]; i < face_offset[v + 1]; ++i) {
        const Vec3& other = face_normals[face_index[i]];
        // cos(angle) ≥ cos_crease, without dividing by |other|
        if (own.dot(other) >= cos_crease * other.norm()) sum += other;
      }
      const Real norm = sum.norm();
      corner_normals[f][k] = norm > 0 ? Vec3(sum / norm) : own;
    }
  }
}

}  // namespace felt
