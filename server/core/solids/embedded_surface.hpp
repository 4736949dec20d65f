#pragma once
// A fine triangle surface carried by a coarse tetrahedral lattice: each fine vertex stores the
// tetrahedron it lies in and its barycentric coordinates there (thesis 2 §7.1). The fine
// surface is what clients see and touch; the lattice is what is simulated.

#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry/tet_mesh.hpp"
#include "core/geometry/triangle_mesh.hpp"

namespace felt {

using Vec4 = Eigen::Matrix<Real, 4, 1>;

struct EmbeddedSurface {
  std::vector<std::uint32_t> tet;  ///< per fine vertex: the index of its tetrahedron
  std::vector<Vec4> weights;       ///< per fine vertex: barycentric coordinates in it
  std::vector<Triangle> triangles;
  std::vector<Vec2> uv;      ///< per fine vertex, or empty
  bool lattice_own = false;  ///< the lattice's own surface (embed_lattice_surface), not a finer one

  std::size_t vertex_count() const { return tet.size(); }

  /// The fine vertices for the lattice nodes at `nodes`.
  void positions(std::span<const Vec3> nodes, std::span<const Tetrahedron> tets,
                 std::vector<Vec3>& out) const;
  /// A value per fine vertex, interpolated from one per lattice node by the barycentric
  /// coordinates.
  void values(std::span<const float> node_values, std::span<const Tetrahedron> tets,
              std::vector<float>& out) const;
};

/// Embeds every vertex of `fine` in the tetrahedron of `lattice` that contains it (the one it is
/// deepest in, when it lies on a shared face), or, for a vertex outside every tetrahedron, in the
/// nearest one (its coordinates then extrapolate). The tetrahedra must be positively oriented;
/// they are found through a uniform grid of their bounding boxes, not by trying them all.
EmbeddedSurface embed_surface(const TetMesh& lattice, const TriangleMesh& fine);

/// A lattice's own surface as an embedded one: its surface nodes only, in node order, each with
/// weight 1 at its corner of a tetrahedron it belongs to, and `surface` (faces over node indices)
/// numbered over them. So a solid without a fine surface shows clients its surface and not its
/// interior nodes (an 11 × 11 × 11 box lattice: 602 vertices of its 1,331 nodes).
EmbeddedSurface embed_lattice_surface(const TetMesh& lattice, std::span<const Triangle> surface);

}  // namespace felt
