#pragma once

#include <cstddef>
#include <span>

#include "core/math/types.hpp"

namespace felt {

/// The number of distinct undirected edges of a triangle mesh.
std::size_t unique_edge_count(std::span<const Triangle> triangles);

}  // namespace felt
