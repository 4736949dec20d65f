// Requests a scene carries out between steps: pause, step, time scale, reset, save and restore,
// adding and removing bodies, forces; and what the other clients hear of them.

#include <atomic>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "core/world/state_hash.hpp"
#include "runner_fixtures.hpp"

namespace felt {
namespace {

using Kind = SceneEvent::Kind;

/// A falling flat cloth that can be built again (for reset), with a member that logs events.
struct Fixture {
  explicit Fixture(Clock& clock = wall_clock())
      : runner(
            flat_cloth_scene(Vec3(0, -9.81, 0)), SceneAccess{1, false, false},
            [] { return std::expected<Scene, SceneError>(flat_cloth_scene(Vec3(0, -9.81, 0))); },
            {}, clock) {
    runner.members().join({2, "observer", log});
    runner.start();
  }
  ~Fixture() { runner.stop(); }

  std::vector<Kind> kinds() const {
    std::vector<Kind> kinds;
    for (const SceneEvent& e : log->events()) kinds.push_back(e.kind);
    return kinds;
  }

  std::shared_ptr<EventLog> log = std::make_shared<EventLog>();
  SceneRunner runner;
};

/// Runs a reset's or an added body's build at once, on the calling thread.
void build_here(std::function<void()> job) {
  job();
}

/// Adds `body` as AddBody does, built at once.
void add(SceneRunner& runner, ClientId by, BuiltBody body, Completion<BodyInfo> done) {
  auto shared = std::make_shared<BuiltBody>(std::move(body));
  runner.add_body(
      by, build_here,
      [shared] { return std::expected<BuiltBody, RunnerError>(std::move(*shared)); },
      std::move(done));
}

/// The flat cloth as a body to add.
SceneBody another_cloth() {
  return SceneBody(std::move(flat_cloth_scene().world.cloths()[0]));
}

TEST(SceneRunnerRequests, NoStepFollowsAPauseReply) {
  Fixture f;
  // a hundred times faster than real time, the physics thread is always catching up: a pause
  // arrives between two steps of one catch-up run
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.set_time_scale(1, 100, done); }));
  int moved_after_pause = 0;
  for (int round = 0; round < 20; ++round) {
    std::this_thread::sleep_for(5ms);
    const auto paused = await<SceneStatus>([&](auto done) { f.runner.pause(1, done); });
    ASSERT_TRUE(paused);
    std::this_thread::sleep_for(5ms);
    const auto now = await<SceneStatus>([&](auto done) { f.runner.pause(1, done); });
    ASSERT_TRUE(now);
    if (now->step != paused->step) ++moved_after_pause;
    ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.resume(1, done); }));
  }
  EXPECT_EQ(moved_after_pause, 0);
}

TEST(SceneRunnerRequests, APausedSceneTakesExactlyTheStepsAskedFor) {
  ManualClock clock;
  Fixture f(clock);
  ASSERT_TRUE(settled(clock));
  const auto paused = await<SceneStatus>([&](auto done) { f.runner.pause(1, done); });
  ASSERT_TRUE(paused);
  EXPECT_TRUE(paused->paused);
  ASSERT_TRUE(move_clock(clock, 1s));
  EXPECT_EQ(f.runner.latest()->step, paused->step);  // nothing moves while paused
  const auto stepped = await<SceneStatus>([&](auto done) { f.runner.step(1, 250, done); });
  ASSERT_TRUE(stepped);
  EXPECT_EQ(stepped->step, paused->step + 250);
  EXPECT_DOUBLE_EQ(stepped->sim_time, static_cast<double>(stepped->step) * 1e-3);
  ASSERT_TRUE(wait_for([&] { return f.runner.latest()->step == stepped->step; }));
  // two requests queue up one after the other
  Awaited<SceneStatus> first, second;
  f.runner.step(1, 10, first.completion());
  f.runner.step(1, 5, second.completion());
  EXPECT_EQ(first.get()->step, stepped->step + 10);
  EXPECT_EQ(second.get()->step, stepped->step + 15);
  const auto resumed = await<SceneStatus>([&](auto done) { f.runner.resume(1, done); });
  ASSERT_TRUE(resumed);
  ASSERT_TRUE(settled(clock));
  clock.advance(500us);
  ASSERT_TRUE(move_clock(clock, 25ms));
  EXPECT_EQ(f.runner.latest()->step, resumed->step + 25);  // from where it was, in step
  EXPECT_EQ(f.kinds(), (std::vector<Kind>{Kind::kPaused, Kind::kResumed}));
}

