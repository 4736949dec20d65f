#pragma once
// Tetrahedral meshes of soft solids and the topology derived from them (thesis 2 §1.1, §6.3).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/math/types.hpp"

namespace felt {

/// Four node indices, ordered so that the signed volume is positive.
using Tetrahedron = std::array<std::uint32_t, 4>;
using Edge = std::array<std::uint32_t, 2>;

/// A volumetric mesh as read or built, before it becomes a body.
struct TetMesh {
  std::vector<Vec3> nodes;
  std::vector<Tetrahedron> tets;
};

/// (1/6) (b − a)·((c − a) × (d − a)): positive when d lies on the side of the counter-clockwise
/// triangle (a, b, c)'s normal.
inline Real signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6;
}
Real signed_volume(std::span<const Vec3> x, const Tetrahedron& t);

/// Swaps two nodes of every tetrahedron with a negative volume, so all are positive.
void orient_positive(TetMesh& mesh);

/// Everything the solver and the collision pipeline look up about a mesh, built once.
struct TetTopology {
  std::vector<Edge> edges;  ///< unique, each as (lower, higher)
  std::vector<Triangle>
      surface;  ///< faces of exactly one tetrahedron, counter-clockwise from outside
  /// neighbours of node n through edges: neighbour_index[neighbour_offset[n] .. [n + 1])
  std::vector<std::uint32_t> neighbour_offset;
  std::vector<std::uint32_t> neighbour_index;
  std::vector<std::uint8_t> on_surface;  ///< per node: 1 when it is a corner of a surface face
  /// surface faces around node n: surface_face_index[surface_face_offset[n] .. [n + 1])
  std::vector<std::uint32_t> surface_face_offset;
  std::vector<std::uint32_t> surface_face_index;

  std::span<const std::uint32_t> neighbours(std::uint32_t n) const {
    return std::span(neighbour_index)
        .subspan(neighbour_offset[n], neighbour_offset[n + 1] - neighbour_offset[n]);
  }
};

/// Builds the topology of a mesh whose tetrahedra are positively oriented.
TetTopology build_topology(const TetMesh& mesh);

/// Sum of the signed volumes of all tetrahedra at positions x.
Real total_volume(std::span<const Vec3> x, std::span<const Tetrahedron> tets);

}  // namespace felt
