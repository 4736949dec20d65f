#pragma once
// One scene served live: a physics thread that is the only writer of the scene's World, paced
// against a clock (Pacer; or paused and stepped on request), carrying out queued requests
// (SceneRequests) between steps and publishing immutable snapshots (LiveScene) and haptic frames
// (LiveHapticFrames) after them.

#include <atomic>
#include <cstdint>
#include <expected>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "runtime/body_catalog.hpp"
#include "runtime/body_stats.hpp"
#include "runtime/clock.hpp"
#include "runtime/command_queue.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/haptic_proxy.hpp"
#include "runtime/haptic_servo.hpp"
#include "runtime/health_events.hpp"
#include "runtime/live_haptic_frames.hpp"
#include "runtime/live_scene.hpp"
#include "runtime/proxy_handle.hpp"
#include "runtime/proxy_presence.hpp"
#include "runtime/published.hpp"
#include "runtime/reaction_accumulator.hpp"
#include "runtime/runner_error.hpp"
#include "runtime/scene_members.hpp"
#include "runtime/scene_requests.hpp"
#include "runtime/snapshot.hpp"
#include "runtime/stats_window.hpp"
#include "scene/scene.hpp"

namespace felt {

struct RunnerStats {
  std::uint64_t steps = 0;
  double sim_time = 0;
  double real_time_factor = 0;  ///< simulated seconds per wall second, over StatsWindow::kLength
  double ms_per_step = 0;       ///< wall time of one step, averaged over StatsWindow::kLength
  /// where a step spent its time, stage by stage, averaged over the same window
  StepProfile cloth_profile, solid_profile;
  std::uint64_t haptic_updates = 0;  ///< proxy solves since the scene started
  std::uint64_t rescued_steps = 0;
  std::uint64_t unrecoverable_steps = 0;
  std::uint64_t over_budget_steps = 0;  ///< steps that reached their budget (HealthEvents)
  bool paused = false;
  double time_scale = 1;
  ServoStats servo;               ///< of the scene's scripted devices, if it has any
  std::vector<BodyStats> bodies;  ///< the cloths and solids, as of the last window
};

/// Who may do what in a scene, fixed when it is created.
struct SceneAccess {
  ClientId owner = 0;       ///< the client that loaded or created it; 0: the server
  bool shared = false;      ///< anyone in it may change any body and control the scene
  bool persistent = false;  ///< stays when its last client leaves (the server's own, or kept)
  /// clients may control it at all (not one of the server's own with --server-scenes-control
  /// none)
  bool controllable = true;
};

class SceneRunner {
 public:
  /// A scene whose physics thread paces itself, publishes and measures by `clock`.
  explicit SceneRunner(Scene scene, SceneAccess access = {}, SceneReloader reload = {},
                       SceneLimits limits = {}, Clock& clock = wall_clock());
  ~SceneRunner();
  SceneRunner(const SceneRunner&) = delete;
  SceneRunner& operator=(const SceneRunner&) = delete;

  /// Starts the physics thread, at `physics_nice` (0 to kMaxNice: set_this_thread_nice), and
  /// the servo thread if the scene has scripted devices. Simulated time then follows the
  /// clock.
  void start(int physics_nice = 0);
  /// Finishes the current step and joins the physics and servo threads. Requests still queued
  /// are cancelled. Safe from any thread, and more than once.
  void stop();

  const std::string& name() const { return name_; }
  const SceneAccess& access() const { return access_; }
  const ProxySettings& haptics() const { return haptics_; }
  Real time_step() const { return time_step_; }
  /// The scene's health settings, which nothing changes while it runs: what a body added to it
  /// is checked against.
  const HealthSettings& health_settings() const { return health_settings_; }
  SceneMembers& members() { return members_; }

  /// The scene's bodies now (never null). A body a request added is in it before the request's
  /// completion runs.
  std::shared_ptr<const BodyCatalog> bodies() const { return live_.bodies(); }
  /// Whether `client` may change body `body`: its owner, or anyone in a shared scene or once
  /// the owner has left the scene.
  bool may_change(ClientId client, const BodyInfo& body) const;
  /// Whether `client` may pause, step, reset or destroy the scene: by the same rule, with the
  /// client that loaded the scene as its owner, and never when the scene is not controllable.
  bool may_control(ClientId client) const;

  /// Queues a change, applied before the next step; `cancel` runs instead if the scene stops
  /// first.
  void post(SceneCommand command, std::function<void()> cancel = {},
            std::function<bool()> ready = {});

