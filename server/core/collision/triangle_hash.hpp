#pragma once
// Optimized spatial hashing over the triangles of one deforming surface (Teschner et al. 2003, as
// thesis 1 §8.2 adapts it for haptics: only triangles are hashed, each by its bounding box, in
// one stage, and the whole table is rehashed after every physics step).

#include <cstdint>
#include <span>
#include <vector>

#include "core/collision/spatial_hash.hpp"
#include "core/collision/triangle_query.hpp"

namespace felt {

class TriangleHash final : public TriangleQuery {
 public:
  /// Cells as large as the mean edge length of the surface at `positions` (Teschner et al.'s
  /// choice); the table has SpatialHash::table_size_for(triangle count) slots.
  TriangleHash(std::span<const Triangle> triangles, std::span<const Vec3> positions);

  /// Rehashes every triangle into every cell its bounding box over both states overlaps.
  void refit(std::span<const Vec3> from, std::span<const Vec3> to) override;
  /// Looks in the region's cells; a triangle found there counts when its bounding box overlaps
  /// the region (the thesis's prefilter against hash collisions and large cells).
  void collect(const Aabb& region, std::vector<std::uint32_t>& out) const override;
  std::unique_ptr<TriangleQuery> clone() const override;
  TriangleQueryKind kind() const override { return TriangleQueryKind::kSpatialHash; }

  Real cell_size() const { return cell_size_; }
  std::size_t table_size() const { return hash_.table_size(); }

 private:
  std::vector<Triangle> triangles_;
  std::size_t vertex_count_ = 0;  ///< one past the highest vertex index the triangles use
  Real cell_size_ = 1;
  std::vector<Aabb> bounds_;  ///< each triangle's bounding box over both states
  /// Triangles whose box spans too many cells (stretched far, or moving fast): tested by their
  /// box at every query instead of filling the table.
  std::vector<std::uint32_t> oversized_;
  SpatialHash hash_;  ///< entries are (0, triangle)
};

}  // namespace felt
