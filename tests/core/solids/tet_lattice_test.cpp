#include "core/solids/tet_lattice.hpp"

#include <map>

#include <gtest/gtest.h>

namespace felt {
namespace {

LatticeGrid cube_grid(int n, Real size) {
  LatticeGrid grid;
  grid.cells = {n, n, n};
  grid.cell_size = Vec3::Constant(size / n);
  return grid;
}

// Table 7.1 of the second thesis: the coarse 5×5×5 cube.
TEST(TetLattice, FiveCubedCubeHasTheThesisCounts) {
  const TetMesh mesh = make_box_lattice(cube_grid(5, 1.0));
  const TetTopology topology = build_topology(mesh);
  EXPECT_EQ(mesh.nodes.size(), 216u);
  EXPECT_EQ(topology.edges.size(), 990u);
  EXPECT_EQ(topology.surface.size(), 300u);
  EXPECT_EQ(mesh.tets.size(), 625u);
}

TEST(TetLattice, TetrahedraArePositiveAndFillTheBox) {
  const TetMesh mesh = make_box_lattice(cube_grid(3, 2.0));
  for (const Tetrahedron& t : mesh.tets) EXPECT_GT(signed_volume(mesh.nodes, t), 0);
  EXPECT_NEAR(total_volume(mesh.nodes, mesh.tets), 8.0, 1e-12);
}

// Matching face diagonals make the surface closed: every surface edge borders exactly two
// surface triangles, with opposite directions (consistent outward orientation).
TEST(TetLattice, SurfaceIsClosedAndConsistentlyOriented) {
  const TetMesh mesh = make_box_lattice(cube_grid(4, 1.0));
  const TetTopology topology = build_topology(mesh);
  std::map<Edge, int> directed;
  for (const Triangle& t : topology.surface) {
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge[1], edge[0]}), 1u);
  }
  // outward: the surface's divergence-theorem volume equals the tetrahedra's
  Real volume = 0;
  for (const Triangle& t : topology.surface) {
    volume += mesh.nodes[t[0]].dot(mesh.nodes[t[1]].cross(mesh.nodes[t[2]])) / 6;
  }
  EXPECT_NEAR(volume, 1.0, 1e-12);
}

TEST(TetLattice, NeighboursAreTheEdges) {
  const TetMesh mesh = make_box_lattice(cube_grid(2, 1.0));
  const TetTopology topology = build_topology(mesh);
  std::size_t links = 0;
  for (std::uint32_t n = 0; n < mesh.nodes.size(); ++n) {
    for (std::uint32_t m : topology.neighbours(n)) {
      EXPECT_TRUE(std::binary_search(topology.edges.begin(), topology.edges.end(),
                                     Edge{std::min(n, m), std::max(n, m)}));
      ++links;
    }
  }
  EXPECT_EQ(links, 2 * topology.edges.size());
  // the centre node of a 2×2×2 block is interior
  int interior = 0;
  for (std::uint8_t s : topology.on_surface) interior += s == 0;
  EXPECT_EQ(interior, 1);
}

TEST(TetLattice, KeptCellsOnlyUseTheirNodes) {
  LatticeGrid grid = cube_grid(3, 3.0);
  // an L of two cells
  const TetMesh mesh =
      make_cell_lattice(grid, [](int i, int j, int k) { return k == 0 && j == 0 && i < 2; });
  EXPECT_EQ(mesh.nodes.size(), 12u);
  EXPECT_EQ(mesh.tets.size(), 10u);
  EXPECT_NEAR(total_volume(mesh.nodes, mesh.tets), 2.0, 1e-12);
}

}  // namespace
}  // namespace felt