// A paused scene publishes a new snapshot (a frame to every subscriber) only for what changes
// what clients see: not for pausing again, a time scale, pins, forces or saving its state.
TEST(SceneRunnerRequests, APausedScenePublishesOnlyVisibleChanges) {
  Fixture f;
  // a paused loop carries out a request pushed after an earlier one's completion in a later
  // turn, after the earlier turn's publication (if any)
  const auto later_turn = [&] {
    return await<SavedState>([&](auto done) { f.runner.save_state(1, done); }).has_value();
  };
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.pause(1, done); }));
  ASSERT_TRUE(later_turn());
  const std::uint64_t version = f.runner.latest()->version;
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.pause(1, done); }));
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.set_time_scale(1, 0.5, done); }));
  ASSERT_TRUE(
      await<BodyId>([&](auto done) { f.runner.apply_force(1, 0, {0}, Vec3(0, 1, 0), 1.0, done); }));
  ASSERT_TRUE(await<BodyId>([&](auto done) {
    f.runner.change_body(
        1, 0, [](World& world) { world.cloth(0)->pin(5); }, done);
  }));
  ASSERT_TRUE(later_turn());
  ASSERT_TRUE(later_turn());
  EXPECT_EQ(f.runner.latest()->version, version);
  ASSERT_TRUE(await<BodyInfo>([&](auto done) { add(f.runner, 1, another_cloth(), done); }));
  EXPECT_GT(f.runner.latest()->version, version);
}

TEST(SceneRunnerRequests, StepsNeedAPausedSceneAndASaneCount) {
  Fixture f;
  const auto running = await<SceneStatus>([&](auto done) { f.runner.step(1, 5, done); });
  ASSERT_FALSE(running);
  EXPECT_EQ(running.error().code, RunnerError::Code::kWrongState);
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.pause(1, done); }));
  const auto none = await<SceneStatus>([&](auto done) { f.runner.step(1, 0, done); });
  EXPECT_EQ(none.error().code, RunnerError::Code::kBadRequest);
}

TEST(SceneRunnerRequests, TimeScaleSetsSimulatedSecondsPerWallSecond) {
  ManualClock clock;
  Fixture f(clock);
  ASSERT_TRUE(settled(clock));
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.set_time_scale(1, 0.25, done); }));
  ASSERT_TRUE(settled(clock));
  const std::uint64_t start = f.runner.latest()->step;
  // a step of 1 ms is 4 ms of the clock at a quarter of real time: the clock moves half a step,
  // then two steps at a time, never stopping where one falls due
  clock.advance(2ms);
  ASSERT_TRUE(move_clock(clock, 400ms, 8ms));
  EXPECT_EQ(f.runner.latest()->step - start, 100u);  // 0.1 s of simulated time in 0.4 s
  const auto bad = await<SceneStatus>([&](auto done) { f.runner.set_time_scale(1, 0, done); });
  EXPECT_EQ(bad.error().code, RunnerError::Code::kBadRequest);
  EXPECT_EQ(f.log->events().back().kind, Kind::kTimeScale);
  EXPECT_DOUBLE_EQ(f.log->events().back().time_scale, 0.25);
}

TEST(SceneRunnerRequests, RestoringASavedStateRepeatsTheSameSteps) {
  Fixture f;
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.pause(1, done); }));
  const auto saved = await<SavedState>([&](auto done) { f.runner.save_state(1, done); });
  ASSERT_TRUE(saved);
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.step(1, 100, done); }));
  ASSERT_TRUE(wait_for([&] { return f.runner.latest()->step == saved->state->step + 100; }));
  const std::vector<Vec3> first = f.runner.latest()->bodies[0].positions;
  const auto restored =
      await<SceneStatus>([&](auto done) { f.runner.restore_state(1, saved->id, done); });
  ASSERT_TRUE(restored);
  EXPECT_EQ(restored->step, saved->state->step);
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { f.runner.step(1, 100, done); }));
  ASSERT_TRUE(wait_for([&] { return f.runner.latest()->step == saved->state->step + 100; }));
  EXPECT_EQ(f.runner.latest()->bodies[0].positions, first);  // bit for bit
  const auto unknown = await<SceneStatus>([&](auto done) { f.runner.restore_state(1, 999, done); });
  EXPECT_EQ(unknown.error().code, RunnerError::Code::kUnknownId);
  EXPECT_EQ(f.kinds().back(), Kind::kStateRestored);
}

