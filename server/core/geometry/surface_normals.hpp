#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/math/types.hpp"

namespace felt {

/// Area-weighted unit vertex normals of a triangle surface (zero for a vertex no triangle with
/// area touches). Computed when a surface is published, not every step: only clients and the
/// haptic side look at normals.
void compute_vertex_normals(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                            std::vector<Vec3>& normals);

/// A triangle's normal weighted by its area (the plain cross product) and as a unit vector.
struct FaceNormal {
  Vec3 area = Vec3::Zero();
  Vec3 unit = Vec3::Zero();  ///< zero for a triangle without area
};

FaceNormal face_normal(std::span<const Vec3> positions, const Triangle& triangle);

/// The normals at the corners of triangle `f`: for each corner, the unit sum of the
/// area-weighted normals of the triangles around it whose normals turn from f's by at most the
/// crease angle (`cos_crease` its cosine). Across gentle edges these are the vertex normals;
/// on either side of a sharp edge each face keeps its own normal, so interpolating them over a
/// flat face gives its normal up to its border. face_index[face_offset[v] .. [v + 1]) are the
/// triangles with corner v; normal_of(g) gives triangle g's FaceNormal.
template <class NormalOf>
std::array<Vec3, 3> corner_normals(std::span<const Triangle> triangles, std::uint32_t f,
                                   std::span<const std::uint32_t> face_offset,
                                   std::span<const std::uint32_t> face_index, Real cos_crease,
                                   NormalOf&& normal_of) {
  const Vec3 own = normal_of(f).unit;
  std::array<Vec3, 3> out;
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = triangles[f][k];
    Vec3 sum = Vec3::Zero();
    for (std::uint32_t i = face_offset[v]; i < face_offset[v + 1]; ++i) {
      const FaceNormal& other = normal_of(face_index[i]);
      if (own.dot(other.unit) >= cos_crease) sum += other.area;
    }
    const Real norm = sum.norm();
    out[k] = norm > 0 ? Vec3(sum / norm) : own;
  }
  return out;
}

}  // namespace felt
