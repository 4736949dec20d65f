#include "core/geometry/surface_normals.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/cloth/cloth_grid.hpp"
#include "core/geometry/tet_mesh.hpp"
#include "core/solids/tet_lattice.hpp"

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

// corner_normals of every triangle of a surface, its face normals computed as needed
std::vector<std::array<Vec3, 3>> all_corner_normals(std::span<const Vec3> x,
                                                    std::span<const Triangle> t,
                                                    std::span<const std::uint32_t> offset,
                                                    std::span<const std::uint32_t> index,
                                                    Real crease_degrees) {
  const Real cos_crease = std::cos(crease_degrees * std::numbers::pi / 180);
  std::vector<std::array<Vec3, 3>> out;
  for (std::uint32_t f = 0; f < t.size(); ++f) {
    out.push_back(corner_normals(t, f, offset, index, cos_crease,
                                 [&](std::uint32_t g) { return face_normal(x, t[g]); }));
  }
  return out;
}

// A box's edges turn by 90°: with a 60° crease every corner of a face takes the face's normal,
// so interpolation is exact up to the face's border; with 180° they are the vertex normals.
TEST(SurfaceNormals, CornerNormalsKeepABoxsFacesFlatUpToTheirEdges) {
  LatticeGrid grid;
  grid.cells = {2, 3, 2};
  const TetMesh box = make_box_lattice(grid);
  const TetTopology topology = build_topology(box);
  const auto normals = [&](Real crease) {
    return all_corner_normals(box.nodes, topology.surface, topology.surface_face_offset,
                              topology.surface_face_index, crease);
  };
  const auto sharp = normals(60), smooth = normals(180);
  std::vector<Vec3> vertex;
  compute_vertex_normals(box.nodes, topology.surface, vertex);
  int tilted = 0;
  for (std::size_t f = 0; f < topology.surface.size(); ++f) {
    const Triangle& t = topology.surface[f];
    const Vec3 own = face_normal(box.nodes, t).unit;
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT((sharp[f][k] - own).norm(), 1e-12);
      EXPECT_LT((smooth[f][k] - vertex[t[k]]).norm(), 1e-12);
      tilted += (vertex[t[k]] - own).norm() > 0.1;
    }
  }
  EXPECT_GT(tilted, 0);  // the box's edges do tilt its vertex normals
}

// Two triangles folded along their shared edge by 30°: smooth under a 60° crease (both sides'
// corners on the fold share the vertex normal), sharp under a 20° one.
TEST(SurfaceNormals, AGentleFoldStaysSmoothUnderTheCrease) {
  const Real fold = 30 * std::numbers::pi / 180;
  const std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                               Vec3(-std::cos(fold), 0, -std::sin(fold))};
  // the edge 0–2 (the y axis) is shared; the second face's normal is tilted by the fold
  const std::vector<Triangle> t = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<std::uint32_t> offset = {0, 2, 3, 5, 6};
  const std::vector<std::uint32_t> index = {0, 1, 0, 0, 1, 1};
  const auto gentle = all_corner_normals(x, t, offset, index, 60);
  const auto sharp = all_corner_normals(x, t, offset, index, 20);
  std::vector<Vec3> vertex;
  compute_vertex_normals(x, t, vertex);
  for (std::size_t f = 0; f < t.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT((gentle[f][k] - vertex[t[f][k]]).norm(), 1e-12) << f << " " << k;
      EXPECT_LT((sharp[f][k] - face_normal(x, t[f]).unit).norm(), 1e-12) << f << " " << k;
    }
  }
}

}  // namespace
}  // namespace felt