TEST(SceneRunnerRequests, OnlyTheLatestSavesAreKept) {
  Fixture f;
  std::uint32_t first = 0;
  for (std::size_t i = 0; i <= SceneRunner::kMaxSavedStates; ++i) {
    const auto saved = await<SavedState>([&](auto done) { f.runner.save_state(1, done); });
    if (i == 0) first = saved->id;
  }
  const auto oldest =
      await<SceneStatus>([&](auto done) { f.runner.restore_state(1, first, done); });
  EXPECT_EQ(oldest.error().code, RunnerError::Code::kUnknownId);
  EXPECT_TRUE(await<SceneStatus>([&](auto done) { f.runner.restore_state(1, first + 1, done); }));
}

TEST(SceneRunnerRequests, BodiesComeAndGoWithEventsAndFreshIds) {
  Fixture f;
  const auto added = await<BodyInfo>([&](auto done) { add(f.runner, 1, another_cloth(), done); });
  ASSERT_TRUE(added);
  EXPECT_EQ(added->body_id, 1u);
  EXPECT_EQ(added->owner, 1u);
  EXPECT_EQ(added->kind, "cloth");
  EXPECT_EQ(added->particles, 121u);
  EXPECT_NE(f.runner.bodies()->find(1), nullptr);  // in the catalog before the completion ran
  ASSERT_TRUE(wait_for([&] { return f.runner.latest()->bodies.size() == 2; }));
  const auto removed = await<BodyId>([&](auto done) { f.runner.remove_body(1, 0, done); });
  ASSERT_TRUE(removed);
  EXPECT_EQ(f.runner.bodies()->find(0), nullptr);
  ASSERT_TRUE(wait_for([&] { return f.runner.latest()->bodies.size() == 1; }));
  EXPECT_EQ(f.runner.latest()->bodies[0].body_id, 1u);
  const auto again = await<BodyId>([&](auto done) { f.runner.remove_body(1, 0, done); });
  EXPECT_EQ(again.error().code, RunnerError::Code::kUnknownId);
  const auto events = f.log->events();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, Kind::kBodyAdded);
  EXPECT_EQ(events[0].bodies.at(0).body_id, 1u);
  EXPECT_EQ(events[1].kind, Kind::kBodyRemoved);
  EXPECT_EQ(events[1].body_ids, std::vector<BodyId>{0});
  EXPECT_EQ(events[1].client, 1u);
}

// A change checked against a body that a request queued before it removes: answered as such,
// not applied, not announced.
TEST(SceneRunnerRequests, AChangeToABodyRemovedFirstIsAnUnknownId) {
  Fixture f;
  Awaited<BodyId> removed, changed;
  bool ran = false;
  f.runner.remove_body(1, 0, removed.completion());
  f.runner.change_body(
      1, 0, [&](World&) { ran = true; }, changed.completion());
  ASSERT_TRUE(removed.get());
  const auto answer = changed.get();
  ASSERT_FALSE(answer);
  EXPECT_EQ(answer.error().code, RunnerError::Code::kUnknownId);
  EXPECT_FALSE(ran);
  EXPECT_EQ(f.kinds(), std::vector<Kind>{Kind::kBodyRemoved});
  // a live body's change is applied, then answered and announced
  const auto added = await<BodyInfo>([&](auto done) { add(f.runner, 1, another_cloth(), done); });
  ASSERT_TRUE(added);
  const auto applied = await<BodyId>([&](auto done) {
    f.runner.change_body(
        1, added->body_id, [&](World&) { ran = true; }, done);
  });
  ASSERT_TRUE(applied);
  EXPECT_EQ(*applied, added->body_id);
  EXPECT_TRUE(ran);
  EXPECT_EQ(f.kinds().back(), Kind::kBodyChanged);
}

TEST(SceneRunnerRequests, TheBodyAndParticleLimitsHold) {
  SceneRunner runner(flat_cloth_scene(), {}, {}, SceneLimits{2, 200});
  runner.start();
  // 121 + 121 particles exceed 200
  const auto heavy = await<BodyInfo>([&](auto done) { add(runner, 0, another_cloth(), done); });
  EXPECT_EQ(heavy.error().code, RunnerError::Code::kLimitExceeded);
  Collider ball;
  ball.shape = Collider::Shape::kSphere;
  ASSERT_TRUE(await<BodyInfo>([&](auto done) { add(runner, 0, ball, done); }));
  const auto third = await<BodyInfo>([&](auto done) { add(runner, 0, ball, done); });
  EXPECT_EQ(third.error().code, RunnerError::Code::kLimitExceeded);
  runner.stop();
}

