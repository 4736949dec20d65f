#include "core/collision/listed_triangle_query.hpp"

namespace felt {

ListedTriangleQuery::ListedTriangleQuery(std::span<const Triangle> triangles,
                                         std::vector<std::uint32_t> listed)
    : triangles_(triangles), listed_(std::move(listed)), bounds_(listed_.size()) {}

void ListedTriangleQuery::refit(std::span<const Vec3> from, std::span<const Vec3> to) {
  for (std::size_t i = 0; i < listed_.size(); ++i) {
    Aabb box;
    for (const std::uint32_t v : triangles_[listed_[i]]) {
      box.grow(from[v]);
      box.grow(to[v]);
    }
    bounds_[i] = box;
  }
}

void ListedTriangleQuery::collect(const Aabb& region, std::vector<std::uint32_t>& out) const {
  for (std::size_t i = 0; i < listed_.size(); ++i) {
    if (bounds_[i].overlaps(region)) out.push_back(listed_[i]);
  }
}

std::unique_ptr<TriangleQuery> ListedTriangleQuery::clone() const {
  return std::make_unique<ListedTriangleQuery>(*this);
}

}  // namespace felt
