#include "runtime/live_haptic_frames.hpp"

#include <set>

#include <gtest/gtest.h>

#include "runner_fixtures.hpp"

namespace felt {
namespace {

TEST(LiveHapticFrames, TheFirstUseMakesAStillFrameOfTheLatestSnapshot) {
  ManualClock clock;
  LiveScene live(flat_cloth_scene(), 0, clock);
  LiveHapticFrames frames(live, TriangleQueryKind::kBvhSphere2);
  const auto frame = frames.current();
  ASSERT_NE(frame, nullptr);
  EXPECT_EQ(frame->to, live.latest());
  EXPECT_EQ(frame->from, live.latest());
  EXPECT_EQ(frames.current(), frame);  // nothing new was published
}

TEST(LiveHapticFrames, RenderingAsksForTheNormalsItShadesWith) {
  ManualClock clock;
  LiveScene live(flat_cloth_scene(), 0, clock);
  LiveHapticFrames frames(live, TriangleQueryKind::kBvhSphere2);
  EXPECT_TRUE(frames.current()->to->bodies[0].normals.empty());  // made before anyone asked
  live.publish();
  frames.publish(SteadyClock::now());
  const auto frame = frames.current();
  EXPECT_EQ(frame->to->bodies[0].normals.size(), frame->to->bodies[0].positions.size());
}

TEST(LiveHapticFrames, PublicationsFollowWhileProxiesAreInUseAndRefitRetiredFrames) {
  ManualClock clock;
  LiveScene live(flat_cloth_scene(Vec3(0, -9.81, 0)), 0, clock);
  LiveHapticFrames frames(live, TriangleQueryKind::kBvhSphere2);
  std::set<const HapticFrame*> made{frames.current().get()};
  auto previous_to = live.latest();
  for (int i = 0; i < 6; ++i) {
    live.scene.world.step();
    live.publish();
    frames.publish(SteadyClock::now());
    const auto frame = frames.current();
    // the frame goes from the snapshot before to the one just published
    EXPECT_EQ(frame->to, live.latest());
    EXPECT_EQ(frame->from, previous_to);
    previous_to = frame->to;
    made.insert(frame.get());
  }
  // seven frames made, but only the pool's three objects: retired ones are refitted
  EXPECT_LE(made.size(), 3u);
}

TEST(LiveHapticFrames, NoFrameIsMadeForAPublicationOnceProxiesAreIdle) {
  ManualClock clock;
  LiveScene live(flat_cloth_scene(Vec3(0, -9.81, 0)), 0, clock);
  LiveHapticFrames frames(live, TriangleQueryKind::kBvhSphere2);
  const auto first = frames.current();
  live.scene.world.step();
  live.publish();
  frames.publish(SteadyClock::now() + std::chrono::seconds(2));  // no render for two seconds
  // the physics thread made no frame for it: renders still get the one they had
  EXPECT_EQ(frames.current(), first);
  EXPECT_EQ(first->to->step, 0u);
}

}  // namespace
}  // namespace felt