TEST(SceneRunnerRequests, ResetBuildsTheSceneAgainFromItsSource) {
  Fixture f;
  ASSERT_TRUE(await<BodyInfo>([&](auto done) { add(f.runner, 1, another_cloth(), done); }));
  ASSERT_TRUE(wait_for([&] { return f.runner.latest()->sim_time > 0.1; }));
  const auto reset = await<SceneStatus>([&](auto done) { f.runner.reset(1, build_here, done); });
  ASSERT_TRUE(reset);
  EXPECT_LT(reset->sim_time, 0.01);
  EXPECT_EQ(f.runner.bodies()->bodies.size(), 1u);
  EXPECT_EQ(f.kinds().back(), Kind::kReset);
  EXPECT_EQ(f.log->events().back().bodies.size(), 1u);
  SceneRunner without_source(flat_cloth_scene());
  without_source.start();
  const auto refused =
      await<SceneStatus>([&](auto done) { without_source.reset(0, build_here, done); });
  EXPECT_EQ(refused.error().code, RunnerError::Code::kWrongState);
}

// The rebuild happens elsewhere while the scene steps on, and the reset keeps its place among
// the requests: a pause sent after it is carried out after it, on the fresh scene.
TEST(SceneRunnerRequests, AResetKeepsItsPlaceWhileItsSceneIsRebuilt) {
  Fixture f;
  ASSERT_TRUE(wait_for([&] { return f.runner.latest()->sim_time > 0.1; }));
  std::jthread builder;
  std::atomic<bool> building = false;
  Awaited<SceneStatus> reset, paused;
  f.runner.reset(
      1,
      [&](std::function<void()> job) {
        building = true;
        builder = std::jthread([&, job = std::move(job)] {
          std::this_thread::sleep_for(300ms);
          building = false;
          job();
        });
      },
      reset.completion());
  f.runner.pause(1, paused.completion());
  const std::uint64_t before = f.runner.latest()->step;
  ASSERT_TRUE(wait_for([&] { return f.runner.latest()->step > before + 5; }));
  EXPECT_TRUE(building) << "the scene stepped only after its rebuild";
  ASSERT_TRUE(reset.get());
  const auto status = paused.get();
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->paused);
  EXPECT_LT(status->sim_time, 0.01) << "the pause overtook the reset";
}

/// The total momentum of body 0 in the scene's saved state, with the cloth's masses.
Vec3 momentum(SceneRunner& runner, const std::vector<Real>& mass) {
  const auto saved = await<SavedState>([&](auto done) { runner.save_state(0, done); });
  Vec3 p = Vec3::Zero();
  const std::vector<Vec3>& v = saved->state->bodies.at(0).velocities;
  for (std::size_t i = 0; i < v.size(); ++i) p += mass[i] * v[i];
  return p;
}

// A body built elsewhere is added at its request's place: removing it right after asking for
// it works, though its build takes 200 ms.
TEST(SceneRunnerRequests, ABodyBuiltElsewhereIsAddedBeforeTheRequestsAfterIt) {
  Fixture f;
  std::jthread builder;
  Awaited<BodyInfo> added;
  Awaited<BodyId> removed;
  f.runner.add_body(
      1,
      [&](std::function<void()> job) {
        builder = std::jthread([job = std::move(job)] {
          std::this_thread::sleep_for(200ms);
          job();
        });
      },
      [] { return std::expected<BuiltBody, RunnerError>(another_cloth()); }, added.completion());
  f.runner.remove_body(1, 1, removed.completion());  // the id the added body will have
  const auto body = added.get();
  ASSERT_TRUE(body);
  EXPECT_EQ(body->body_id, 1u);
  const auto gone = removed.get();
  ASSERT_TRUE(gone) << gone.error().message;
  EXPECT_EQ(f.runner.bodies()->bodies.size(), 1u);
  // a build that fails answers with its error, in its place too
  Awaited<BodyInfo> refused;
  f.runner.add_body(
      1, build_here,
      [] {
        return std::expected<BuiltBody, RunnerError>(
            std::unexpected(RunnerError{RunnerError::Code::kBadScene, "no such mesh"}));
      },
      refused.completion());
  EXPECT_EQ(refused.get().error().code, RunnerError::Code::kBadScene);
}

// A reset whose scene is still being rebuilt when the scene stops is cancelled, and so is
// every request waiting behind it.
TEST(SceneRunnerRequests, AResetStillBeingBuiltIsCancelledWithTheSceneStop) {
  Fixture f;
  std::function<void()> never_run;
  Awaited<SceneStatus> reset, paused;
  f.runner.reset(
      1, [&](std::function<void()> job) { never_run = std::move(job); }, reset.completion());
  f.runner.pause(1, paused.completion());
  std::this_thread::sleep_for(20ms);
  f.runner.stop();
  EXPECT_EQ(reset.get().error().code, RunnerError::Code::kCancelled);
  EXPECT_EQ(paused.get().error().code, RunnerError::Code::kCancelled);
}

