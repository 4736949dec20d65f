#include "runtime/scene_runner.hpp"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "runner_fixtures.hpp"

namespace felt {
namespace {

TEST(SceneRunner, PublishesSnapshotsThatFollowItsClock) {
  ManualClock clock;
  SceneRunner runner(flat_cloth_scene(Vec3(0, -9.81, 0)), {}, {}, {}, clock);
  const auto first = runner.latest();
  EXPECT_EQ(first->step, 0u);
  runner.start();
  ASSERT_TRUE(settled(clock));
  EXPECT_EQ(runner.latest()->step, 0u);  // nothing is due before the clock moves
  // half a step first, so that the clock never stops where a step falls due
  clock.advance(500us);
  ASSERT_TRUE(move_clock(clock, 200ms));
  const auto later = runner.latest();
  runner.stop();
  EXPECT_EQ(later->step, 200u);  // a step of 1 ms per millisecond of the clock, exactly
  EXPECT_DOUBLE_EQ(later->sim_time, 0.2);
  // the centre particle sags under gravity
  const std::uint32_t centre = 5 * 11 + 5;
  EXPECT_LT(later->bodies[0].positions[centre].y(), first->bodies[0].positions[centre].y() - 1e-3);
  // snapshots are immutable: the first one still shows the start
  EXPECT_EQ(first->bodies[0].positions[centre].y(), 0.0);
  EXPECT_EQ(runner.latest()->step, runner.stats().steps);
}

TEST(SceneRunner, StepsNobodyWatchesAreLeftOutOfTheSnapshotsUntilAFrameIsAskedFor) {
  ManualClock clock;
  SceneRunner runner(flat_cloth_scene(Vec3(0, -9.81, 0)), {}, {}, {}, clock);
  runner.start();
  ASSERT_TRUE(settled(clock));
  clock.advance(500us);
  ASSERT_TRUE(move_clock(clock, 100ms));
  EXPECT_TRUE(runner.stale());  // a hundred steps, no snapshot of them
  EXPECT_EQ(runner.latest()->step, 0u);
  runner.prepare_frames();  // a client subscribes
  ASSERT_TRUE(wait_for([&] { return !runner.stale(); }));
  EXPECT_EQ(runner.latest()->step, 100u);
  // read lately: every pass of steps is published from now on
  ASSERT_TRUE(move_clock(clock, 10ms));
  EXPECT_EQ(runner.latest()->step, 110u);
  EXPECT_FALSE(runner.stale());
  runner.stop();
}

TEST(SceneRunner, ReportsTheRealTimeFactorOverHalfASecondOfItsClock) {
  ManualClock clock;
  SceneRunner runner(flat_cloth_scene(), {}, {}, {}, clock);
  runner.start();
  ASSERT_TRUE(settled(clock));
  clock.advance(500us);
  ASSERT_TRUE(move_clock(clock, 490ms));
  EXPECT_EQ(runner.stats().real_time_factor, 0);  // the window is not full yet
  ASSERT_TRUE(move_clock(clock, 10ms));
  const RunnerStats stats = runner.stats();
  runner.stop();
  // 500 steps of 1 ms in the 500.5 ms since the thread started; a step takes no time of this
  // clock
  EXPECT_EQ(stats.steps, 500u);
  EXPECT_DOUBLE_EQ(stats.real_time_factor, 0.5 / 0.5005);
  EXPECT_EQ(stats.ms_per_step, 0);
}

// Issue 31, found 4: a scene whose steps cannot keep up with its clock (a step of 1e-9 s then)
// took every step due before it published: one frame in 3 s, and GetStats said 0 steps. On a
// clock that moves 100 us at every reading, each step takes 200 us for 1 us of the scene.
TEST(SceneRunner, ASceneThatCannotKeepUpStillPublishesEveryPassOfItsClock) {
  TickingClock clock(100us);
  SceneRunner runner(flat_cloth_scene(Vec3(0, -9.81, 0), 1e-6), {}, {}, {}, clock);
  runner.start();
  ASSERT_TRUE(wait_for([&] { return runner.latest()->step >= 5000; }, 20s));
  const auto snapshot = runner.latest();
  const RunnerStats stats = runner.stats();
  runner.stop();
  // a pass ends after 16 ms of the clock: at most 16 ms / 200 us = 80 steps between snapshots
  EXPECT_LE(snapshot->step, 81 * snapshot->version);
  EXPECT_GE(stats.steps + 81, snapshot->step);  // the statistics are as fresh as the snapshots
  EXPECT_NEAR(stats.ms_per_step, 0.1, 1e-9);    // a step's two readings are one tick apart
  EXPECT_GT(stats.real_time_factor, 0);
  EXPECT_LT(stats.real_time_factor, 0.01);
}

// Issue 31, found 5: a time scale of 1e-300 overflowed the pacing arithmetic and the physics
// thread spun at 100 % of a core while the scene stood still.
TEST(SceneRunner, ATinyTimeScaleHoldsTheSceneStillAndItsThreadAsleep) {
  ManualClock clock;
  SceneRunner runner(flat_cloth_scene(Vec3(0, -9.81, 0)), {}, {}, {}, clock);
  runner.latest();  // watched: its steps are published
  runner.start();
  ASSERT_TRUE(settled(clock));
  clock.advance(500us);
  ASSERT_TRUE(move_clock(clock, 10ms));
  Awaited<SceneStatus> scaled;
  runner.set_time_scale(0, 1e-300, scaled.completion());
  ASSERT_TRUE(scaled.get());
  const std::uint64_t steps = runner.latest()->step;
  ASSERT_TRUE(move_clock(clock, 1s));  // only possible while the thread sleeps between looks
  EXPECT_EQ(runner.latest()->step, steps);
  EXPECT_EQ(runner.stats().time_scale, 1e-300);
  runner.stop();
}

TEST(SceneRunner, AppliesPostedCommandsBetweenSteps) {
  SceneRunner runner(flat_cloth_scene());
  runner.start();
  std::atomic<std::uint64_t> seen_at{0};
  // lift a particle and pin it there: every snapshot after the command shows it lifted
  runner.post([&](Scene& scene) {
    scene.world.cloths()[0].state().x[60] += Vec3(0, 0.1, 0);
    scene.world.cloths()[0].pin(60);
    seen_at = scene.world.step_count() + 1;
  });
  ASSERT_TRUE(wait_for([&] { return seen_at > 0 && runner.latest()->step >= seen_at; }));
  EXPECT_DOUBLE_EQ(runner.latest()->bodies[0].positions[60].y(), 0.1);
  runner.stop();
}

/// One update of `proxy` with no buttons held.
HapticContact touch(ProxyHandle& proxy, const Vec3& device) {
  return proxy.update(device, 0).contact;
}

TEST(SceneRunner, TouchPushesOutOfTheClothAndDentsIt) {
  ManualClock clock;
  SceneRunner runner(flat_cloth_scene(), {}, {}, {}, clock);
  ProxyHandle proxy = runner.open_proxy({0, 1});
  const std::uint32_t centre = 5 * 11 + 5;
  // a proxy of radius 5 cm centred 3 cm above the centre of the sheet: depth 2 cm
  const Vec3 above(0, 0.03, 0);
  const HapticContact contact = touch(proxy, above);
  ASSERT_TRUE(contact.in_contact);
  EXPECT_NEAR(contact.force.y(), 400 * 0.02, 1e-6);
  EXPECT_NEAR(contact.force.x(), 0, 1e-12);
  EXPECT_NEAR(contact.force.z(), 0, 1e-12);
  EXPECT_NEAR(contact.contact_point.y(), 0, 1e-12);

  // held there for 0.3 s, one update per step of the scene, the reaction pushes the sheet down
  // under the proxy. The scene's own clock keeps the updates in step with the physics: on the
  // wall's clock a loaded machine let the held reaction push for tens of steps between two
  // updates, and the sheet, pushed past the proxy, sprang back up through it (CI, 8 cm up).
  runner.start();
  ASSERT_TRUE(settled(clock));
  clock.advance(500us);
  for (int step = 0; step < 300; ++step) {
    touch(proxy, above);
    ASSERT_TRUE(move_clock(clock, 1ms));
  }
  runner.stop();
  EXPECT_EQ(runner.latest()->step, 300u);
  EXPECT_LT(runner.latest()->bodies[0].positions[centre].y(), -0.005);
  EXPECT_EQ(runner.stats().haptic_updates, 301u);

  // from below, the force points down
  ProxyHandle other = runner.open_proxy({0, 2});
  const HapticContact below = touch(other, Vec3(0.2, -0.2, 0.2));
  EXPECT_FALSE(below.in_contact);
  EXPECT_EQ(below.force, Vec3::Zero());
  EXPECT_EQ(below.contact_point, Vec3(0.2, -0.2, 0.2));
}

TEST(SceneRunner, AProxyIsClosedWhenItsHandleGoes) {
  SceneRunner runner(flat_cloth_scene());
  {
    ProxyHandle first = runner.open_proxy({0, 1});
    ASSERT_TRUE(touch(first, Vec3(0, 0.03, 0)).in_contact);
    ProxyHandle moved = std::move(first);  // the moved-from handle closes nothing
    touch(moved, Vec3(0, 0.03, 0));
    ProxyHandle second = runner.open_proxy({0, 2});
    touch(second, Vec3(0.2, 0.5, 0.2));
    EXPECT_EQ(runner.presence(1h).size(), 2u);
  }
  // both are forgotten: no presence shown to the others, and no reaction held for the cloth
  EXPECT_TRUE(runner.presence(1h).empty());
}

TEST(SceneRunner, ASingleTouchKeepsPushingUntilTheNextUpdate) {
  // a device slower than the physics: its last reaction is held between its updates
  ManualClock clock;
  SceneRunner runner(flat_cloth_scene(), {}, {}, {}, clock);
  ProxyHandle proxy = runner.open_proxy({0, 1});
  const std::uint32_t centre = 5 * 11 + 5;
  ASSERT_TRUE(touch(proxy, Vec3(0, 0.03, 0)).in_contact);
  runner.start();
  ASSERT_TRUE(settled(clock));
  clock.advance(500us);
  ASSERT_TRUE(move_clock(clock, 200ms));
  const Real dented = runner.latest()->bodies[0].positions[centre].y();
  EXPECT_LT(dented, -0.005);
  // a free update releases it: the sheet springs back toward flat (slowly from a shallow dent:
  // the tension of a sheet with none at rest grows with the square of its dent)
  touch(proxy, Vec3(0, 1, 0));
  ASSERT_TRUE(move_clock(clock, 1800ms));
  runner.stop();
  EXPECT_EQ(runner.latest()->step, 2000u);
  EXPECT_GT(runner.latest()->bodies[0].positions[centre].y(), dented * 2 / 3);
}

TEST(SceneRunner, AClientsArrivalHasThePhysicsThreadMakeHapticFramesBeforeItsFirstTouch) {
  // a falling cloth: a frame the physics thread made spans two snapshots, while the one the
  // first touch of an idle scene makes for itself is still (from = to)
  SceneRunner runner(flat_cloth_scene(Vec3(0, -9.81, 0)));
  runner.start();
  ASSERT_TRUE(wait_for([&] { return runner.latest()->step >= 5; }));
  runner.prepare_haptics();
  const std::uint64_t prepared_at = runner.latest()->step;
  ASSERT_TRUE(wait_for([&] { return runner.latest()->step >= prepared_at + 5; }));
  const auto frame = runner.haptic_frame();
  runner.stop();
  EXPECT_NE(frame->from, frame->to);
  EXPECT_GT(frame->to->step, prepared_at);
}

TEST(SceneRunner, ForceIsClampedToTheMaximum) {
  SceneRunner runner(flat_cloth_scene());
  ProxyHandle proxy = runner.open_proxy({0, 1});
  // at the surface the depth is the whole radius: 400 N/m · 5 cm = 20 N, clamped to 10 N
  const HapticContact contact = touch(proxy, Vec3(0.01, 0.0001, 0.01));
  ASSERT_TRUE(contact.in_contact);
  EXPECT_NEAR(contact.force.norm(), 10, 1e-9);
}

TEST(SceneRunner, TheServoThreadDrivesTheScenesScriptedDevices) {
  Scene scene = flat_cloth_scene();
  DevicePath press;
  press.shape = DevicePath::Shape::kPress;
  press.a = Vec3(0, 0.3, 0);
  press.b = Vec3(0, -0.05, 0);  // 10 cm into the sheet for a 5 cm proxy
  press.period = 0.1;
  scene.devices.push_back({"finger", press});
  SceneRunner runner(std::move(scene));
  runner.start();
  // the sheet, pinned only at its corners, bounces on the finger: watch it for half a second
  double largest_push = 0, deepest = 0;
  const auto deadline = std::chrono::steady_clock::now() + test::scaled(500ms);
  while (std::chrono::steady_clock::now() < deadline) {
    const auto devices = runner.device_states();
    ASSERT_EQ(devices.size(), 1u);
    if (devices[0].in_contact) largest_push = std::max(largest_push, devices[0].force.y());
    deepest = std::min(deepest, runner.latest()->bodies[0].positions[5 * 11 + 5].y());
    std::this_thread::sleep_for(2ms);
  }
  runner.stop();
  const std::uint64_t ticks = runner.stats().servo.ticks;
  EXPECT_GT(ticks, 100u);        // about 500 on an idle machine
  EXPECT_GT(largest_push, 1.0);  // the sheet pushes back up on the finger
  EXPECT_LT(deepest, -0.05);     // and the finger pushes it down
  // stopping stopped the servo too
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(runner.stats().servo.ticks, ticks);
}

TEST(SceneRunner, StopsPromptly) {
  SceneRunner runner(flat_cloth_scene());
  runner.start();
  std::this_thread::sleep_for(20ms);
  const auto start = std::chrono::steady_clock::now();
  runner.stop();
  EXPECT_LT(std::chrono::steady_clock::now() - start, test::scaled(1s));
}

// A cloth whose springs explicit Euler cannot integrate at any substep: its unrecoverable
// steps reach clients as events, coalesced rather than one per step. A step budget of 50
// substeps keeps each failing step cheap (the default 1000 spends seconds on the 1200 steps,
// more than a loaded machine gives a slice of the clock).
TEST(SceneRunner, UnrecoverableStepsBecomeCoalescedEvents) {
  HealthSettings health;
  health.step_budget = 50;
  Scene scene = flat_cloth_scene(Vec3(0, -9.81, 0), 1e-3, health);
  ClothBody& cloth = scene.world.cloths()[0];
  ClothParams params = cloth.params();
  params.spring(SpringKind::kStructural).stiffness = 1e8;
  cloth.set_params(params);
  cloth.set_integrator(make_integrator("explicit_euler"));
  ManualClock clock;
  SceneRunner runner(std::move(scene), {}, {}, {}, clock);
  auto log = std::make_shared<EventLog>();
  runner.members().join({7, "test", log});
  runner.start();
  ASSERT_TRUE(settled(clock));
  clock.advance(500us);
  ASSERT_TRUE(move_clock(clock, 1200ms));
  const std::uint64_t failed = runner.stats().unrecoverable_steps;
  std::vector<SceneEvent> events = log->events();
  runner.stop();
  std::erase_if(events,
                [](const SceneEvent& e) { return e.kind != SceneEvent::Kind::kUnrecoverableStep; });
  // every step but the first few fails: the first pass's (10 steps) are told at once, then the
  // steps of each half second of the clock in one event, not one event per step
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].step, 10u);
  EXPECT_GT(events[0].count, 0u);
  EXPECT_EQ(events[0].body_ids, std::vector<BodyId>{0});
  EXPECT_EQ(events[1].step, 510u);
  EXPECT_EQ(events[1].count, 500u);
  EXPECT_EQ(events[2].step, 1010u);
  EXPECT_EQ(events[2].count, 500u);
  EXPECT_EQ(failed, events[0].count + 1000u + 190u);
  EXPECT_LT(events[0].sequence, events[1].sequence);
  // stopping tells the rest (and, after it, the steps that spent their whole budget)
  std::vector<SceneEvent> all = log->events();
  std::erase_if(all,
                [](const SceneEvent& e) { return e.kind != SceneEvent::Kind::kUnrecoverableStep; });
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all.back().count, 190u);
}

}  // namespace
}  // namespace felt
