#include "core/geometry/tet_mesh.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace felt {
namespace {

// A list per node as offsets and entries, from the (node, entry) pairs `each` emits: called
// twice, to count and then to fill
template <class Each>
void node_lists(std::size_t node_count, Each each, std::vector<std::uint32_t>& offset,
                std::vector<std::uint32_t>& index) {
  offset.assign(node_count + 1, 0);
  each([&](std::uint32_t node, std::uint32_t) { ++offset[node + 1]; });
  for (std::size_t n = 0; n < node_count; ++n) offset[n + 1] += offset[n];
  index.resize(offset.back());
  std::vector<std::uint32_t> fill(offset.begin(), offset.end() - 1);
  each([&](std::uint32_t node, std::uint32_t entry) { index[fill[node]++] = entry; });
}

}  // namespace

Real signed_volume(std::span<const Vec3> x, const Tetrahedron& t) {
  return signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
}

void orient_positive(TetMesh& mesh) {
  for (Tetrahedron& t : mesh.tets) {
    if (signed_volume(mesh.nodes, t) < 0) std::swap(t[2], t[3]);
  }
}

TetTopology build_topology(const TetMesh& mesh) {
  TetTopology topology;
  const auto node_count = static_cast<std::uint32_t>(mesh.nodes.size());

  topology.edges.reserve(mesh.tets.size() * 6);
  for (const Tetrahedron& t : mesh.tets) {
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) {
        topology.edges.push_back({std::min(t[a], t[b]), std::max(t[a], t[b])});
      }
    }
  }
  std::ranges::sort(topology.edges);
  const auto [first, last] = std::ranges::unique(topology.edges);
  topology.edges.erase(first, last);

  node_lists(
      node_count,
      [&](auto emit) {
        for (const Edge& e : topology.edges) {
          emit(e[0], e[1]);
          emit(e[1], e[0]);
        }
      },
      topology.neighbour_offset, topology.neighbour_index);

  // The outward faces of a positive tetrahedron (a, b, c, d): d lies on the normal's side of
  // (a, b, c), so that face turns round to (a, c, b), and so on.
  std::map<std::array<std::uint32_t, 3>, std::pair<Triangle, int>> faces;
  for (const Tetrahedron& t : mesh.tets) {
    const std::array<Triangle, 4> outward = {Triangle{t[0], t[2], t[1]}, Triangle{t[0], t[1], t[3]},
                                             Triangle{t[0], t[3], t[2]},
                                             Triangle{t[1], t[2], t[3]}};
    for (const Triangle& face : outward) {
      std::array<std::uint32_t, 3> key = face;
      std::ranges::sort(key);
      auto [it, inserted] = faces.try_emplace(key, face, 0);
      ++it->second.second;
    }
  }
  topology.on_surface.assign(node_count, 0);
  for (const auto& [key, face_and_count] : faces) {
    if (face_and_count.second != 1) continue;
    topology.surface.push_back(face_and_count.first);
    for (std::uint32_t n : key) topology.on_surface[n] = 1;
  }
  node_lists(
      node_count,
      [&](auto emit) {
        for (std::uint32_t f = 0; f < topology.surface.size(); ++f) {
          for (std::uint32_t corner : topology.surface[f]) emit(corner, f);
        }
      },
      topology.surface_face_offset, topology.surface_face_index);
  return topology;
}

Real total_volume(std::span<const Vec3> x, std::span<const Tetrahedron> tets) {
  Real volume = 0;
  for (const Tetrahedron& t : tets) volume += signed_volume(x, t);
  return volume;
}

}  // namespace felt