TEST(SceneRunnerRequests, AForceGivesTheImpulseOfItsDurationAndThenStops) {
  // a free, weightless cloth without drag: its springs conserve momentum, so the momentum it
  // gains is exactly the impulse of the pushes, force x steps x h
  Scene scene = flat_cloth_scene();
  ClothBody& cloth = scene.world.cloths()[0];
  for (std::uint32_t p = 0; p < cloth.model().particle_count(); ++p) cloth.unpin(p);
  ClothParams params = cloth.params();
  params.drag = 0;
  cloth.set_params(params);
  const std::vector<Real> mass = cloth.model().mass;
  SceneRunner runner(std::move(scene));
  runner.start();
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { runner.pause(0, done); }));
  const Vec3 force(0, 0.5, 0);
  const double h = 1e-3;
  // 0.1005 s covers the steps starting at 0, h, ..., 100 h: 101 of them
  ASSERT_TRUE(await<BodyId>([&](auto done) {
    runner.apply_force(0, 0, {60, 61}, force, 0.1005, done);
  }));
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { runner.step(0, 150, done); }));
  EXPECT_NEAR(momentum(runner, mass).y(), 2 * force.y() * 101 * h, 1e-9);
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { runner.step(0, 100, done); }));
  EXPECT_NEAR(momentum(runner, mass).y(), 2 * force.y() * 101 * h, 1e-9);  // it has stopped
  // a duration of 0: the next step only
  ASSERT_TRUE(await<BodyId>([&](auto done) { runner.apply_force(0, 0, {5}, force, 0, done); }));
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { runner.step(0, 20, done); }));
  EXPECT_NEAR(momentum(runner, mass).y(), (2 * 101 + 1) * force.y() * h, 1e-9);
  runner.stop();
}

TEST(SceneRunnerRequests, APausedSceneHoldsABoundedNumberOfForces) {
  SceneRunner runner(flat_cloth_scene());
  runner.start();
  ASSERT_TRUE(await<SceneStatus>([&](auto done) { runner.pause(0, done); }));
  // paused, nothing expires: the scene refuses more than it may hold
  for (std::size_t i = 0; i < SceneRunner::kMaxTimedForces; ++i) {
    ASSERT_TRUE(await<BodyId>(
        [&](auto done) { runner.apply_force(0, 0, {1}, Vec3(0, 1e-3, 0), 3600, done); }));
  }
  const auto refused = await<BodyId>(
      [&](auto done) { runner.apply_force(0, 0, {1}, Vec3(0, 1e-3, 0), 3600, done); });
  EXPECT_EQ(refused.error().code, RunnerError::Code::kLimitExceeded);
  // nor does a restored clock go past what pacing can count
  auto state = std::make_shared<WorldState>();
  state->step = 10'000'000'000'000'000ull;
  const auto huge = await<SceneStatus>([&](auto done) { runner.restore_state(0, state, done); });
  EXPECT_EQ(huge.error().code, RunnerError::Code::kBadRequest);
  runner.stop();
}

TEST(SceneRunnerRequests, RequestsLeftWhenTheSceneStopsAreCancelled) {
  auto runner = std::make_unique<SceneRunner>(flat_cloth_scene());
  // never started: the request waits in the queue until stop() cancels it
  Awaited<SceneStatus> pause;
  runner->pause(0, pause.completion());
  runner->stop();
  EXPECT_EQ(pause.get().error().code, RunnerError::Code::kCancelled);
  Awaited<SceneStatus> late;
  runner->pause(0, late.completion());
  EXPECT_EQ(late.get().error().code, RunnerError::Code::kCancelled);
}

TEST(SceneRunnerRequests, OwnersChangeTheirBodiesAndWhatIsLeftBehindIsAnyones) {
  Fixture f;  // loaded by client 1, not shared
  const BodyInfo own = *f.runner.bodies()->find(0);
  f.runner.members().join({1, "owner", std::make_shared<EventLog>()});
  EXPECT_TRUE(f.runner.may_change(1, own));
  EXPECT_FALSE(f.runner.may_change(2, own));
  EXPECT_FALSE(f.runner.may_control(2));
  f.runner.members().leave(1);
  EXPECT_TRUE(f.runner.may_change(2, own));
  EXPECT_TRUE(f.runner.may_control(2));
}

}  // namespace
}  // namespace felt
