#include "core/collision/triangle_hash.hpp"

#include <algorithm>
#include <cmath>

#include "core/math/check.hpp"

namespace felt {
namespace {

// A cloth triangle about one cell across overlaps up to 2 × 2 × 2 cells, a few more while it
// moves; one spanning more than this is not worth storing in every cell it touches.
constexpr std::uint64_t kMaxCellsPerTriangle = 64;

}  // namespace

TriangleHash::TriangleHash(std::span<const Triangle> triangles, std::span<const Vec3> positions)
    : triangles_(triangles.begin(), triangles.end()), bounds_(triangles.size()) {
  for (const Triangle& t : triangles) {
    vertex_count_ = std::max(vertex_count_, std::size_t{*std::max_element(t.begin(), t.end())} + 1);
  }
  FELT_CHECK(positions.size() >= vertex_count_);
  Real total = 0;
  for (const Triangle& t : triangles) {
    for (int e = 0; e < 3; ++e) total += (positions[t[(e + 1) % 3]] - positions[t[e]]).norm();
  }
  const Real mean = total / static_cast<Real>(3 * triangles.size());
  // a surface without extent (no triangles, or all collapsed to points) fits any cell
  if (mean > 0 && std::isfinite(mean)) cell_size_ = mean;
  refit(positions, positions);
}

void TriangleHash::refit(std::span<const Vec3> from, std::span<const Vec3> to) {
  FELT_CHECK(from.size() == to.size() && from.size() >= vertex_count_);
  hash_.begin(cell_size_, triangles_.size());
  oversized_.clear();
  for (std::uint32_t i = 0; i < triangles_.size(); ++i) {
    Aabb& box = bounds_[i];
    box = Aabb{};
    for (const std::uint32_t v : triangles_[i]) {
      box.grow(from[v]);
      box.grow(to[v]);
    }
    const SpatialHash::Cell first = hash_.cell_of(box.lo);
    const SpatialHash::Cell last = hash_.cell_of(box.hi);
    std::uint64_t cells = 1;
    for (int a = 0; a < 3; ++a) cells *= static_cast<std::uint64_t>(last[a] - first[a] + 1);
    if (cells > kMaxCellsPerTriangle) {
      oversized_.push_back(i);
      continue;
    }
    SpatialHash::Cell cell;
    for (cell[2] = first[2]; cell[2] <= last[2]; ++cell[2]) {
      for (cell[1] = first[1]; cell[1] <= last[1]; ++cell[1]) {
        for (cell[0] = first[0]; cell[0] <= last[0]; ++cell[0]) hash_.insert(0, i, cell);
      }
    }
  }
}

void TriangleHash::collect(const Aabb& region, std::vector<std::uint32_t>& out) const {
  if (region.empty()) return;
  const std::size_t first = out.size();
  const auto consider = [&](std::uint32_t triangle) {
    if (bounds_[triangle].overlaps(region)) out.push_back(triangle);
  };
  hash_.for_each_in_box(region.lo, region.hi, [&](std::uint32_t /*body*/, std::uint32_t triangle) {
    consider(triangle);
  });
  for (const std::uint32_t triangle : oversized_) consider(triangle);
  // a triangle stored in several of the region's cells was found once per cell; sorting what
  // this query appended, not a shared mark array, keeps concurrent queries independent
  const auto appended = out.begin() + static_cast<std::ptrdiff_t>(first);
  std::sort(appended, out.end());
  out.erase(std::unique(appended, out.end()), out.end());
}

std::unique_ptr<TriangleQuery> TriangleHash::clone() const {
  return std::make_unique<TriangleHash>(*this);
}

}  // namespace felt
