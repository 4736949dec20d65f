#pragma once
// A bounding-volume hierarchy over the triangles of one deforming surface (thesis 1 §6.1 and
// §8.2): built once, top-down by median splits, one triangle per leaf, then only refitted, never
// rebuilt, and never by recursion.
//
// Two refits, kept selectable so that they can be measured (tests/bench/triangle_query_bench,
// docs/results/haptics.md): the thesis's, which refits only the volumes that were escaped, and a
// plain pass over every node in reverse breadth-first order. The plain pass is the default: on a
// falling, swinging cloth nearly every leaf escapes every step, and the thesis's refit, which
// must test before it fits, took 1.3-1.5x as long (19,602 triangles: 0.26 against 0.18 ms for
// binary boxes, 0.72 against 0.50 ms for binary spheres). It wins only on a cloth at rest (0.11
// against 0.16 ms for boxes), where it finds nothing to do; and its volumes only grow until
// escaped, so they are never tighter.

#include <cstdint>
#include <span>
#include <vector>

#include "core/collision/triangle_query.hpp"

namespace felt {

/// A sphere. The hierarchy's spheres enclose what they bound but are not the smallest that do
/// (Quinlan's and Brown et al.'s trade: cheaper to update, a little looser). A leaf's sphere
/// encloses its triangle's bounding box over both states, so that it misses nothing a box
/// would find.
struct BoundingSphere {
  Vec3 center = Vec3::Zero();
  Real radius = 0;
};

enum class BvhVolume : std::uint8_t { kSphere, kAabb };

/// How a refit restores the volumes after the surface moved.
enum class BvhRefit : std::uint8_t {
  /// Thesis 1 §6.1.3 and §8.2: the leaves whose triangle left its volume are found by scanning
  /// the array of leaves and refitted; then parents, highest breadth-first id first, each at most
  /// once, are refitted where a refitted child escaped them. A volume that was not escaped keeps
  /// its old, looser size.
  kEscaped,
  /// Every leaf tight around its triangle, then every internal node from its children, in
  /// reverse breadth-first order (children have higher ids than their parent).
  kReverseOrder,
};

/// How the leaves whose triangle left its volume are found (thesis 1 Table 9.2).
enum class DeformedLeafSearch : std::uint8_t {
  kLeafArray,  ///< a scan of the array of leaves, as the thesis's refit does
  kTopDown,    ///< a walk down from the root through every node
};

struct TriangleBvhOptions {
  BvhVolume volume = BvhVolume::kSphere;
  std::uint32_t branching = 2;  ///< children per internal node: 2 or 4
  BvhRefit refit = BvhRefit::kReverseOrder;
};

class TriangleBvh final : public TriangleQuery {
 public:
  static constexpr std::uint32_t kNoParent = ~std::uint32_t{0};

  /// A node of the hierarchy. Nodes are numbered breadth-first: a parent's id is below its
  /// children's, and the children of a node have consecutive ids.
  struct Node {
    std::uint32_t parent = kNoParent;
    std::uint32_t first = 0;        ///< the first child's id, or for a leaf its triangle
    std::uint32_t child_count = 0;  ///< 0 for a leaf; up to the branching factor otherwise

    bool leaf() const { return child_count == 0; }
  };

  /// Builds the hierarchy over `triangles` from their centroids at `positions`: each node's
  /// triangles are split at the median along the longest axis of their centroids' bounds (for
  /// four children, each half again along its own longest axis), down to one triangle per leaf.
  TriangleBvh(std::span<const Triangle> triangles, std::span<const Vec3> positions,
              TriangleBvhOptions options = {});

  void refit(std::span<const Vec3> from, std::span<const Vec3> to) override;
  void collect(const Aabb& region, std::vector<std::uint32_t>& out) const override;
  std::unique_ptr<TriangleQuery> clone() const override;
  TriangleQueryKind kind() const override;

  const TriangleBvhOptions& options() const { return options_; }
  std::span<const Node> nodes() const { return nodes_; }
  /// The leaves' node ids, ascending.
  std::span<const std::uint32_t> leaves() const { return leaves_; }
  /// Node volumes by node id: spheres() for BvhVolume::kSphere, boxes() for kAabb (the other is
  /// empty).
  std::span<const BoundingSphere> spheres() const { return spheres_; }
  std::span<const Aabb> boxes() const { return boxes_; }
  /// How many node volumes the last refit changed (thesis 1 Table 9.1's #u).
  std::size_t last_refit_updates() const { return last_refit_updates_; }

  /// Appends the ids of the leaves whose triangle, over its motion from `from` to `to`, is not
  /// inside the leaf's volume.
  void find_deformed_leaves(std::span<const Vec3> from, std::span<const Vec3> to,
                            DeformedLeafSearch search, std::vector<std::uint32_t>& out) const;

 private:
  template <class Volume>
  void refit_escaped(std::vector<Volume>& volumes, std::span<const Vec3> from,
                     std::span<const Vec3> to);
  template <class Volume>
  void refit_reverse_order(std::vector<Volume>& volumes, std::span<const Vec3> from,
                           std::span<const Vec3> to);
  template <class Volume>
  void collect_in(const std::vector<Volume>& volumes, const Aabb& region,
                  std::vector<std::uint32_t>& out) const;
  template <class Volume>
  void find_deformed_leaves_in(const std::vector<Volume>& volumes, std::span<const Vec3> from,
                               std::span<const Vec3> to, DeformedLeafSearch search,
                               std::vector<std::uint32_t>& out) const;

  TriangleBvhOptions options_;
  std::vector<Triangle> triangles_;
  std::size_t vertex_count_ = 0;  ///< one past the highest vertex index the triangles use
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> leaves_;
  std::vector<BoundingSphere> spheres_;
  std::vector<Aabb> boxes_;
  std::size_t last_refit_updates_ = 0;
  // the escaped refit's queue of parents (two sorted lists), kept to spare allocations
  std::vector<std::uint32_t> leaf_parents_;
  std::vector<std::uint32_t> parents_;
};

}  // namespace felt
