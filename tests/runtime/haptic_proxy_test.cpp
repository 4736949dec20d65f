// One device's proxy in a scene: grabbing, and device positions that are no reading.

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
  HapticProxy proxy(1, scene.haptics);
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
    EXPECT_EQ(report.flags, kStepOk) << far.transpose();
  }

  // back to a reading 10 cm above the cloth: the grab spring, clamped to 10 N, pulls down
  out = proxy.update(surface, 1e-3, Vec3(0.02, 0.1, 0.03), kGrabButton, reactions);
  ASSERT_TRUE(out.grabbing);
  EXPECT_EQ(out.grabbed_vertex, held);
  EXPECT_NEAR(out.contact.force.norm(), 10, 1e-9);
  EXPECT_LT(out.contact.force.y(), -9);
  reactions.apply_and_clear(scene.world);
  EXPECT_EQ(scene.world.step().flags, kStepOk);
  reactions.forget(1);
}

}  // namespace
}  // namespace felt
