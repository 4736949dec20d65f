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
#include "runtime/haptic_frame.hpp"
#include "runtime/haptic_proxy.hpp"
#include "runtime/haptic_servo.hpp"
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
  ServoStats servo;  ///< of the scene's scripted devices, if it has any
};

class SceneRunner {
 public:
  explicit SceneRunner(Scene scene);
  ~SceneRunner();
  SceneRunner(const SceneRunner&) = delete;
  SceneRunner& operator=(const SceneRunner&) = delete;

  /// Starts the physics thread, and the servo thread if the scene has scripted devices.
  /// Simulated time then follows the wall clock.
  void start();
  /// Finishes the current step and joins the physics and servo threads.
  void stop();

  const std::string& name() const { return name_; }
  const ProxySettings& haptics() const { return haptics_; }
  const std::vector<BodyInfo>& bodies() const { return bodies_; }

  /// Queues a change, applied before the next step.
  void post(SceneCommand command) { commands_.push(std::move(command)); }

  /// The latest published snapshot (never null).
  std::shared_ptr<const SceneSnapshot> latest() const { return latest_.load(); }

  /// A new proxy with the scene's haptics settings, known to the scene as `key`.
  HapticProxy open_proxy(std::uint64_t key) const { return HapticProxy(key, haptics_); }
  /// Updates `proxy` with its device at `device` against the surfaces as rendered now, and
  /// records its reaction on the touched body. Safe from any thread; one proxy is updated by
  /// one thread at a time.
  ProxyOutput render(HapticProxy& proxy, const Vec3& device, std::uint32_t buttons);
  /// Forgets a closed proxy's pending reaction.
  void close_proxy(const HapticProxy& proxy) { reactions_.forget(proxy.key()); }
  /// The surfaces proxies render against (made now from the latest snapshot if no proxy was
  /// used lately, after which the physics thread keeps them up to date).
  std::shared_ptr<const HapticFrame> haptic_frame();

  RunnerStats stats() const;
  /// The scripted devices' latest updates (empty without devices).
  std::vector<HapticRecord> device_states() const;

 private:
  void run(std::stop_token stop);
  void publish();
  /// Makes the haptic frame for the snapshot just published, if proxies are in use.
  void publish_haptics(SteadyClock::time_point now);
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

  TriangleQueryKind haptic_structure_;
  std::atomic<std::shared_ptr<const HapticFrame>> haptic_;
  /// frames the physics thread made; one nobody else holds any more is refitted, not copied
  std::vector<std::shared_ptr<HapticFrame>> haptic_pool_;
  std::mutex haptic_mutex_;                       ///< held while a haptic frame is made
  std::atomic<SteadyClock::rep> last_render_{0};  ///< steady-clock ticks of the latest render

  std::unique_ptr<HapticServo> servo_;  ///< null without scripted devices

  std::atomic<std::uint64_t> haptic_updates_{0};
  mutable std::mutex stats_mutex_;
  RunnerStats stats_;  ///< guarded by stats_mutex_, except haptic_updates

  std::mutex wake_mutex_;
  std::condition_variable_any wake_;
  std::jthread thread_;
};

}  // namespace felt
