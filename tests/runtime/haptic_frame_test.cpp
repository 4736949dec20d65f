// The haptic frames the physics thread publishes, as a proxy that updates rarely sees them:
// the bound on the motion between any two frames of a chain, the snapshots a kept surface
// holds on to, a new proxy's first contact, and a cloth that passes a still device between two
// of the proxy's updates; and when a local model cut from a frame shows the surface.

#include <chrono>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "core/geometry/surface_normals.hpp"
#include "core/haptics/god_object.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/haptic_proxy.hpp"
#include "runtime/proxy_render.hpp"
#include "runtime/reaction_accumulator.hpp"

namespace felt {
namespace {

constexpr std::uint32_t kSide = 11;  // a 1 m square cloth, 10 × 10 cells

std::shared_ptr<const std::vector<Triangle>> square_cloth() {
  auto triangles = std::make_shared<std::vector<Triangle>>();
  for (std::uint32_t j = 0; j + 1 < kSide; ++j) {
    for (std::uint32_t i = 0; i + 1 < kSide; ++i) {
      const std::uint32_t v = j * kSide + i;
      triangles->push_back({v, v + 1, v + kSide + 1});
      triangles->push_back({v, v + kSide + 1, v + kSide});
    }
  }
  return triangles;
}

/// A snapshot of one body: the cloth flat at height z, its vertex i raised by `bump` (m).
std::shared_ptr<const SceneSnapshot> snapshot_at(
    std::uint64_t step, Real z, const std::shared_ptr<const std::vector<Triangle>>& surface,
    Real bump = 0) {
  auto snapshot = std::make_shared<SceneSnapshot>();
  snapshot->step = step;
  BodySnapshot& body = snapshot->bodies.emplace_back();
  body.body_id = 7;
  body.surface = surface;
  for (std::uint32_t j = 0; j < kSide; ++j) {
    for (std::uint32_t i = 0; i < kSide; ++i) {
      body.positions.emplace_back(Real(i) / (kSide - 1) - 0.5, Real(j) / (kSide - 1) - 0.5, z);
    }
  }
  body.positions[0].z() += bump;
  compute_vertex_normals(body.positions, body.triangles(), body.normals);
  return snapshot;
}

/// Frames published one after another, two taking turns as the batch runner's do (the older
/// is refitted into the newer, so a frame a reader let go of is reused at once).
struct Publisher {
  std::shared_ptr<HapticFrame> frame, spare;
  SteadyClock::time_point now = SteadyClock::now();

