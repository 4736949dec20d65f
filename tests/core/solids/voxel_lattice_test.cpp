#include "core/solids/voxel_lattice.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/geometry/closed_surface.hpp"
#include "core/geometry/procedural_surfaces.hpp"
#include "scene/obj_reader.hpp"

namespace felt {
namespace {

using std::numbers::pi;

/// The lattice is a valid solid: positive tetrahedra, a closed outward surface of the given
/// genus that encloses the tetrahedra's volume, and every fine vertex inside its tetrahedron
/// and reproduced at rest.
void expect_sound_embedded_solid(const EmbeddedSolid& solid, const TriangleMesh& fine, int genus) {
  const TetMesh& lattice = solid.lattice;
  for (const Tetrahedron& t : lattice.tets) ASSERT_GT(signed_volume(lattice.nodes, t), 0);
  const TetTopology topology = build_topology(lattice);
  EXPECT_TRUE(test::is_closed_and_oriented(topology.surface));
  EXPECT_EQ(test::euler_characteristic(topology.surface), 2 - 2 * genus);
  EXPECT_NEAR(test::enclosed_volume(lattice.nodes, topology.surface),
              total_volume(lattice.nodes, lattice.tets), 1e-9);

  ASSERT_EQ(solid.surface.vertex_count(), fine.positions.size());
  std::vector<Vec3> x;
  solid.surface.positions(lattice.nodes, lattice.tets, x);
  for (std::size_t v = 0; v < x.size(); ++v) {
    EXPECT_GE(solid.surface.weights[v].minCoeff(), -1e-9) << v;
    EXPECT_LT((x[v] - fine.positions[v]).norm(), 1e-12) << v;
  }
}

// Table 7.1 of the second thesis: the fine 20 × 20 × 20 cube embedded in a 5 × 5 × 5 lattice
// of 216 nodes, 990 edges, 300 surface triangles and 625 tetrahedra.
TEST(VoxelLattice, ThesisCubeHasTheTableCounts) {
  const TriangleMesh fine = make_box_surface(Vec3::Ones(), 20);
  const EmbeddedSolid cube = voxelize_surface(fine, 5);
  const TetTopology topology = build_topology(cube.lattice);
  EXPECT_EQ(cube.lattice.nodes.size(), 216u);
  EXPECT_EQ(topology.edges.size(), 990u);
  EXPECT_EQ(topology.surface.size(), 300u);
  EXPECT_EQ(cube.lattice.tets.size(), 625u);
  EXPECT_EQ(cube.surface.vertex_count(), 2402u);
  EXPECT_NEAR(total_volume(cube.lattice.nodes, cube.lattice.tets), 1, 1e-12);
  expect_sound_embedded_solid(cube, fine, 0);
}

// Every point of the ball deeper than half a cell diagonal inside the fine polyhedron lies in
// a cell whose centre is inside, and every kept cell reaches the surface within a cell
// diagonal, so the lattice's volume lies between the balls of those radii.
TEST(VoxelLattice, SphereVolumeIsWithinTheCellSizeBound) {
  const Real r = 1;
  const TriangleMesh fine = make_sphere_surface(r, 3);
  Real inradius = r;
  for (const Triangle& t : fine.triangles) {
    const Vec3& a = fine.positions[t[0]];
    const Vec3 normal = (fine.positions[t[1]] - a).cross(fine.positions[t[2]] - a).normalized();
    inradius = std::min(inradius, a.dot(normal));
  }
  for (int resolution : {6, 10, 16}) {
    const EmbeddedSolid ball = voxelize_surface(fine, resolution);
    const Real diagonal = std::sqrt(3.0) * 2 * r / resolution;
    const Real volume = total_volume(ball.lattice.nodes, ball.lattice.tets);
    EXPECT_GE(volume, 4 * pi / 3 * std::pow(inradius - diagonal / 2, 3)) << resolution;
    EXPECT_LE(volume, 4 * pi / 3 * std::pow(r + diagonal, 3)) << resolution;
    expect_sound_embedded_solid(ball, fine, 0);
  }
}

TEST(VoxelLattice, TorusKeepsItsHole) {
  const TriangleMesh fine = make_torus_surface(1, 0.35, 48, 16);
  const EmbeddedSolid ring = voxelize_surface(fine, 12);
  expect_sound_embedded_solid(ring, fine, 1);
}

// Two cubes that touch only along an edge, or only at a corner: their cells meet there alone,
// which is not a manifold; cells are added there until the lattice's surface is closed and
// manifold.
TEST(VoxelLattice, CellsMeetingAlongAnEdgeOrAtACornerAreJoined) {
  for (const Vec3& offset : {Vec3(1, 1, 0), Vec3(1, 1, 1)}) {
    TriangleMesh fine = make_box_surface(Vec3::Ones(), 2);
    const TriangleMesh second = make_box_surface(Vec3::Ones(), 2);
    const auto first_count = static_cast<std::uint32_t>(fine.positions.size());
    for (const Vec3& p : second.positions) fine.positions.push_back(p + offset);
    for (const Vec2& uv : second.uv) fine.uv.push_back(uv);
    for (const Triangle& t : second.triangles) {
      fine.triangles.push_back({t[0] + first_count, t[1] + first_count, t[2] + first_count});
    }
    const EmbeddedSolid joined = voxelize_surface(fine, 4);  // cells of half a cube
    SCOPED_TRACE(offset.transpose());
    expect_sound_embedded_solid(joined, fine, 0);
    EXPECT_GT(total_volume(joined.lattice.nodes, joined.lattice.tets), 2);
  }
}

// The generalized winding number changes little away from a hole, so a sphere with a missing
// triangle gives the lattice of the closed sphere.
TEST(VoxelLattice, ToleratesASmallHole) {
  const TriangleMesh closed = make_sphere_surface(1, 2);
  TriangleMesh open = closed;
  open.triangles.erase(open.triangles.begin() + 17);
  const EmbeddedSolid from_closed = voxelize_surface(closed, 8);
  const EmbeddedSolid from_open = voxelize_surface(open, 8);
  EXPECT_EQ(from_open.lattice.nodes, from_closed.lattice.nodes);
  EXPECT_EQ(from_open.lattice.tets, from_closed.lattice.tets);
}

// The bunny at about seven cells along its longest side: a lattice of the thesis dog's size
// (113 nodes, 232 tetrahedra), whose ears and feet stay joined by faces.
TEST(VoxelLattice, BunnyMakesASmallSoundLattice) {
  const auto bunny = read_obj_file(std::string(FELT_SCENE_DIR) + "/meshes/bunny.obj");
  ASSERT_TRUE(bunny) << bunny.error();
  const EmbeddedSolid solid = voxelize_surface(*bunny, 7);
  expect_sound_embedded_solid(solid, *bunny, 0);
  EXPECT_GT(solid.lattice.nodes.size(), 50u);
  EXPECT_LT(solid.lattice.nodes.size(), 300u);
  EXPECT_LT(solid.lattice.tets.size(), 800u);
}

}  // namespace
}  // namespace felt
