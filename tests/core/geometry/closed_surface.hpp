#pragma once
// Geometry checks of closed triangle surfaces, from first principles: shared by the tests of
// the procedural surfaces and of the voxel lattices.

#include <map>
#include <set>
#include <span>

#include <gtest/gtest.h>

#include "core/geometry/mesh_topology.hpp"
#include "core/geometry/tet_mesh.hpp"

namespace felt::test {

/// Closed and consistently oriented: every directed edge appears once and its reverse once.
inline ::testing::AssertionResult is_closed_and_oriented(std::span<const Triangle> triangles) {
  std::map<Edge, int> directed;
  for (const Triangle& t : triangles) {
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    if (count != 1) {
      return ::testing::AssertionFailure()
             << "edge " << edge[0] << "→" << edge[1] << " appears " << count << " times";
    }
    if (!directed.contains({edge[1], edge[0]})) {
      return ::testing::AssertionFailure()
             << "edge " << edge[0] << "→" << edge[1] << " has no reverse (open boundary)";
    }
  }
  return ::testing::AssertionSuccess();
}

/// The volume a closed surface encloses, by the divergence theorem: positive when its triangles
/// face outwards.
inline Real enclosed_volume(std::span<const Vec3> x, std::span<const Triangle> triangles) {
  Real volume = 0;
  for (const Triangle& t : triangles) volume += x[t[0]].dot(x[t[1]].cross(x[t[2]])) / 6;
  return volume;
}

inline Real surface_area(std::span<const Vec3> x, std::span<const Triangle> triangles) {
  Real area = 0;
  for (const Triangle& t : triangles)
    area += (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm() / 2;
  return area;
}

/// V − E + F of the surface over the vertices it uses: 2 − 2·genus for a closed surface.
inline long euler_characteristic(std::span<const Triangle> triangles) {
  std::set<std::uint32_t> used;
  for (const Triangle& t : triangles) used.insert(t.begin(), t.end());
  return static_cast<long>(used.size()) - static_cast<long>(unique_edge_count(triangles)) +
         static_cast<long>(triangles.size());
}

}  // namespace felt::test
