#pragma once

#include <span>
#include <vector>

#include "core/types.hpp"

namespace felt {

/// Area-weighted unit vertex normals of a triangle surface (zero for a vertex no triangle with
/// area touches). Computed when a surface is published, not every step: only clients and the
/// haptic side look at normals.
void compute_vertex_normals(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                            std::vector<Vec3>& normals);

}  // namespace felt
