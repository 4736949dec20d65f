// What a viewer gets besides the vertices: the colliders' shapes in the body catalog, every
// proxy of the scene in the frames with its client's name (its own marked), a cloth's strain or
// a solid's volume change per vertex when asked, and each body's integrator and strain in GetStats.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <thread>
#include <vector>

#include "feltd_fixture.hpp"

namespace felt::test {
namespace {

const v1::BodyInfo* find_collider(const v1::SceneLoaded& scene, v1::ColliderKind kind) {
  for (const v1::BodyInfo& body : scene.bodies()) {
    if (body.kind() == "collider" && body.has_collider() && body.collider().kind() == kind) {
      return &body;
    }
  }
  return nullptr;
}

TEST_F(FeltdTest, CollidersAreDescribedWithTheirShapes) {
  auto client = greeted("viewer");
  const v1::SceneLoaded scene = client->load_scene_by_name("cloth_on_ball");
  // the scene file: a floor through the origin facing up, a ball of 0.3 m at (0, 0.3, 0)
  const v1::BodyInfo* floor = find_collider(scene, v1::COLLIDER_KIND_PLANE);
  ASSERT_TRUE(floor);
  EXPECT_EQ(floor->collider().normal().y(), 1.0);
  EXPECT_EQ(floor->collider().center().y(), 0.0);
  EXPECT_EQ(floor->collider().friction(), 0.5);
  const v1::BodyInfo* ball = find_collider(scene, v1::COLLIDER_KIND_SPHERE);
  ASSERT_TRUE(ball);
  EXPECT_EQ(ball->collider().radius(), 0.3);
  EXPECT_EQ(ball->collider().center().y(), 0.3);
  // the sheet is no collider; a collider added later is described in its reply and its event
  EXPECT_FALSE(scene.bodies(0).has_collider());
  auto other = greeted("other");
  other->join_scene(scene.scene_id());
  const v1::BodyAdded box = client->add_collider(
      R"({"type": "box", "center": [1, 0.5, 0], "half_extents": [0.1, 0.2, 0.3]})");
  EXPECT_EQ(box.body().collider().kind(), v1::COLLIDER_KIND_BOX);
  EXPECT_EQ(box.body().collider().half_extents().z(), 0.3);
  const auto added = other->wait_event(v1::EVENT_KIND_BODY_ADDED, 5s);
  ASSERT_TRUE(added);
  EXPECT_EQ(added->bodies(0).collider().center().x(), 1.0);
}

/// The next frame whose proxies hold one of client `name` in contact, or nothing within 5 s,
/// while `touch` keeps that client's proxy pressed into the curtain. In contact: on a loaded
/// machine the first frame the viewer got showed the proxy free, with no force (CI, once).
template <class Touch>
std::optional<v1::ProxyPresence> presence_of(Client& viewer, const std::string& name, Touch touch) {
  const auto deadline = std::chrono::steady_clock::now() + scaled(5s);
  while (std::chrono::steady_clock::now() < deadline) {
    touch();
    const auto frame = viewer.next_frame(100ms);
    if (!frame) continue;
    for (const v1::ProxyPresence& proxy : frame->proxies()) {
      if (proxy.client_name() == name && proxy.in_contact()) return proxy;
    }
  }
  return std::nullopt;
}

TEST_F(FeltdTest, FramesShowEveryClientsProxiesByName) {
  auto alice = greeted("alice");
  auto bob = greeted("bob");
  alice->subscribe_frames(120);
  bob->subscribe_frames(120);
  // what bob felt at each of his updates: the curtain swings under his touch (about 4 N at
  // first, the README's; 0.4 N once it had swung back on a loaded machine)
  std::vector<v1::ForceUpdate> felt;
  const auto bob_touches = [&] { felt.push_back(bob->proxy_update(7, {0, 1.2, 0.01})); };
  const auto seen = presence_of(*alice, "bob", bob_touches);
  ASSERT_TRUE(seen);
  EXPECT_EQ(seen->proxy_id(), 7u);
  EXPECT_FALSE(seen->own());
  // the frame shows the force and the god-object of one of bob's updates, pushing him out of
  // the curtain along +z from where his proxy rests on it
  const bool shown = std::ranges::any_of(felt, [&](const v1::ForceUpdate& update) {
    return update.in_contact() && std::abs(update.force().z() - seen->force().z()) < 1e-9 &&
           std::abs(update.proxy().z() - seen->position().z()) < 1e-9;
  });
  EXPECT_TRUE(shown) << seen->ShortDebugString();
  EXPECT_GT(seen->force().z(), 0);
  EXPECT_GT(seen->position().z(), 0.01);
  EXPECT_GT(seen->radius(), 0.0);
  // bob sees his own, marked as his
  const auto own = presence_of(*bob, "bob", bob_touches);
  ASSERT_TRUE(own);
  EXPECT_TRUE(own->own());
  // a closed proxy is gone from the frames
  bob->close_proxy(7);
  // alice's socket still holds frames sent before the close (she read few while bob touched,
  // more than 20 in the full suite): read on to those built after it
  bool gone = false;
  const auto deadline = std::chrono::steady_clock::now() + scaled(5s);
  while (!gone && std::chrono::steady_clock::now() < deadline) {
    const auto frame = alice->next_frame(scaled(1s));
    gone = frame && frame->proxies_size() == 0;
  }
  EXPECT_TRUE(gone);
}

TEST_F(FeltdTest, ScalarsAreAClothsStrainPerVertexOnlyWhenAsked) {
  auto client = greeted("viewer");
  client::FrameSubscription subscription;
  subscription.quantized = true;
  subscription.deltas = true;
  subscription.scalars = true;
  client->subscribe_frames(subscription);
  // the first frames may show the curtain as it starts, not yet stretched: look 0.1 s in
  std::optional<v1::Frame> frame;
  const auto deadline = std::chrono::steady_clock::now() + scaled(5s);
  do {
    frame = client->next_frame(scaled(5s));
  } while (frame && frame->step() < 100 && std::chrono::steady_clock::now() < deadline);
  ASSERT_TRUE(frame);
  ASSERT_GE(frame->step(), 100u);
  const v1::BodyFrame& curtain = frame->bodies(0);
  ASSERT_EQ(curtain.scalars_size(), 400);
  float largest = 0;
  for (float s : curtain.scalars()) {
    ASSERT_TRUE(std::isfinite(s));
    largest = std::max(largest, s);
  }
  // hanging from two corners it is stretched, a few percent
  EXPECT_GT(largest, 0.0f);
  EXPECT_LT(largest, 0.5f);
  client->subscribe_frames(60);
  const auto plain = client->next_frame(scaled(5s));
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->bodies(0).scalars_size(), 0);
}

TEST_F(FeltdTest, ScalarsAreASolidsVolumeChangePerVertex) {
  auto client = greeted("viewer");
  // a block of 1 m on the floor, with a fine surface: its weight squeezes its bottom
  client->load_scene_json(R"({"time_step": 0.01,
    "colliders": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]}],
    "bodies": [{"name": "block", "type": "solid",
                "lattice": {"cells": [2, 2, 2], "size": [1, 1, 1], "fine_divisions": 4},
                "transform": {"translate": [0, 0.5, 0]}, "model": "mass_spring", "node_mass": 0.05,
                "mass_spring": {"distance_stiffness": 60, "volume_stiffness": 20, "damping": 2}}]})");
  client::FrameSubscription subscription;
  subscription.quantized = true;
  subscription.scalars = true;
  client->subscribe_frames(subscription);
  std::optional<v1::Frame> frame;
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  do {
    frame = client->next_frame(5s);
  } while (frame && frame->step() < 50 && std::chrono::steady_clock::now() < deadline);
  ASSERT_TRUE(frame);
  ASSERT_GE(frame->step(), 50u);
  const v1::BodyFrame& block = frame->bodies(0);
  ASSERT_GT(block.vertex_count(), 27u);  // the fine surface's vertices, not the lattice's nodes
  ASSERT_EQ(block.scalars_size(), static_cast<int>(block.vertex_count()));
  float smallest = 0;
  for (float s : block.scalars()) {
    ASSERT_TRUE(std::isfinite(s));
    ASSERT_GT(s, -1.0f);  // no tetrahedron of it is turned inside out
    smallest = std::min(smallest, s);
  }
  EXPECT_LT(smallest, -1e-3f);
}

