#include "runtime/live_scene.hpp"

#include <chrono>

#include <gtest/gtest.h>

#include "core/cloth/cloth_point_compliance.hpp"
#include "core/geometry/surface_normals.hpp"

#include "runner_fixtures.hpp"

namespace felt {
namespace {

TEST(LiveScene, PublishesVersionedSnapshotsThatKeepWhatTheyShowed) {
  ManualClock clock;
  LiveScene live(flat_cloth_scene(Vec3(0, -9.81, 0)), 0, clock);
  const auto first = live.latest();
  EXPECT_EQ(first->version, 1u);  // the scene as it was built is published at once
  EXPECT_EQ(live.published(), 1u);
  live.scene.world.step();
  live.publish();
  const auto second = live.latest();
  EXPECT_EQ(second->version, 2u);
  EXPECT_EQ(second->step, 1u);
  EXPECT_EQ(first->step, 0u);
  EXPECT_NE(second->bodies[0].positions, first->bodies[0].positions);
}

TEST(LiveScene, SnapshotsCarryNormalsOnlyWhileHapticsAskForThem) {
  ManualClock clock;
  LiveScene live(flat_cloth_scene(Vec3(0, -9.81, 0)), 0, clock);
  EXPECT_TRUE(live.latest()->bodies[0].normals.empty());  // nobody renders haptics
  live.render_haptics(std::chrono::steady_clock::now());
  live.publish();
  const BodySnapshot& body = live.latest()->bodies[0];
  std::vector<Vec3> normals;
  compute_vertex_normals(body.positions, body.triangles(), normals);
  EXPECT_EQ(body.normals, normals);
}

TEST(LiveScene, PointComplianceIsFoundOnAThreadOfItsOwnAndKeptUntilItIsOld) {
  ManualClock clock;
  LiveScene live(flat_cloth_scene(Vec3(0, -9.81, 0)), 0, clock);
  EXPECT_FALSE(live.latest()->bodies[0].compliance_time);  // nobody asked for it
  for (int k = 0; k < 200; ++k) live.scene.world.step();   // sagging: its springs in tension
  live.serve_local_models();
  const Real asked_at = live.scene.world.time();
  const auto found_at = [&](Real time) {
    return wait_for([&] {
      live.publish();  // each publication looks for what the thread found
      return live.latest()->bodies[0].compliance_time == time;
    });
  };
  ASSERT_TRUE(found_at(asked_at));
  // what the thread found is the body's own compliance, as found on this thread
  const BodySnapshot& sheet = live.latest()->bodies[0];
  const ClothBody& cloth = live.scene.world.cloths()[0];
  const std::vector<WeightedNode> middle{{60, 1}};
  const Real at_rest = point_compliance(cloth).stiffness(middle, Vec3::UnitY());
  EXPECT_GT(at_rest, 0);
  EXPECT_EQ(sheet.compliance.stiffness(middle, Vec3::UnitY()), at_rest);
  EXPECT_EQ(sheet.prompt_compliance.stiffness(middle, Vec3::UnitY()),
            point_compliance(cloth, kComplianceHorizon).stiffness(middle, Vec3::UnitY()));
  // kept while recent, found again once older than kComplianceRefresh
  const int refresh_steps = static_cast<int>(kComplianceRefresh / 1e-3);
  for (int k = 0; k < refresh_steps / 2; ++k) live.scene.world.step();
  live.publish();
  EXPECT_EQ(live.latest()->bodies[0].compliance_time, asked_at);
  for (int k = 0; k < refresh_steps; ++k) live.scene.world.step();
  const Real asked_again = live.scene.world.time();
  EXPECT_TRUE(found_at(asked_again));
}

TEST(LiveScene, TheCatalogNamesEachBodysOwnerOncePublished) {
  ManualClock clock;
  const ClientId loader = 7;
  LiveScene live(flat_cloth_scene(), loader, clock);
  ASSERT_EQ(live.bodies()->bodies.size(), 1u);
  const BodyId sheet = live.bodies()->bodies[0].body_id;
  EXPECT_EQ(live.bodies()->bodies[0].owner, loader);

  Collider floor;
  floor.center = Vec3(0, -1, 0);  // a plane facing up
  const BodyId added = live.scene.world.add_collider(floor);
  live.add_owner(added, 9);
  const auto before = live.bodies();
  EXPECT_EQ(before->find(added), nullptr);  // not before it is published
  const std::uint64_t published = live.published();
  live.publish_bodies();
  EXPECT_EQ(live.published(), published + 1);  // a snapshot with the catalog
  ASSERT_NE(live.bodies()->find(added), nullptr);
  EXPECT_EQ(live.bodies()->find(added)->owner, 9u);
  EXPECT_EQ(live.bodies()->find(sheet)->owner, loader);

  live.scene.world.remove_body(added);
  live.forget_owner(added);
  live.publish_bodies();
  EXPECT_EQ(live.bodies()->find(added), nullptr);
  EXPECT_EQ(live.bodies()->bodies.size(), 1u);
}

TEST(LiveScene, StatusAndEventsCarryTheScenesClockAndScale) {
  ManualClock clock;
  LiveScene live(flat_cloth_scene(), 0, clock);
  live.scene.world.step();
  live.scene.world.step();
  live.pacer.pause();
  live.pacer.set_scale(0.5);
  const SceneStatus status = live.status();
  EXPECT_EQ(status.step, 2u);
  EXPECT_DOUBLE_EQ(status.sim_time, 0.002);
  EXPECT_TRUE(status.paused);
  EXPECT_EQ(status.time_scale, 0.5);
  const SceneEvent event = live.event(SceneEvent::Kind::kPaused, 4);
  EXPECT_EQ(event.kind, SceneEvent::Kind::kPaused);
  EXPECT_EQ(event.client, 4u);
  EXPECT_EQ(event.step, 2u);
  EXPECT_DOUBLE_EQ(event.sim_time, 0.002);
  EXPECT_EQ(event.time_scale, 0.5);
}

}  // namespace
}  // namespace felt