  // Requests answered through a completion once the physics thread has carried them out
  // (SceneRequests says what each does).
  void pause(ClientId by, Completion<SceneStatus> done) { requests_.pause(by, std::move(done)); }
  void resume(ClientId by, Completion<SceneStatus> done) { requests_.resume(by, std::move(done)); }
  void step(ClientId by, std::uint32_t steps, Completion<SceneStatus> done) {
    requests_.step(by, steps, std::move(done));
  }
  void set_time_scale(ClientId by, double scale, Completion<SceneStatus> done) {
    requests_.set_time_scale(by, scale, std::move(done));
  }
  void reset(ClientId by, const Offload& build_on, Completion<SceneStatus> done) {
    requests_.reset(by, build_on, std::move(done));
  }
  void save_state(ClientId by, Completion<SavedState> done) {
    requests_.save_state(by, std::move(done));
  }
  void restore_state(ClientId by, std::uint32_t state_id, Completion<SceneStatus> done) {
    requests_.restore_state(by, state_id, std::move(done));
  }
  void restore_state(ClientId by, std::shared_ptr<const WorldState> state,
                     Completion<SceneStatus> done) {
    requests_.restore_state(by, std::move(state), std::move(done));
  }
  void add_body(ClientId by, const Offload& build_on,
                std::function<std::expected<BuiltBody, RunnerError>()> build,
                Completion<BodyInfo> done) {
    requests_.add_body(by, build_on, std::move(build), std::move(done));
  }
  void remove_body(ClientId by, BodyId body, Completion<BodyId> done) {
    requests_.remove_body(by, body, std::move(done));
  }
  void change_body(ClientId by, BodyId body, std::function<void(World&)> change,
                   Completion<BodyId> done) {
    requests_.change_body(by, body, std::move(change), std::move(done));
  }
  void apply_force(ClientId by, BodyId body, std::vector<std::uint32_t> vertices, const Vec3& force,
                   Real duration, Completion<BodyId> done) {
    requests_.apply_force(by, body, std::move(vertices), force, duration, std::move(done));
  }

  /// The latest published snapshot (never null).
  std::shared_ptr<const SceneSnapshot> latest() const { return live_.latest(); }
  /// The latest snapshot lacks steps nobody watched (LiveScene::publish_steps).
  bool stale() const { return live_.stale(); }

  /// A new proxy known to the scene as `key`, with the scene's haptics settings or `settings`:
  /// the handle updates it (render) and closes it when it goes (close_proxy).
  ProxyHandle open_proxy(ProxyKey key) { return {*this, HapticProxy(key, haptics_)}; }
  ProxyHandle open_proxy(ProxyKey key, const ProxySettings& settings) {
    return {*this, HapticProxy(key, settings)};
  }
  /// The proxies rendered in the last `within`, as everyone in the scene may see them.
  std::vector<ProxyPresenceEntry> presence(std::chrono::steady_clock::duration within) const {
    return presence_.since(std::chrono::steady_clock::now() - within);
  }
  /// The surfaces proxies render against (made now from the latest snapshot if no proxy was
  /// used lately, after which the physics thread keeps them up to date).
  std::shared_ptr<const HapticFrame> haptic_frame() { return haptic_frames_.current(); }
  /// A client came that may touch the scene: the physics thread makes haptic frames between
  /// its steps for a while, as it does while proxies are in use, so that the client's first
  /// touch finds one, or refits one (a fraction of a millisecond), instead of building the
  /// structures on the network thread that answers it (5 ms for 20,000 triangles, in which that
  /// thread's other clients wait).
  void prepare_haptics();
  /// A client subscribed to the scene's frames: the steps nobody watched are published now,
  /// between two steps, so that its first frame shows the scene as it is.
  void prepare_frames();

  RunnerStats stats() const;
  /// The scripted devices' latest updates (empty without devices).
  std::vector<HapticRecord> device_states() const;

  static constexpr std::size_t kMaxSavedStates = SceneRequests::kMaxSavedStates;
  static constexpr std::size_t kMaxTimedForces = SceneRequests::kMaxTimedForces;
  static constexpr std::uint32_t kMaxStepsPerRequest = SceneRequests::kMaxStepsPerRequest;

 private:
  friend class ProxyHandle;

  /// Updates `proxy` with its device at `device` against the surfaces as rendered now, and
  /// records its reaction on the touched body (the reaction of `local`, when a local renderer
  /// felt it: HapticProxy::update). A local-model proxy gets the surface near it (near
  /// `local`'s proxy, else the server's) in the output when its feed has one due. Safe from any
  /// thread; one proxy is updated by one thread at a time.
  ProxyOutput render(HapticProxy& proxy, const Vec3& device, std::uint32_t buttons,
                     const LocalContact* local = nullptr);
  /// Forgets a closed proxy's pending reaction and presence.
  void close_proxy(const HapticProxy& proxy) {
    reactions_.forget(proxy.key());
    presence_.forget(proxy.key());
  }

  void run(std::stop_token stop);
  /// One step: queued forces and reactions, the world's step, the health bookkeeping.
  StepReport step_once();
  /// Reports rescued and unrecoverable steps not yet reported (HealthEvents::report).
  void report_health(bool at_once);

  Clock& clock_;
  std::string name_;
  SceneAccess access_;
  ProxySettings haptics_;
  Real time_step_;
  HealthSettings health_settings_;
  SceneMembers members_;
  CommandQueue commands_;
  ReactionAccumulator reactions_;
  LiveScene live_;  ///< the physics thread's, once started
  SceneRequests requests_;
  HealthEvents health_{members_};
  LiveHapticFrames haptic_frames_;
  std::atomic<bool> catching_up_{false};  ///< a prepare_frames command is queued

  ProxyPresence presence_;

  std::unique_ptr<HapticServo> servo_;  ///< null without scripted devices

  std::atomic<std::uint64_t> haptic_updates_{0};
  mutable std::mutex stats_mutex_;
  RunnerStats stats_;  ///< guarded by stats_mutex_, except haptic_updates

  std::mutex stop_mutex_;  ///< one stop() at a time: a second waits for the first to finish
  std::jthread thread_;
};

}  // namespace felt
