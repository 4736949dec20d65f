#pragma once
// A broad phase over a few listed triangles of a large surface, by their boxes: a local model
// holds the few hundred triangles near a proxy out of a surface of any size
// (core/haptics/extrapolated_surface.hpp), and the list changes with every model.

#include <vector>

#include "core/collision/triangle_query.hpp"

namespace felt {

class ListedTriangleQuery final : public TriangleQuery {
 public:
  /// Over `listed` (indices into `triangles`, which must outlive the query).
  ListedTriangleQuery(std::span<const Triangle> triangles, std::vector<std::uint32_t> listed);

  void refit(std::span<const Vec3> from, std::span<const Vec3> to) override;
  void collect(const Aabb& region, std::vector<std::uint32_t>& out) const override;
  std::unique_ptr<TriangleQuery> clone() const override;
  TriangleQueryKind kind() const override { return TriangleQueryKind::kBruteForce; }

 private:
  std::span<const Triangle> triangles_;
  std::vector<std::uint32_t> listed_;
  std::vector<Aabb> bounds_;  ///< per listed triangle, over [from, to]
};

}  // namespace felt
