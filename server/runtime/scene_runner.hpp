#pragma once
// One scene served live: a physics thread that is the only writer of the scene's World, paced
// against the wall clock, publishing immutable snapshots after its steps.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "runtime/command_queue.hpp"
#include "runtime/proxy_contact.hpp"
#include "runtime/reaction_accumulator.hpp"
#include "runtime/snapshot.hpp"
#include "scene/scene.hpp"

namespace felt {

/// What a client is told about a body when it loads or joins a scene.
struct BodyInfo {
  std::uint32_t body_id = 0;
  std::string name;
  std::string kind;
  std::uint32_t particles = 0;
  std::uint32_t triangles = 0;
};

struct RunnerStats {
  std::uint64_t steps = 0;
  double sim_time = 0;
  double real_time_factor = 0;  ///< simulated seconds per wall second, over the last half second
  double ms_per_step = 0;       ///< wall time of one step, averaged over the last half second
  std::uint64_t haptic_updates = 0;  ///< proxy solves since the scene started
  std::uint64_t rescued_steps = 0;
  std::uint64_t unrecoverable_steps = 0;
};

class SceneRunner {
 public:
  explicit SceneRunner(Scene scene);
  ~SceneRunner();
  SceneRunner(const SceneRunner&) = delete;
  SceneRunner& operator=(const SceneRunner&) = delete;

  /// Starts the physics thread. Simulated time then follows the wall clock.
  void start();
  /// Finishes the current step and joins the physics thread.
  void stop();

  const std::string& name() const { return name_; }
  const ProxySettings& haptics() const { return haptics_; }
  const std::vector<BodyInfo>& bodies() const { return bodies_; }

  /// Queues a change, applied before the next step.
  void post(SceneCommand command) { commands_.push(std::move(command)); }

  /// The latest published snapshot (never null).
  std::shared_ptr<const SceneSnapshot> latest() const { return latest_.load(); }

  /// Solves proxy `proxy_key` at `position` against the latest snapshot and records its reaction
  /// on the touched body. Safe from any thread.
  ProxyContact touch(std::uint64_t proxy_key, const Vec3& position);
  /// Forgets a closed proxy's pending reaction.
  void close_proxy(std::uint64_t proxy_key) { reactions_.forget(proxy_key); }

  RunnerStats stats() const;

 private:
  void run(std::stop_token stop);
  void publish();
  /// Records that `unrecoverable_steps` steps failed, the last of them in `bodies`.
  void record_event(std::uint64_t unrecoverable_steps, std::vector<std::uint32_t> bodies);

  Scene scene_;  ///< written by the physics thread only, once started
  std::string name_;
  ProxySettings haptics_;
  std::vector<BodyInfo> bodies_;
  CommandQueue commands_;
  ReactionAccumulator reactions_;
  std::atomic<std::shared_ptr<const SceneSnapshot>> latest_;
  /// the latest events, written by the physics thread, shared by the snapshots it publishes
  std::shared_ptr<const std::vector<SceneEvent>> events_;

  std::atomic<std::uint64_t> haptic_updates_{0};
  mutable std::mutex stats_mutex_;
  RunnerStats stats_;  ///< guarded by stats_mutex_, except haptic_updates

  std::mutex wake_mutex_;
  std::condition_variable_any wake_;
  std::jthread thread_;
};

}  // namespace felt
