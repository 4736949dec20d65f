// The per-vertex scalar frames carry, from a snapshot of a world: a cloth's strain, a solid's
// volume change at its lattice nodes or at the vertices of the surface it carries.

#include "runtime/vertex_scalars.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "core/cloth/cloth_grid.hpp"
#include "core/geometry/procedural_surfaces.hpp"
#include "core/solids/embedded_surface.hpp"
#include "core/solids/tet_lattice.hpp"

namespace felt {
namespace {

// a linear map whose determinant, 1.1 · 1.2 · 0.9, scales every volume
Vec3 stretched(const Vec3& p) {
  return Vec3(1.1 * p.x() + 0.2 * p.y(), 1.2 * p.y(), 0.9 * p.z());
}
constexpr Real kVolumeChange = 1.1 * 1.2 * 0.9 - 1;

SolidBody unit_block() {
  LatticeGrid grid;
  grid.cells = {2, 2, 2};
  grid.cell_size = Vec3::Constant(0.5);
  SolidMaterial material;
  material.node_mass = 0.01;
  return SolidBody("block", make_box_lattice(grid), material);
}

TEST(VertexScalars, ASolidsVolumeChangeAtItsNodes) {
  World world;
  SolidBody block = unit_block();
  for (Vec3& p : block.positions()) p = stretched(p);
  world.add_body(std::move(block));
  const auto snapshot = make_snapshot(world);
  std::vector<float> scalars;
  vertex_scalars(snapshot->bodies.at(0), scalars);
  ASSERT_EQ(scalars.size(), 27u);
  for (float s : scalars) EXPECT_NEAR(s, kVolumeChange, 1e-6);
}

TEST(VertexScalars, ASolidsVolumeChangeAtTheVerticesOfTheSurfaceItCarries) {
  World world;
  SolidBody block = unit_block();
  TriangleMesh ball = make_sphere_surface(0.4, 1);
  for (Vec3& p : ball.positions) p += Vec3::Constant(0.5);
  block.set_embedded_surface(
      std::make_shared<const EmbeddedSurface>(embed_surface(block.rest(), ball)));
  for (Vec3& p : block.positions()) p = stretched(p);
  world.add_body(std::move(block));
  const auto snapshot = make_snapshot(world);
  std::vector<float> scalars;
  vertex_scalars(snapshot->bodies.at(0), scalars);
  ASSERT_EQ(scalars.size(), ball.positions.size());
  for (float s : scalars) EXPECT_NEAR(s, kVolumeChange, 1e-6);
}

TEST(VertexScalars, AClothsStrainAtItsParticles) {
  GridClothSpec spec;
  spec.nx = spec.ny = 4;
  ClothBody cloth("square", std::make_shared<const ClothModel>(make_grid_cloth(spec)), {},
                  make_integrator("symplectic_euler"));
  for (Vec3& p : cloth.state().x) p *= 1.25;  // every spring a quarter longer
  World world;
  world.add_body(std::move(cloth));
  std::vector<float> scalars;
  vertex_scalars(make_snapshot(world)->bodies.at(0), scalars);
  ASSERT_EQ(scalars.size(), 16u);
  for (float s : scalars) EXPECT_NEAR(s, 0.25f, 1e-6f);
}

}  // namespace
}  // namespace felt
