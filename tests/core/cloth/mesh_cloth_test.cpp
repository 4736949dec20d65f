// Cloth from arbitrary triangle meshes, and the scene transform.

#include "core/cloth/mesh_cloth.hpp"

#include <gtest/gtest.h>

#include "core/cloth/cloth_grid.hpp"
#include "core/geometry/mesh_topology.hpp"

namespace felt {
namespace {

std::size_t count(const ClothModel& model, SpringKind kind) {
  std::size_t n = 0;
  for (const Spring& s : model.springs) n += s.kind == kind ? 1 : 0;
  return n;
}

TEST(MeshCloth, SquareHasFiveEdgesAndOneBendAcrossTheDiagonal) {
  // 2 ── 3
  // │  ╲ │     triangles (0, 1, 2) and (1, 3, 2) share the diagonal 1–2
  // 0 ── 1
  TriangleMesh mesh{
      {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}, {}, {{0, 1, 2}, {1, 3, 2}}};
  const ClothModel model = make_mesh_cloth(mesh, 2.0);
  EXPECT_EQ(count(model, SpringKind::kStructural), 5u);
  ASSERT_EQ(count(model, SpringKind::kBend), 1u);
  const Spring& bend = model.springs.back();
  EXPECT_EQ(std::minmax(bend.i, bend.j), std::minmax(0u, 3u));
  EXPECT_NEAR(bend.rest_length, std::sqrt(2.0), 1e-15);
  // area lumping: corners 1 and 2 touch both triangles, 0 and 3 one each
  EXPECT_NEAR(model.mass[0], 2.0 / 6, 1e-15);
  EXPECT_NEAR(model.mass[1], 2.0 / 3, 1e-15);
  EXPECT_NEAR(model.mass[2], 2.0 / 3, 1e-15);
  EXPECT_NEAR(model.mass[3], 2.0 / 6, 1e-15);
}

// A triangle with a repeated corner (an OBJ face may name a vertex twice) has an edge from a
// vertex to itself: no spring, which would have no length to keep and no direction to push.
TEST(MeshCloth, ADegenerateTrianglesEdgeFromAVertexToItselfIsNoSpring) {
  TriangleMesh mesh{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {}, {{0, 1, 2}, {2, 2, 1}}};
  const ClothModel model = make_mesh_cloth(mesh, 1.0);
  EXPECT_EQ(count(model, SpringKind::kStructural), 3u);
  for (const Spring& s : model.springs) EXPECT_NE(s.i, s.j);
}

TEST(MeshCloth, ClosedSurfaceHasABendForEveryEdge) {
  // a tetrahedron's surface: 4 faces, 6 edges, each shared by two faces
  TriangleMesh mesh{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                    {},
                    {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}};
  const ClothModel model = make_mesh_cloth(mesh, 1.0);
  EXPECT_EQ(count(model, SpringKind::kStructural), 6u);
  EXPECT_EQ(count(model, SpringKind::kBend), 6u);
  EXPECT_EQ(unique_edge_count(model.triangles), 6u);
  Real total = 0;
  for (Real m : model.mass) total += m;
  EXPECT_NEAR(total, 1.0, 1e-15);
}

TEST(MeshCloth, UnusedVerticesStillGetMass) {
  TriangleMesh mesh{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(5, 5, 5)}, {}, {{0, 1, 2}}};
  const ClothModel model = make_mesh_cloth(mesh, 1.0);
  EXPECT_GT(model.mass[3], 0);
  EXPECT_NEAR(model.mass[3], model.mass[0], 1e-15);
}

TEST(ClothGridTransform, ScalingAGridScalesItsRestLengths) {
  GridClothSpec spec;
  spec.nx = spec.ny = 3;
  spec.transform.scale = Vec3::Constant(2);
  spec.transform.rotate_degrees = Vec3(90, 0, 0);  // hanging → lying
  const ClothModel model = make_grid_cloth(spec);
  EXPECT_NEAR(model.springs[0].rest_length, 1.0, 1e-12);  // 0.5 m spacing, doubled
  for (const Vec3& p : model.rest_positions) EXPECT_NEAR(p.y(), 0, 1e-12);
}

TEST(Transform, RotatesThenScalesThenTranslates) {
  Transform t;
  t.rotate_degrees = Vec3(0, 0, 90);
  t.scale = Vec3(2, 3, 4);
  t.translate = Vec3(10, 0, 0);
  // (1, 0, 0) → rotated (0, 1, 0) → scaled (0, 3, 0) → translated (10, 3, 0)
  EXPECT_LT((t.apply(Vec3(1, 0, 0)) - Vec3(10, 3, 0)).norm(), 1e-12);
  // x first, then y: (0, 1, 0) → about x by 90° → (0, 0, 1) → about y by 90° → (1, 0, 0)
  Transform xy;
  xy.rotate_degrees = Vec3(90, 90, 0);
  EXPECT_LT((xy.apply(Vec3(0, 1, 0)) - Vec3(1, 0, 0)).norm(), 1e-12);
}

}  // namespace
}  // namespace felt
