#include "core/collision/triangle_query.hpp"

#include <array>
#include <numeric>
#include <utility>

#include "core/collision/triangle_bvh.hpp"
#include "core/collision/triangle_hash.hpp"
#include "core/math/check.hpp"

namespace felt {
namespace {

constexpr std::array<std::pair<TriangleQueryKind, std::string_view>, 6> kNames{{
    {TriangleQueryKind::kBruteForce, "brute_force"},
    {TriangleQueryKind::kBvhSphere2, "bvh_sphere_2"},
    {TriangleQueryKind::kBvhSphere4, "bvh_sphere_4"},
    {TriangleQueryKind::kBvhAabb2, "bvh_aabb_2"},
    {TriangleQueryKind::kBvhAabb4, "bvh_aabb_4"},
    {TriangleQueryKind::kSpatialHash, "spatial_hash"},
}};

/// Every triangle, every time: nothing to refit, nothing to miss.
class BruteForceQuery final : public TriangleQuery {
 public:
  explicit BruteForceQuery(std::size_t triangle_count) : count_(triangle_count) {}

  void refit(std::span<const Vec3>, std::span<const Vec3>) override {}
  void collect(const Aabb&, std::vector<std::uint32_t>& out) const override {
    const std::size_t first = out.size();
    out.resize(first + count_);
    std::iota(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(), std::uint32_t{0});
  }
  std::unique_ptr<TriangleQuery> clone() const override {
    return std::make_unique<BruteForceQuery>(*this);
  }
  TriangleQueryKind kind() const override { return TriangleQueryKind::kBruteForce; }

 private:
  std::size_t count_;
};

}  // namespace

std::string_view to_string(TriangleQueryKind kind) {
  for (const auto& [k, name] : kNames) {
    if (k == kind) return name;
  }
  return "unknown";
}

std::optional<TriangleQueryKind> triangle_query_kind(std::string_view name) {
  for (const auto& [kind, n] : kNames) {
    if (n == name) return kind;
  }
  return std::nullopt;
}

std::unique_ptr<TriangleQuery> make_triangle_query(TriangleQueryKind kind,
                                                   std::span<const Triangle> triangles,
                                                   std::span<const Vec3> positions) {
  // the hierarchies refit the way TriangleBvhOptions defaults to, the faster one measured
  const auto bvh = [&](BvhVolume volume, std::uint32_t branching) {
    TriangleBvhOptions options;
    options.volume = volume;
    options.branching = branching;
    return std::make_unique<TriangleBvh>(triangles, positions, options);
  };
  switch (kind) {
    case TriangleQueryKind::kBruteForce:
      return std::make_unique<BruteForceQuery>(triangles.size());
    case TriangleQueryKind::kBvhSphere2:
      return bvh(BvhVolume::kSphere, 2);
    case TriangleQueryKind::kBvhSphere4:
      return bvh(BvhVolume::kSphere, 4);
    case TriangleQueryKind::kBvhAabb2:
      return bvh(BvhVolume::kAabb, 2);
    case TriangleQueryKind::kBvhAabb4:
      return bvh(BvhVolume::kAabb, 4);
    case TriangleQueryKind::kSpatialHash:
      return std::make_unique<TriangleHash>(triangles, positions);
  }
  check_failed("unknown triangle query kind");
}

}  // namespace felt
