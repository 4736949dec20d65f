#include "core/surface_normals.hpp"

#include <gtest/gtest.h>

#include "core/cloth_grid.hpp"

namespace felt {
namespace {

TEST(SurfaceNormals, FlatGridFacesItsFront) {
  GridClothSpec spec;
  spec.nx = 5;
  spec.ny = 4;
  const ClothModel model = make_grid_cloth(spec);
  std::vector<Vec3> normals;
  compute_vertex_normals(model.rest_positions, model.triangles, normals);
  for (const Vec3& n : normals) EXPECT_LT((n - Vec3::UnitZ()).norm(), 1e-12);
}

TEST(SurfaceNormals, ClosedSurfacePointsOutward) {
  // a tetrahedron wound counter-clockwise seen from outside
  const std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const std::vector<Triangle> t = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  std::vector<Vec3> normals;
  compute_vertex_normals(x, t, normals);
  const Vec3 centroid = Vec3(0.25, 0.25, 0.25);
  for (std::size_t p = 0; p < x.size(); ++p) {
    EXPECT_NEAR(normals[p].norm(), 1, 1e-12);
    EXPECT_GT(normals[p].dot(x[p] - centroid), 0) << p;
  }
  // the corner at the origin sees three equal faces: its normal is −(1, 1, 1)/√3 weighted by
  // areas ½, ½, ½ plus the slanted face's share, which it does not touch
  EXPECT_LT((normals[0] + Vec3::Ones().normalized()).norm(), 1e-12);
}

}  // namespace
}  // namespace felt