// Issue 31, found 7: a lattice without a fine surface streamed all 1,331 of its nodes, though
// its surface uses 602.
TEST_F(FeltdTest, ALatticeWithoutAFineSurfaceSendsItsSurfaceNodesOnly) {
  auto client = greeted("viewer");
  // a 1 m box of 10 x 10 x 10 cells, weightless and touching nothing: it stays at rest
  const v1::SceneLoaded loaded = client->load_scene_json(R"({"time_step": 0.01,
    "gravity": [0, 0, 0],
    "bodies": [{"name": "block", "type": "solid",
                "lattice": {"cells": [10, 10, 10], "size": [1, 1, 1]}, "node_mass": 0.05,
                "mass_spring": {"distance_stiffness": 60, "volume_stiffness": 20}}]})");
  ASSERT_EQ(loaded.bodies_size(), 1);
  EXPECT_EQ(loaded.bodies(0).nodes(), 1331u);
  // 11^3 nodes less the 9^3 inside
  EXPECT_EQ(loaded.bodies(0).particles(), 602u);
  EXPECT_EQ(loaded.bodies(0).triangles(), 6u * 10 * 10 * 2);
  client->subscribe_frames(60);
  const auto frame = client->next_frame(scaled(5s));
  ASSERT_TRUE(frame);
  const v1::BodyFrame& block = frame->bodies(0);
  ASSERT_EQ(block.vertex_count(), 602u);
  ASSERT_EQ(block.positions_size(), 3 * 602);
  ASSERT_EQ(block.triangles_size(), 3 * 1200);
  std::vector<int> uses(602, 0);
  for (std::uint32_t v : block.triangles()) {
    ASSERT_LT(v, 602u);
    ++uses[v];
  }
  for (std::size_t v = 0; v < uses.size(); ++v) {
    EXPECT_GT(uses[v], 0) << "vertex " << v << " is on no triangle";
    // every vertex is on a face of the box: some coordinate at +-0.5 m
    float outermost = 0;
    for (int a = 0; a < 3; ++a)
      outermost = std::max(outermost, std::abs(block.positions(3 * v + a)));
    EXPECT_NEAR(outermost, 0.5f, 1e-5f) << "vertex " << v;
  }
}

TEST_F(FeltdTest, StatsNameEachBodysIntegratorAndStrain) {
  auto client = greeted("steerer");
  v1::SetBodyParameters set;
  set.set_body_id(0);
  set.set_integrator("rk4");
  client->set_body_parameters(set);
  // statistics are measured every half second
  const auto deadline = std::chrono::steady_clock::now() + scaled(5s);
  v1::BodyStats body;
  while (std::chrono::steady_clock::now() < deadline) {
    const auto stats = client->stats();
    if (stats.scene().body_stats_size() > 0) body = stats.scene().body_stats(0);
    if (body.integrator() == "rk4") break;
    std::this_thread::sleep_for(50ms);
  }
  EXPECT_EQ(body.integrator(), "rk4");
  EXPECT_EQ(body.kind(), "cloth");
  EXPECT_GT(body.max_strain(), 0.0);
  EXPECT_GT(body.kinetic_energy(), -1e-12);
}

}  // namespace
}  // namespace felt::test
