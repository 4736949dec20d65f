#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.hpp"

namespace felt {

/// Area-weighted unit vertex normals of a triangle surface (zero for a vertex no triangle with
/// area touches). Computed when a surface is published, not every step: only clients and the
/// haptic side look at normals.
void compute_vertex_normals(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                            std::vector<Vec3>& normals);

/// Per corner of each triangle, the unit sum of the area-weighted normals of the triangles
/// around that corner whose normals turn from the triangle's own by at most the crease angle
/// (`cos_crease` its cosine): the vertex normal across gentle edges, the face's own normal on
/// either side of a sharp one, so interpolating them over a flat face gives its normal up to
/// its border. face_index[face_offset[v] .. [v + 1]) are the triangles with corner v;
/// `face_normals` receives their area-weighted normals.
void compute_corner_normals(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                            std::span<const std::uint32_t> face_offset,
                            std::span<const std::uint32_t> face_index, Real cos_crease,
                            std::vector<Vec3>& face_normals,
                            std::vector<std::array<Vec3, 3>>& corner_normals);

}  // namespace felt
