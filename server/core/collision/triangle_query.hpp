#pragma once
// Which triangles of a deforming surface may lie in a region: the haptic query's broad phase
// (thesis 1 §6, §9). The surface moves from one physics snapshot to the next; a structure
// bounds every triangle over both states, so one refit per physics step answers for every
// interpolated state the haptic loop renders in between.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/math/aabb.hpp"
#include "core/math/types.hpp"

namespace felt {

enum class TriangleQueryKind : std::uint8_t {
  kBruteForce,   ///< every triangle: the reference the others are checked against
  kBvhSphere2,   ///< bounding-sphere hierarchy, binary
  kBvhSphere4,   ///< bounding-sphere hierarchy, four children per node
  kBvhAabb2,     ///< axis-aligned box hierarchy, binary
  kBvhAabb4,     ///< axis-aligned box hierarchy, four children per node
  kSpatialHash,  ///< optimized spatial hashing over triangles (Teschner et al.)
};

/// "brute_force", "bvh_sphere_2", "bvh_sphere_4", "bvh_aabb_2", "bvh_aabb_4", "spatial_hash".
std::string_view to_string(TriangleQueryKind kind);
std::optional<TriangleQueryKind> triangle_query_kind(std::string_view name);

class TriangleQuery {
 public:
  virtual ~TriangleQuery() = default;

  /// Bounds every triangle over its motion from `from` to `to` (vertex positions, the topology
  /// the structure was made for). Without recursion, so deep trees cannot overflow the stack.
  virtual void refit(std::span<const Vec3> from, std::span<const Vec3> to) = 0;

  /// Appends to `out` every triangle whose bounds overlap `region`: a superset of the triangles
  /// that reach into it at any state between `from` and `to`, each once.
  virtual void collect(const Aabb& region, std::vector<std::uint32_t>& out) const = 0;

  /// An independent copy (snapshots are immutable: the physics thread refits a copy).
  virtual std::unique_ptr<TriangleQuery> clone() const = 0;

  virtual TriangleQueryKind kind() const = 0;
};

/// A structure of `kind` over `triangles`, fitted to the static surface at `positions`.
std::unique_ptr<TriangleQuery> make_triangle_query(TriangleQueryKind kind,
                                                   std::span<const Triangle> triangles,
                                                   std::span<const Vec3> positions);

}  // namespace felt
