#pragma once
// Which nodes of which soft solids lie inside which other solids' tetrahedra, found by
// optimized spatial hashing (Teschner et al. 2003, thesis 2 §2.2, Algorithm 6.2).

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "core/collision/spatial_hash.hpp"
#include "core/solids/solid_body.hpp"

namespace felt {

/// A node inside a tetrahedron of another body (or of its own body, when self-collision is on
/// and the node is neither a corner of the tetrahedron nor an edge neighbour of one).
struct CollidingNode {
  std::uint32_t body = 0;
  std::uint32_t node = 0;
  std::uint32_t penetrated_body = 0;
  std::uint32_t tet = 0;  ///< in the penetrated body
};

struct CollisionSet {
  /// One entry per (node, penetrated body) pair: a node inside two bodies appears twice
  /// (the thesis handled at most one; Felt resolves against each).
  std::vector<CollidingNode> nodes;
  /// per body: indices into its topology().surface of the triangles with a colliding or
  /// participating corner (stage TC)
  std::vector<std::vector<std::uint32_t>> triangles;
};

/// Mean rest length of the edges of all bodies, 0 when there are none: the thesis's best cell
/// size for the hash grid (§6.3.1).
Real mean_rest_edge_length(std::span<const SolidBody> bodies);

/// What the last detection looked at and found (Table 7.3 counts colliding nodes and
/// triangles).
struct CollisionCounts {
  std::size_t hashed_nodes = 0;     ///< those in their body's reach (see detect)
  std::size_t candidates = 0;       ///< node–tetrahedron pairs the hash proposed
  std::size_t colliding_nodes = 0;  ///< entries of CollisionSet::nodes
  std::size_t colliding_triangles = 0;
};

/// Finds nodes inside other bodies' tetrahedra (Algorithm 6.2) and the surface triangles they
/// may have entered through (§6.3.4). Keeps its table and flags from step to step, so a step
/// allocates nothing once the bodies stop changing.
class SolidCollisionDetector {
 public:
  /// Edge of the grid's cubic cells, > 0; pass mean_rest_edge_length of the bodies.
  void set_cell_size(Real cell_size);
  Real cell_size() const { return cell_size_; }

  /// Phase 1 hashes the nodes inside their body's reach (the hull of the overlaps of its
  /// bounding box with those of the bodies it can collide with); phase 2 tests the nodes in the
  /// cells each tetrahedron's box overlaps within those boxes (of the tetrahedra whose box meets
  /// their body's reach), by box and then by barycentric coordinates: the same nodes, in the
  /// same order, as hashing and querying everything. Writes out.nodes and remembers which nodes
  /// collide or are corners of a tetrahedron containing a colliding node.
  ///
  /// A node of the tetrahedron's own body counts only when the body has self_collision and the
  /// node is neither a corner of the tetrahedron nor an edge neighbour of one: a node that
  /// close is a folded or inverted element, not a contact, and pushing it out through the
  /// surface would tear the mesh.
  void detect(std::span<const SolidBody> bodies, CollisionSet& out);

  /// Stage TC: per body, every surface triangle with a colliding or participating corner, in
  /// surface order. Call after detect with the same bodies.
  void collect_triangles(std::span<const SolidBody> bodies, CollisionSet& out);

  const CollisionCounts& counts() const { return counts_; }

 private:
  Real cell_size_ = 0;
  SpatialHash hash_;
  CollisionCounts counts_;
  std::vector<std::size_t> node_offset_;                ///< first flat node index of each body
  std::vector<Eigen::AlignedBox<Real, 3>> body_boxes_;  ///< of each body's nodes
  /// per body: the hull of its box's overlaps with the boxes of the bodies it can touch
  std::vector<Eigen::AlignedBox<Real, 3>> reach_;
  std::vector<std::uint8_t> outcodes_;  ///< per flat node: beyond which faces of its reach
  std::vector<std::uint8_t> colliding_;
  std::vector<std::uint8_t> participating_;
  /// the last body found to contain each node: one entry per (node, penetrated body), as
  /// tetrahedra are visited body by body
  std::vector<std::uint32_t> last_penetrated_;
};

}  // namespace felt
