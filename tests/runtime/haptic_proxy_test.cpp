// One device's proxy in a scene: grabbing, device positions that are no reading, and the
// reaction of what a local renderer felt.

#include <limits>
#include <memory>

#include <gtest/gtest.h>

#include "runner_fixtures.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/haptic_proxy.hpp"
#include "runtime/reaction_accumulator.hpp"
#include "runtime/snapshot.hpp"

namespace felt {
namespace {

// Issue 31: grabbing, then moving the device to 1e308 gave a NaN force, at 1e200 no force
// instead of the clamp, and the scene's steps were unrecoverable until the release. A device
// beyond ±1e6 m is no reading: no force, nothing pulled, and the grab holds for the next.
TEST(HapticProxy, AGrabHoldsThroughDevicePositionsThatAreNoReading) {
  Scene scene = flat_cloth_scene();  // a flat cloth in y = 0, proxy radius 5 cm, 10 N at most
  const auto frame = make_haptic_frame(make_snapshot(scene.world), nullptr, nullptr,
                                       TriangleQueryKind::kBvhAabb4, SteadyClock::now());
  const HapticSurface surface = frame->surface_at(1);
  ReactionAccumulator reactions;
  HapticProxy proxy(ProxyKey{0, 1}, scene.haptics);
  const Vec3 above(0.02, 0.2, 0.03);
  const Vec3 pressed(0.02, 0.04, 0.03);  // the sphere 1 cm into the cloth
  for (int i = 0; i <= 20; ++i)
    proxy.update(surface, 1e-3, above + (pressed - above) * i / 20.0, 0, reactions);
  ProxyOutput out = proxy.update(surface, 1e-3, pressed, kGrabButton, reactions);
  ASSERT_TRUE(out.grabbing);
  const std::uint32_t held = out.grabbed_vertex;

  const Real huge = std::numeric_limits<Real>::max();
  for (const Vec3& far : {Vec3(0, 1e308, 0), Vec3(0, 1e200, 0), Vec3(-huge, huge, 0)}) {
    out = proxy.update(surface, 1e-3, far, kGrabButton, reactions);
    EXPECT_TRUE(out.contact.force.allFinite() && out.contact.proxy.allFinite() &&
                out.contact.contact_point.allFinite())
        << far.transpose();
    EXPECT_EQ(out.contact.force, Vec3::Zero()) << far.transpose();
    EXPECT_TRUE(out.grabbing);
    EXPECT_EQ(out.grabbed_vertex, held);
    reactions.apply_and_clear(scene.world);
    const StepReport report = scene.world.step();
    EXPECT_EQ(report.flags, StepFlags{}) << far.transpose();
  }

  // back to a reading 10 cm above the cloth: the grab spring, clamped to 10 N, pulls down
  out = proxy.update(surface, 1e-3, Vec3(0.02, 0.1, 0.03), kGrabButton, reactions);
  ASSERT_TRUE(out.grabbing);
  EXPECT_EQ(out.grabbed_vertex, held);
  EXPECT_NEAR(out.contact.force.norm(), 10, 1e-9);
  EXPECT_LT(out.contact.force.y(), -9);
  reactions.apply_and_clear(scene.world);
  EXPECT_EQ(scene.world.step().flags, StepFlags{});
  reactions.forget(ProxyKey{0, 1});
}

// Issue 26: a local-model proxy's body takes the reaction of the contact the client's renderer
// felt (its triangle, stiffness · (proxy − device) clamped), not the server's own contact.
TEST(HapticProxy, ALocalContactPushesTheTriangleTheClientFelt) {
  const auto positions_after_a_step = [](const LocalContact* local) {
    Scene scene = flat_cloth_scene();  // in y = 0, 1 m square, 10 N at most
    const auto frame = make_haptic_frame(make_snapshot(scene.world), nullptr, nullptr,
                                         TriangleQueryKind::kBvhAabb4, SteadyClock::now());
    ReactionAccumulator reactions;
    HapticProxy proxy(ProxyKey{0, 1}, scene.haptics);
    // the server's proxy is free, 20 cm above the cloth
    const ProxyOutput out =
        proxy.update(frame->surface_at(1), 1e-3, Vec3(0.5, 0.2, 0.5), 0, reactions, local);
    EXPECT_FALSE(out.contact.in_contact);
    reactions.apply_and_clear(scene.world);
    EXPECT_EQ(scene.world.step().flags, StepFlags{});
    return make_snapshot(scene.world)->bodies[0].positions;
  };
  const std::vector<Vec3> untouched = positions_after_a_step(nullptr);
  const Scene probe = flat_cloth_scene();
  const std::vector<Triangle>& triangles = make_snapshot(probe.world)->bodies[0].triangles();
  LocalContact felt;
  felt.in_contact = true;
  felt.body_id = make_snapshot(probe.world)->bodies[0].body_id.value();
  felt.triangle = static_cast<std::int32_t>(triangles.size() / 2 + 5);
  felt.barycentric = Vec3::Constant(1.0 / 3);
  felt.proxy = Vec3(0.5, 0.3, 0.5);  // 10 cm above the device: 40 N, clamped to 10 N
  felt.stiffness = 400;
  const std::vector<Vec3> pushed = positions_after_a_step(&felt);
  const Triangle& corners = triangles[static_cast<std::size_t>(felt.triangle)];
  for (std::uint32_t v = 0; v < pushed.size(); ++v) {
    const bool corner = v == corners[0] || v == corners[1] || v == corners[2];
    if (corner) {
      // pushed down, away from the proxy above it
      EXPECT_LT(pushed[v].y(), untouched[v].y() - 1e-9) << "corner " << v;
    } else {
      EXPECT_EQ(pushed[v], untouched[v]) << "vertex " << v;  // one step: only the corners
    }
  }
  // a triangle the surface does not have pushes nothing
  felt.triangle = static_cast<std::int32_t>(triangles.size());
  EXPECT_EQ(positions_after_a_step(&felt), untouched);
}

}  // namespace
}  // namespace felt
