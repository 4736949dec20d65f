#pragma once
// What the runtime tests share: a small flat cloth scene, waiting for a condition, moving a
// scene's manual clock, and a scene member that records the events it hears.

#include <algorithm>
#include <chrono>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/cloth/cloth_grid.hpp"
#include "manual_clock.hpp"
#include "runtime/scene_runner.hpp"
#include "support/time_scale.hpp"
#include "ticking_clock.hpp"

namespace felt {

using namespace std::chrono_literals;

/// A horizontal 1 m cloth at y = 0 held at its four corners, without gravity, so that it stays
/// flat until something touches it.
inline Scene flat_cloth_scene(Vec3 gravity = Vec3::Zero(), Real time_step = 1e-3,
                              HealthSettings health = {}) {
  GridClothSpec spec;
  spec.nx = 11;
  spec.ny = 11;
  spec.total_mass = 0.2;
  spec.plane = GridClothSpec::Plane::kXZ;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 200, 0.05};
  params.spring(SpringKind::kShear) = {true, 50, 0.02};
  params.spring(SpringKind::kBend) = {true, 5, 0.005};
  params.drag = 0.02;
  ClothBody cloth("sheet", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                  make_integrator("symplectic_euler"));
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kFourCorners)) cloth.pin(p);
  WorldSettings settings{gravity, time_step, 100, 6};
  settings.health = health;
  Scene scene("flat", World(settings));
  scene.haptics.radius = 0.05;
  scene.haptics.stiffness = 400;
  scene.haptics.max_force = 10;
  scene.world.add_body(std::move(cloth));
  return scene;
}

template <typename Predicate>
bool wait_for(Predicate done, std::chrono::milliseconds timeout = 5s) {
  const auto deadline = std::chrono::steady_clock::now() + test::scaled(timeout);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(2ms);
  }
  return true;
}

/// Waits until the physics thread on `clock` has done what is due and sleeps.
inline bool settled(const ManualClock& clock) {
  return wait_for([&] { return clock.sleeping(); });
}

/// Moves `clock` on by `by` in slices of `slice` (shorter than a scene may fall behind before
/// it re-synchronises), letting the physics thread on it catch up after each.
inline bool move_clock(ManualClock& clock, Clock::duration by,
                       Clock::duration slice = std::chrono::milliseconds(10)) {
  while (by > Clock::duration::zero()) {
    const Clock::duration move = std::min(by, slice);
    clock.advance(move);
    by -= move;
    if (!settled(clock)) return false;
  }
  return true;
}

/// A member of a scene that keeps every event it is sent.
class EventLog : public SceneListener {
 public:
  void on_scene_event(const SceneEvent& event) override {
    std::lock_guard lock(mutex_);
    events_.push_back(event);
  }
  std::vector<SceneEvent> events() const {
    std::lock_guard lock(mutex_);
    return events_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<SceneEvent> events_;
};

/// A request's outcome, awaited: hand completion() to the runner, then get() it.
template <class T>
class Awaited {
 public:
  Completion<T> completion() {
    return [promise = promise_](std::expected<T, RunnerError> result) {
      promise->set_value(std::move(result));
    };
  }
  /// The outcome; a timeout fails the test and returns a kCancelled error.
  std::expected<T, RunnerError> get(std::chrono::milliseconds timeout = 5s) {
    auto future = promise_->get_future();
    if (future.wait_for(test::scaled(timeout)) != std::future_status::ready) {
      ADD_FAILURE() << "no completion within the timeout";
      return std::unexpected(RunnerError{RunnerError::Code::kCancelled, "timeout"});
    }
    return future.get();
  }

 private:
  std::shared_ptr<std::promise<std::expected<T, RunnerError>>> promise_ =
      std::make_shared<std::promise<std::expected<T, RunnerError>>>();
};

/// Runs a request and waits for its outcome.
template <class T, class Request>
std::expected<T, RunnerError> await(Request request) {
  Awaited<T> awaited;
  request(awaited.completion());
  return awaited.get();
}

}  // namespace felt