  const HapticFrame& publish(std::shared_ptr<const SceneSnapshot> snapshot) {
    now += std::chrono::milliseconds(10);
    auto next = make_haptic_frame(std::move(snapshot), frame.get(), std::move(spare),
                                  TriangleQueryKind::kBvhAabb4, now);
    spare = std::exchange(frame, std::move(next));
    return *frame;
  }
};

TEST(HapticFrame, AChainOfFramesBoundsTheMotionBetweenAnyTwoOfThem) {
  const auto surface = square_cloth();
  Publisher publisher;
  const HapticFrame& first = publisher.publish(snapshot_at(1, 0, surface));
  EXPECT_EQ(first.motion[0].travelled, 0);
  const std::uint64_t chain = first.motion[0].chain;
  EXPECT_NE(chain, 0u);
  // one vertex goes up 3 cm while the whole cloth goes down 1 cm a step
  Real expected = 0;
  for (int step = 2; step <= 6; ++step) {
    const Real bump = step % 2 == 0 ? 0.03 : 0;
    const HapticFrame& frame =
        publisher.publish(snapshot_at(step, -0.01 * (step - 1), surface, bump));
    const Real moved = step % 2 == 0 ? 0.02 : 0.04;  // the bump's vertex moves farthest
    expected += moved;
    EXPECT_NEAR(frame.motion[0].max_displacement, moved, 1e-12) << "step " << step;
    EXPECT_NEAR(frame.motion[0].travelled, expected, 1e-12) << "step " << step;
    EXPECT_EQ(frame.motion[0].chain, chain) << "step " << step;
  }
  // a new surface under the same id (a reset scene) starts a new chain
  const HapticFrame& reset = publisher.publish(snapshot_at(7, 0, square_cloth()));
  EXPECT_NE(reset.motion[0].chain, chain);
  EXPECT_EQ(reset.motion[0].travelled, 0);
}

TEST(HapticFrame, AKeptSurfaceHoldsItsSnapshotsAfterTheFrameIsReused) {
  const auto surface = square_cloth();
  Publisher publisher;
  publisher.publish(snapshot_at(1, 0, surface));
  auto second = snapshot_at(2, -0.01, surface);
  const std::weak_ptr<const SceneSnapshot> watched = second;
  const HapticSurface kept = publisher.publish(std::move(second)).surface_at(0.5);
  for (int step = 3; step <= 6; ++step) publisher.publish(snapshot_at(step, -0.01 * step, surface));
  EXPECT_FALSE(watched.expired()) << "a kept surface's vertices were freed under it";
  EXPECT_EQ(kept.bodies[0].to[0].z(), -0.01);
}

// A proxy keeps the snapshots it last rendered against until its next update, unless it is
// idle: then it lets them go (an idle client must not hold a large scene's memory).
TEST(HapticFrame, AnIdleProxyLetsGoOfTheSnapshotsItKept) {
  const auto surface = square_cloth();
  ReactionAccumulator reactions;
  HapticProxy proxy(ProxyKey{0, 1}, ProxySettings{});
  std::weak_ptr<const SceneSnapshot> kept;
  {
    Publisher publisher;
    auto snapshot = snapshot_at(1, 0, surface);
    kept = snapshot;
    const HapticFrame& frame = publisher.publish(std::move(snapshot));
    const SteadyClock::time_point now = SteadyClock::now();
    proxy.seconds_since_last(now);
    proxy.update(frame.surface_at(1), 0, Vec3(0.1, 0.1, 0.05), 0, reactions);
    proxy.forget_surface_if_idle(now + std::chrono::milliseconds(500), std::chrono::seconds(1));
  }
  EXPECT_FALSE(kept.expired()) << "a proxy updated half a second ago keeps its surface";
  proxy.forget_surface_if_idle(SteadyClock::now() + std::chrono::seconds(2),
                               std::chrono::seconds(1));
  EXPECT_TRUE(kept.expired());
  reactions.forget(ProxyKey{0, 1});
}

// A new proxy's first update, overlapping the cloth or not, comes out the same whatever the
// body's structure: brute force over all the triangles is the reference. One that overlaps it
// is pushed out on its own side.
TEST(HapticFrame, ANewProxysFirstContactIsTheSameWithEveryStructureAsWithBruteForce) {
  const auto surface = square_cloth();
  const auto bumped = snapshot_at(1, 0, surface, 0.03);
  ProxySettings settings;
  settings.radius = 0.03;
  settings.stiffness = 1000;
  settings.max_force = 50;
  const SteadyClock::time_point now = SteadyClock::now();
  const auto reference =
      make_haptic_frame(bumped, nullptr, nullptr, TriangleQueryKind::kBruteForce, now);
  ReactionAccumulator reactions;
  std::uint32_t key = 0;
  const auto first_update = [&](const HapticFrame& frame, const Vec3& device) {
    HapticProxy proxy(ProxyKey{0, ++key}, settings);
    const ProxyOutput out = proxy.update(frame.surface_at(1), 0, device, 0, reactions);
    reactions.forget(ProxyKey{0, key});
    return out.contact;
  };
  int overlapping = 0;
  for (const TriangleQueryKind kind : {TriangleQueryKind::kBvhAabb4, TriangleQueryKind::kBvhSphere2,
                                       TriangleQueryKind::kSpatialHash}) {
    const auto frame = make_haptic_frame(bumped, nullptr, nullptr, kind, now);
    for (Real x = -0.5; x <= 0.5; x += 0.125) {
      for (Real y = -0.5; y <= 0.5; y += 0.125) {
        for (const Real z : {-0.025, -0.01, 0.005, 0.02, 0.035}) {
          const Vec3 device(x, y, z);
          const HapticContact expected = first_update(*reference, device);
          const HapticContact contact = first_update(*frame, device);
          EXPECT_EQ(contact.proxy, expected.proxy)
              << to_string(kind) << " at " << device.transpose();
          EXPECT_EQ(contact.force, expected.force)
              << to_string(kind) << " at " << device.transpose();
          if (expected.in_contact) ++overlapping;
        }
      }
    }
  }
  EXPECT_GT(overlapping, 100);
  // 1 cm from the flat part with a 3 cm sphere, on either side (the normals point up): pushed
  // out to touch it on the device's side, 1000 N/m · 2 cm
  const auto flat = make_haptic_frame(snapshot_at(1, 0, surface), nullptr, nullptr,
                                      TriangleQueryKind::kBvhAabb4, now);
  for (const Real side : {1.0, -1.0}) {
    const HapticContact pushed = first_update(*flat, Vec3(0.23, 0.26, side * 0.01));
    ASSERT_TRUE(pushed.in_contact) << side;
    EXPECT_NEAR(pushed.proxy.z(), side * 0.03, 1e-12);
    EXPECT_NEAR(pushed.force.z(), side * 20, 1e-9);
    EXPECT_NEAR(pushed.force.x(), 0, 1e-12);
    EXPECT_NEAR(pushed.force.y(), 0, 1e-12);
  }
}

// The cloth comes down 1 cm per frame from 2.5 cm above a still device; the proxy is updated
// at the first frame and then only every fifth: it is carried down with the cloth all the same.
TEST(HapticFrame, AProxyUpdatedEveryFifthFrameIsCarriedByACrossingCloth) {
  const auto surface = square_cloth();
  Publisher publisher;
  const Vec3 device(0.03, 0.02, 0);
  ProxySettings settings;
  settings.radius = 0.01;
  settings.max_force_change = 0;
  GodObject proxy(settings, device);
  const Real start = 0.025 + settings.radius;
  EXPECT_FALSE(
      proxy.update(publisher.publish(snapshot_at(1, start, surface)).surface_at(1), device, 1e-3)
          .in_contact);
  for (int step = 2; step <= 16; ++step) {
    const Real z = start - 0.01 * (step - 1);
    const HapticFrame& frame = publisher.publish(snapshot_at(step, z, surface));
    if (step % 5 != 1) continue;
    const HapticContact c = proxy.update(frame.surface_at(1), device, 0.05);
    EXPECT_LE(c.proxy.z(), z - settings.radius + 1e-9) << "step " << step;
    EXPECT_TRUE(c.in_contact) << "step " << step;
    EXPECT_LT(c.force.z(), 0) << "step " << step;
  }
}

// A local model shows its snapshot as the scene was when it was published, whatever the
// server's own render does with it. Dated one interval later (when that render reaches it), a
// model cut just after a 300 ms stall of the physics thread claimed to show the surface 300 ms
// ahead: the client moved it back by its velocities, and a swinging curtain came back through
// the client's proxy (felt touch --local-model on a loaded machine).
TEST(HapticFrame, ALocalModelAfterAStallShowsItsSnapshotWhenPublished) {
  const auto surface = square_cloth();
  Publisher publisher;
  auto still = std::const_pointer_cast<SceneSnapshot>(snapshot_at(1, 0, surface));
  still->sim_time = 0.001;
  publisher.publish(still);
  publisher.now += std::chrono::milliseconds(300);  // the physics thread stalls
  auto moved = std::const_pointer_cast<SceneSnapshot>(snapshot_at(2, 0.001, surface));
  moved->sim_time = 0.002;
  const HapticFrame& frame = publisher.publish(moved);
  ASSERT_EQ(frame.interval, std::chrono::milliseconds(310));

  HapticProxy proxy(ProxyKey{0, 1}, ProxySettings{});
  proxy.enable_local_model({.radius = 0.2, .rate_hz = 0});
  ReactionAccumulator reactions;
  const SteadyClock::time_point now = frame.published + std::chrono::milliseconds(1);
  const ProxyOutput out =
      render_proxy(proxy, frame, now, 1, Vec3(0, 0, 0.1), 0, reactions, nullptr);
  ASSERT_TRUE(out.local_model);
  EXPECT_EQ(now - out.local_model->rendered_at, std::chrono::milliseconds(1));
  // the positions are the newer snapshot's, moving 1 mm per millisecond of the scene
  const LocalModelBody& body = out.local_model->model.bodies.at(0);
  EXPECT_DOUBLE_EQ(body.positions.at(0).z(), 0.001);
  EXPECT_DOUBLE_EQ(body.velocities.at(0).z(), 1);
}

}  // namespace
}  // namespace felt
