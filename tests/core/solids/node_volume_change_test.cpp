// A solid's volume change per lattice node, for clients to colour: volume / rest volume − 1 of
// the tetrahedra at each node, averaged.

#include "core/solids/node_volume_change.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "core/solids/tet_lattice.hpp"

namespace felt {
namespace {

TEST(NodeVolumeChange, ALinearMapChangesEveryNodeByItsDeterminantLessOne) {
  LatticeGrid grid;
  grid.cells = {3, 2, 2};
  const TetMesh rest = make_box_lattice(grid);
  std::vector<Vec3> x;
  for (const Vec3& p : rest.nodes)
    x.push_back(Vec3(1.1 * p.x() + 0.2 * p.y(), 1.2 * p.y(), 0.9 * p.z()));
  std::vector<float> change;
  node_volume_change(rest, x, change);
  ASSERT_EQ(change.size(), rest.nodes.size());
  // a linear map scales every volume by its determinant, 1.1 · 1.2 · 0.9 (the shear adds none)
  for (float c : change) EXPECT_NEAR(c, 1.1 * 1.2 * 0.9 - 1, 1e-6);
  node_volume_change(rest, rest.nodes, change);
  for (float c : change) EXPECT_NEAR(c, 0.0f, 1e-7f);
}

TEST(NodeVolumeChange, AveragesTheTetrahedraAtEachNode) {
  // two unit-corner tetrahedra sharing the face (0, 1, 2), on either side of it
  TetMesh rest;
  rest.nodes = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
  rest.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  ASSERT_GT(signed_volume(rest.nodes, rest.tets[1]), 0);
  std::vector<Vec3> x = rest.nodes;
  x[3].z() = 2;  // the first tetrahedron's height, and its volume, doubled
  std::vector<float> change;
  node_volume_change(rest, x, change);
  ASSERT_EQ(change.size(), 5u);
  EXPECT_NEAR(change[3], 1.0f, 1e-6f);  // only in the doubled one
  for (int shared : {0, 1, 2}) EXPECT_NEAR(change[shared], 0.5f, 1e-6f);
  EXPECT_NEAR(change[4], 0.0f, 1e-6f);  // only in the unchanged one
}

TEST(NodeVolumeChange, ATetrahedronOfNoRestVolumeCountsAsUnchanged) {
  TetMesh rest;
  rest.nodes = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(5, 5, 5)};
  rest.tets = {{0, 1, 2, 3}};  // flat
  std::vector<Vec3> x = rest.nodes;
  x[3].z() = 1;
  std::vector<float> change;
  node_volume_change(rest, x, change);
  for (int n : {0, 1, 2, 3}) EXPECT_EQ(change[n], 0.0f);
  EXPECT_EQ(change[4], 0.0f);  // in no tetrahedron
}

}  // namespace
}  // namespace felt
