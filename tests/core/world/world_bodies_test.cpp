// Bodies coming and going in a world (ids with generations, colliders as bodies), and a world's
// state taken out and put back.

#include <gtest/gtest.h>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/solids/solid_fixtures.hpp"
#include "core/world/state_hash.hpp"
#include "core/world/world_state.hpp"

namespace felt {
namespace {

using test::small_grid_body;

SolidBody small_cube(Vec3 offset) {
  SolidBody body("cube", test::box({2, 2, 2}, 0.1), test::mass_spring(0.01, 20, 10, 0.5));
  for (Vec3& x : body.positions()) x += offset;
  body.previous_positions() = body.positions();
  return body;
}

Collider floor_plane() {
  Collider floor;
  floor.shape = Collider::Shape::kPlane;
  floor.center = Vec3::Zero();
  floor.normal = Vec3::UnitY();
  return floor;
}

World mixed_world() {
  World world(WorldSettings{Vec3(0, -9.81, 0), 2e-3, 100, 6});
  world.add_body(small_grid_body(6, 6, 200, 0.05, "symplectic_euler"));
  world.add_body(small_cube(Vec3(0, 0.5, 0)));
  world.add_collider(floor_plane());
  return world;
}

TEST(WorldBodies, TheFirstBodiesIdsAreTheirIndicesWhateverTheirKind) {
  const World world = mixed_world();
  EXPECT_EQ(world.body_ids(), (std::vector<BodyId>{0, 1, 2}));
  EXPECT_EQ(world.body_ref(0).kind, BodyRef::Kind::kCloth);
  EXPECT_EQ(world.body_ref(1).kind, BodyRef::Kind::kSolid);
  EXPECT_EQ(world.body_ref(2).kind, BodyRef::Kind::kCollider);
  EXPECT_NE(world.cloth(0), nullptr);
  EXPECT_EQ(world.cloth(1), nullptr);
  EXPECT_NE(world.solid(1), nullptr);
  EXPECT_EQ(world.surface_vertex_count(2), 0u);
}

TEST(WorldBodies, ASurfaceVertexIsWhereItsParticleOrItsNodesAreAndAnswersForcesByTheirMasses) {
  World world = mixed_world();
  const ClothBody& cloth = *world.cloth(0);
  EXPECT_EQ(world.surface_position(0, 7), cloth.state().x[7]);
  EXPECT_EQ(world.surface_inverse_mass(0, 7), cloth.inv_mass()[7]);
  // without a fine surface a solid's surface vertex is its node
  const SolidBody& cube = *world.solid(1);
  EXPECT_EQ(world.surface_position(1, 5), cube.positions()[5]);
  EXPECT_DOUBLE_EQ(world.surface_inverse_mass(1, 5), 1 / 0.01);

  // a fine vertex at a tetrahedron's centroid: the mean of its corners, and a force spread a
  // quarter to each of four 10 g nodes moves it as 4 (1/4)^2 / 0.01 kg: 1 / 0.04 kg
  SolidBody embedded = small_cube(Vec3(1, 0.5, 0));
  const Tetrahedron tet = embedded.rest().tets[3];
  EmbeddedSurface fine;
  fine.tet = {3};
  fine.weights = {Vec4::Constant(0.25)};
  embedded.set_embedded_surface(std::make_shared<const EmbeddedSurface>(fine));
  Vec3 centroid = Vec3::Zero();
  for (std::uint32_t n : tet) centroid += embedded.positions()[n] / 4;
  const BodyId id = world.add_body(std::move(embedded));
  EXPECT_TRUE(world.surface_position(id, 0).isApprox(centroid, 1e-15));
  EXPECT_DOUBLE_EQ(world.surface_inverse_mass(id, 0), 1 / 0.04);
}

TEST(WorldBodies, ARemovedIdIsNeverValidAgainAndItsSlotGetsTheNextGeneration) {
  World world = mixed_world();
  world.remove_body(0);
  EXPECT_FALSE(world.contains(0));
  EXPECT_EQ(world.body_count(), 2u);
  // the others keep their ids and find their bodies, though the cloth list moved
  EXPECT_NE(world.solid(1), nullptr);
  EXPECT_EQ(world.colliders().size(), 1u);
  const BodyId again = world.add_body(small_grid_body(4, 4, 100, 0.05, "symplectic_euler"));
  EXPECT_NE(again, 0u);
  EXPECT_EQ(again.value() & 0xffffu, 0u);  // slot 0 again
  EXPECT_EQ(again.value() >> 16, 1u);      // at generation 1
  EXPECT_FALSE(world.contains(0));
  EXPECT_EQ(world.cloth(again)->model().particle_count(), 16u);
  EXPECT_EQ(world.cloth(0), nullptr);
}

TEST(WorldBodies, AWorldBuiltAgainNeverHandsOutAnIdOfTheOneItReplaces) {
  World old = mixed_world();
  const BodyId extra = old.add_body(small_grid_body(4, 4, 100, 0.05, "symplectic_euler"));
  old.remove_body(0);
  const BodyId reused = old.add_body(small_grid_body(4, 4, 100, 0.05, "symplectic_euler"));
  World fresh = mixed_world();  // a reset: the scene file's bodies again
  fresh.continue_ids_from(old);
  EXPECT_EQ(fresh.body_ids(), (std::vector<BodyId>{0, 1, 2}));  // they keep their ids
  fresh.remove_body(0);
  std::vector<BodyId> later;
  for (int i = 0; i < 3; ++i) {
    later.push_back(fresh.add_body(small_grid_body(4, 4, 100, 0.05, "symplectic_euler")));
  }
  for (BodyId id : later) {
    EXPECT_NE(id, extra);
    EXPECT_NE(id, reused);
    EXPECT_NE(id, 0u);
  }
}

TEST(WorldBodies, RemovingAColliderStopsItHoldingAnything) {
  World world(WorldSettings{Vec3(0, -9.81, 0), 2e-3, 100, 6});
  const BodyId cube = world.add_body(small_cube(Vec3(0, 0.02, 0)));
  const BodyId floor = world.add_collider(floor_plane());
  for (int n = 0; n < 200; ++n) world.step();
  const Real resting = world.solid(cube)->positions()[0].y();
  EXPECT_GT(resting, -0.01);  // held by the floor
  world.remove_body(floor);
  for (int n = 0; n < 200; ++n) world.step();
  EXPECT_LT(world.solid(cube)->positions()[0].y(), resting - 0.1);  // and now it falls
}

TEST(WorldBodies, RemovingASolidKeepsTheOthersColliding) {
  World world(WorldSettings{Vec3(0, -9.81, 0), 2e-3, 100, 6});
  world.add_collider(floor_plane());
  const BodyId low = world.add_body(small_cube(Vec3(0, 0.01, 0)));
  const BodyId gone = world.add_body(small_cube(Vec3(1, 0.01, 0)));
  const BodyId high = world.add_body(small_cube(Vec3(0, 0.25, 0)));
  world.remove_body(gone);
  for (int n = 0; n < 500; ++n) world.step();
  // the high cube lands on the low one (the contact pipeline restarted without the removed one)
  Real lowest_high = 1e9, highest_low = -1e9;
  for (const Vec3& x : world.solid(high)->positions()) lowest_high = std::min(lowest_high, x.y());
  for (const Vec3& x : world.solid(low)->positions()) highest_low = std::max(highest_low, x.y());
  EXPECT_GT(lowest_high, highest_low - 0.03);
  EXPECT_EQ(world.body_count(), 3u);
}

TEST(WorldState, RestoringAStateReplaysTheSameStepsBitForBit) {
  World world = mixed_world();
  for (int n = 0; n < 50; ++n) world.step();
  const WorldState saved = capture_state(world);
  for (int n = 0; n < 100; ++n) world.step();
  const std::uint64_t first = state_hash(world);
  const Real first_time = world.time();
  ASSERT_TRUE(restore_state(world, saved));
  EXPECT_EQ(world.step_count(), 50u);
  for (int n = 0; n < 100; ++n) world.step();
  EXPECT_EQ(state_hash(world), first);
  EXPECT_EQ(world.time(), first_time);
}

TEST(WorldState, PinsArePartOfTheState) {
  World world = mixed_world();
  const WorldState unpinned = capture_state(world);
  world.cloth(0)->pin(3);
  world.solid(1)->pin(5);
  const WorldState pinned = capture_state(world);
  EXPECT_EQ(pinned.bodies[0].pinned, std::vector<std::uint32_t>{3});
  EXPECT_EQ(pinned.bodies[1].pinned, std::vector<std::uint32_t>{5});
  ASSERT_TRUE(restore_state(world, unpinned));
  EXPECT_FALSE(world.cloth(0)->is_pinned(3));
  EXPECT_GT(world.solid(1)->inv_mass()[5], 0);
}

TEST(WorldState, AStateThatDoesNotFitChangesNothing) {
  World world = mixed_world();
  for (int n = 0; n < 10; ++n) world.step();
  const std::uint64_t before = state_hash(world);
  WorldState state = capture_state(world);
  state.bodies[0].positions[7] = Vec3(std::nan(""), 0, 0);
  const auto nonfinite = restore_state(world, state);
  ASSERT_FALSE(nonfinite);
  EXPECT_NE(nonfinite.error().find("finite"), std::string::npos);
  // finite but beyond the bound of every vector from outside (issue 31: frames then carried
  // infinities)
  state = capture_state(world);
  state.bodies[0].positions[3] = Vec3(0, 1e300, 0);
  EXPECT_FALSE(restore_state(world, state));
  state = capture_state(world);
  state.bodies[1].velocities[2] = Vec3(0, 0, -2e6);
  EXPECT_FALSE(restore_state(world, state));
  state = capture_state(world);
  state.bodies[1].previous_positions[0] = Vec3(1e7, 0, 0);
  EXPECT_FALSE(restore_state(world, state));
  // a solid's last step longer than any of the scene's: its Verlet step scales the acceleration
  // by it
  for (const Real previous_step : {1e300, 2 * world.settings().time_step, -1e-3}) {
    state = capture_state(world);
    state.bodies[1].previous_step = previous_step;
    EXPECT_FALSE(restore_state(world, state)) << previous_step;
  }
  state = capture_state(world);
  state.bodies[1].velocities.pop_back();
  EXPECT_FALSE(restore_state(world, state));
  state = capture_state(world);
  state.bodies[0].body_id = 2;  // the collider
  EXPECT_FALSE(restore_state(world, state));
  EXPECT_EQ(state_hash(world), before);
}

}  // namespace
}  // namespace felt
