#include "core/cloth/mesh_cloth.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>

#include "core/math/check.hpp"

namespace felt {

ClothModel make_mesh_cloth(const TriangleMesh& mesh, Real total_mass) {
  FELT_CHECK(total_mass > 0 && !mesh.positions.empty());
  const std::size_t n = mesh.positions.size();
  ClothModel model;
  model.rest_positions = mesh.positions;
  model.uv = mesh.uv.size() == n ? mesh.uv : std::vector<Vec2>(n, Vec2::Zero());
  model.triangles = mesh.triangles;

  std::vector<Real> area(n, 0);
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const Real third =
        (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).norm() / 6;  // ½|×| / 3
    for (std::uint32_t corner : t) area[corner] += third;
  }
  const Real total_area = std::accumulate(area.begin(), area.end(), Real{0});
  const std::size_t unused = static_cast<std::size_t>(std::count(area.begin(), area.end(), 0));
  const Real mean = total_area > 0 && unused < n ? total_area / static_cast<Real>(n - unused) : 1;
  for (Real& a : area) a = a > 0 ? a : mean;
  const Real scale = total_mass / std::accumulate(area.begin(), area.end(), Real{0});
  model.mass.resize(n);
  std::transform(area.begin(), area.end(), model.mass.begin(), [&](Real a) { return a * scale; });

  // edge -> the vertex opposite it in the first triangle seen
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> opposite;
  auto rest = [&](std::uint32_t i, std::uint32_t j) {
    return (mesh.positions[i] - mesh.positions[j]).norm();
  };
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = t[k], j = t[(k + 1) % 3], o = t[(k + 2) % 3];
      if (i == j) continue;  // a degenerate triangle's edge from a vertex to itself is no spring
      const auto edge = std::minmax(i, j);
      const auto [it, first] = opposite.emplace(edge, o);
      if (first) {
        model.springs.push_back({edge.first, edge.second, rest(i, j), SpringKind::kStructural});
      } else if (it->second != o) {
        model.springs.push_back({it->second, o, rest(it->second, o), SpringKind::kBend});
      }
    }
  }
  return model;
}

}  // namespace felt
