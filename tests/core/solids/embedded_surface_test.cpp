#include "core/solids/embedded_surface.hpp"

#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "core/geometry/procedural_surfaces.hpp"
#include "core/geometry/triangle_geometry.hpp"
#include "core/solids/tet_lattice.hpp"

namespace felt {
namespace {

TetMesh box_lattice(const std::array<int, 3>& cells, const Vec3& origin, Real cell) {
  LatticeGrid grid;
  grid.cells = cells;
  grid.origin = origin;
  grid.cell_size = Vec3::Constant(cell);
  return make_box_lattice(grid);
}

TriangleMesh random_points(const Vec3& lo, const Vec3& hi, int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<Real> unit(0, 1);
  TriangleMesh points;
  for (int i = 0; i < count; ++i) {
    points.positions.push_back(
        lo + Vec3(unit(random), unit(random), unit(random)).cwiseProduct(hi - lo));
  }
  return points;
}

/// Barycentric coordinates from the 4 × 4 system [corners; 1 1 1 1] w = [p; 1], solved
/// directly: an independent reference for the embedding's own arithmetic.
Vec4 reference_barycentric(const TetMesh& mesh, const Tetrahedron& t, const Vec3& p) {
  Eigen::Matrix4d corners;
  for (int c = 0; c < 4; ++c) corners.col(c) << mesh.nodes[t[c]], 1;
  return corners.fullPivLu().solve(Vec4(p.x(), p.y(), p.z(), 1));
}

/// Distance from p to a tetrahedron by brute force: 0 inside, else to the nearest face.
Real distance_to_tet(const TetMesh& mesh, const Tetrahedron& t, const Vec3& p) {
  if (reference_barycentric(mesh, t, p).minCoeff() >= 0) return 0;
  Real distance = std::numeric_limits<Real>::infinity();
  const auto& x = mesh.nodes;
  for (const auto& [a, b, c] : {std::array{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}) {
    distance = std::min(distance,
                        (p - closest_point_on_triangle(p, x[t[a]], x[t[b]], x[t[c]]).point).norm());
  }
  return distance;
}

TEST(EmbeddedSurface, AtRestReproducesTheFineVerticesInsideTheirTetrahedra) {
  const TetMesh lattice = box_lattice({4, 3, 5}, Vec3(-1, 0, 2), 0.25);
  const TriangleMesh fine = random_points(Vec3(-1, 0, 2), Vec3(0, 0.75, 3.25), 500, 1);
  const EmbeddedSurface surface = embed_surface(lattice, fine);
  ASSERT_EQ(surface.vertex_count(), fine.positions.size());
  std::vector<Vec3> x;
  surface.positions(lattice.nodes, lattice.tets, x);
  for (std::size_t v = 0; v < x.size(); ++v) {
    EXPECT_LT((x[v] - fine.positions[v]).norm(), 1e-14) << v;
    const Vec4 w = reference_barycentric(lattice, lattice.tets[surface.tet[v]], fine.positions[v]);
    EXPECT_GE(w.minCoeff(), -1e-12) << v;  // the tetrahedron chosen holds the vertex
    EXPECT_LT((w - surface.weights[v]).cwiseAbs().maxCoeff(), 1e-12) << v;
    EXPECT_NEAR(surface.weights[v].sum(), 1, 1e-14);
  }
}

// Vertices on shared faces, edges and nodes of the lattice (the worst cases for a containment
// test) are still placed in a tetrahedron that holds them.
TEST(EmbeddedSurface, VerticesOnLatticeNodesAndFacesAreInside) {
  const TetMesh lattice = box_lattice({2, 2, 2}, Vec3::Zero(), 0.5);
  TriangleMesh fine;
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; j <= 4; ++j) {
      for (int k = 0; k <= 4; ++k) fine.positions.push_back(Vec3(i, j, k) / 4);
    }
  }
  const EmbeddedSurface surface = embed_surface(lattice, fine);
  std::vector<Vec3> x;
  surface.positions(lattice.nodes, lattice.tets, x);
  for (std::size_t v = 0; v < x.size(); ++v) {
    EXPECT_GE(surface.weights[v].minCoeff(), -1e-12) << fine.positions[v].transpose();
    EXPECT_LT((x[v] - fine.positions[v]).norm(), 1e-15);
  }
}

// Barycentric interpolation is exact for affine maps, extrapolation included: after moving
// the lattice nodes by x → A x + b the fine vertices are A p + b.
TEST(EmbeddedSurface, FollowsAnAffineMapOfTheLatticeExactly) {
  const TetMesh lattice = box_lattice({3, 3, 3}, Vec3::Zero(), 1.0 / 3);
  TriangleMesh fine = make_sphere_surface(0.45, 2);
  for (Vec3& p : fine.positions) p += Vec3::Constant(0.5);
  // and a few vertices just outside the lattice, which extrapolate
  fine.positions.push_back(Vec3(-0.01, 0.5, 0.5));
  fine.positions.push_back(Vec3(1.02, 1.01, 0.3));
  const EmbeddedSurface surface = embed_surface(lattice, fine);

  Mat3 A;
  A << 1.2, 0.3, -0.1, -0.2, 0.8, 0.4, 0.1, -0.5, 1.5;
  const Vec3 b(0.3, -2, 1);
  std::vector<Vec3> moved;
  for (const Vec3& n : lattice.nodes) moved.push_back(A * n + b);
  std::vector<Vec3> x;
  surface.positions(moved, lattice.tets, x);
  for (std::size_t v = 0; v < x.size(); ++v) {
    EXPECT_LT((x[v] - (A * fine.positions[v] + b)).norm(), 1e-13) << v;
  }
  EXPECT_EQ(surface.triangles, fine.triangles);
  EXPECT_EQ(surface.uv, fine.uv);
}

// Barycentric interpolation reproduces a linear function: values given at the nodes by one come
// out at every fine vertex as the function's value there.
TEST(EmbeddedSurface, CarriesALinearFunctionOfTheNodesToTheVerticesExactly) {
  const TetMesh lattice = box_lattice({2, 3, 2}, Vec3(-1, 0, 0.5), 0.4);
  const TriangleMesh fine = random_points(Vec3(-1, 0, 0.5), Vec3(-0.2, 1.2, 1.3), 200, 7);
  const EmbeddedSurface surface = embed_surface(lattice, fine);
  const auto f = [](const Vec3& p) { return 0.5 - 2 * p.x() + 0.25 * p.y() + 3 * p.z(); };
  std::vector<float> at_nodes;
  for (const Vec3& n : lattice.nodes) at_nodes.push_back(static_cast<float>(f(n)));
  std::vector<float> at_vertices;
  surface.values(at_nodes, lattice.tets, at_vertices);
  ASSERT_EQ(at_vertices.size(), fine.positions.size());
  for (std::size_t v = 0; v < at_vertices.size(); ++v) {
    EXPECT_NEAR(at_vertices[v], f(fine.positions[v]), 1e-5) << v;
  }
}

// A vertex outside every tetrahedron goes to the nearest one, compared with a brute-force
// search over all of them, near the lattice and far from it.
TEST(EmbeddedSurface, OutsideVerticesGoToTheNearestTetrahedron) {
  LatticeGrid grid;
  grid.cells = {4, 4, 4};
  grid.cell_size = Vec3::Constant(0.25);
  // an L-shaped lattice, so that the nearest tetrahedron is not simply the nearest cell of a box
  const TetMesh lattice = make_cell_lattice(grid, [](int i, int j, int) { return i < 1 || j < 1; });
  const TriangleMesh fine = random_points(Vec3::Constant(-0.5), Vec3::Constant(2.5), 300, 2);
  const EmbeddedSurface surface = embed_surface(lattice, fine);
  for (std::size_t v = 0; v < fine.positions.size(); ++v) {
    const Vec3& p = fine.positions[v];
    Real nearest = std::numeric_limits<Real>::infinity();
    for (const Tetrahedron& t : lattice.tets)
      nearest = std::min(nearest, distance_to_tet(lattice, t, p));
    EXPECT_NEAR(distance_to_tet(lattice, lattice.tets[surface.tet[v]], p), nearest, 1e-12)
        << p.transpose();
    const Vec4 w = reference_barycentric(lattice, lattice.tets[surface.tet[v]], p);
    EXPECT_LT((w - surface.weights[v]).cwiseAbs().maxCoeff(), 1e-10) << v;
  }
}

// A larger lattice than a brute-force search would handle quickly: every vertex of 20 000 is
// still found in a tetrahedron that holds it.
TEST(EmbeddedSurface, EmbedsManyVerticesInALargeLattice) {
  const TetMesh lattice = box_lattice({30, 30, 30}, Vec3::Zero(), 0.1);  // 135 000 tets
  const TriangleMesh fine = random_points(Vec3::Zero(), Vec3::Constant(3), 20000, 3);
  const EmbeddedSurface surface = embed_surface(lattice, fine);
  std::vector<Vec3> x;
  surface.positions(lattice.nodes, lattice.tets, x);
  for (std::size_t v = 0; v < x.size(); ++v) {
    ASSERT_GE(surface.weights[v].minCoeff(), -1e-12) << v;
    ASSERT_LT((x[v] - fine.positions[v]).norm(), 1e-13) << v;
  }
}

TEST(EmbeddedLatticeSurface, IsTheLatticesSurfaceNodesAtTheirOwnPositionsWithoutTheInterior) {
  // 3 x 3 x 3 cells: 4^3 = 64 nodes, of which the 2^3 = 8 inside touch no face
  TetMesh lattice = box_lattice({3, 3, 3}, Vec3(-1, 0, 2), 0.5);
  const TetTopology topology = build_topology(lattice);
  const EmbeddedSurface surface = embed_lattice_surface(lattice, topology.surface);
  ASSERT_EQ(surface.vertex_count(), 56u);
  EXPECT_TRUE(surface.lattice_own);
  ASSERT_EQ(surface.triangles.size(), topology.surface.size());

  // moved anywhere, each vertex is exactly its node, in node order
  std::mt19937 random(7);
  std::uniform_real_distribution<Real> jitter(-0.1, 0.1);
  for (Vec3& x : lattice.nodes) x += Vec3(jitter(random), jitter(random), jitter(random));
  std::vector<Vec3> positions;
  surface.positions(lattice.nodes, lattice.tets, positions);
  std::vector<std::uint32_t> node_of;
  for (std::uint32_t n = 0; n < lattice.nodes.size(); ++n) {
    if (topology.on_surface[n]) node_of.push_back(n);
  }
  ASSERT_EQ(node_of.size(), positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    EXPECT_EQ(positions[v], lattice.nodes[node_of[v]]) << "vertex " << v;
  }
  // and the faces are the lattice's, corner for corner
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(node_of[surface.triangles[f][c]], topology.surface[f][c]) << "face " << f;
    }
  }
}

}  // namespace
}  // namespace felt
