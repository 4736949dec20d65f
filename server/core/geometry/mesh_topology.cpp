#include "core/geometry/mesh_topology.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace felt {

std::size_t unique_edge_count(std::span<const Triangle> triangles) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * triangles.size());
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  return static_cast<std::size_t>(std::unique(edges.begin(), edges.end()) - edges.begin());
}

}  // namespace felt
