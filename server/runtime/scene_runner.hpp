#pragma once
// One scene served live: a physics thread that is the only writer of the scene's World, paced
// against a clock (Pacer; or paused and stepped on request), applying queued requests between
// steps and publishing immutable snapshots after them.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <expected>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "core/world/world_state.hpp"
#include "runtime/body_catalog.hpp"
#include "runtime/body_stats.hpp"
#include "runtime/clock.hpp"
#include "runtime/command_queue.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/haptic_proxy.hpp"
#include "runtime/haptic_servo.hpp"
#include "runtime/health_events.hpp"
#include "runtime/pacer.hpp"
#include "runtime/proxy_presence.hpp"
#include "runtime/published.hpp"
#include "runtime/reaction_accumulator.hpp"
#include "runtime/runner_error.hpp"
#include "runtime/scene_members.hpp"
#include "runtime/snapshot.hpp"
#include "runtime/stats_window.hpp"
#include "runtime/timed_forces.hpp"
#include "scene/scene.hpp"
#include "scene/scene_error.hpp"
#include "scene/scene_loader.hpp"

namespace felt {

struct RunnerStats {
  std::uint64_t steps = 0;
  double sim_time = 0;
  double real_time_factor = 0;  ///< simulated seconds per wall second, over StatsWindow::kLength
  double ms_per_step = 0;       ///< wall time of one step, averaged over StatsWindow::kLength
  std::uint64_t haptic_updates = 0;  ///< proxy solves since the scene started
  std::uint64_t rescued_steps = 0;
  std::uint64_t unrecoverable_steps = 0;
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
};

/// Where the scene came from, to build it again for a reset (null: it cannot be reset).
using SceneReloader = std::function<std::expected<Scene, SceneError>()>;

/// The scene's clock after a request.
struct SceneStatus {
  std::uint64_t step = 0;
  double sim_time = 0;
  bool paused = false;
  double time_scale = 1;
};

struct SavedState {
  std::uint32_t id = 0;
  std::shared_ptr<const WorldState> state;
  double sim_time = 0;
};

/// Runs a job on another thread (a loader's), keeping whatever the job needs alive until it
/// has run.
using Offload = std::function<void(std::function<void()>)>;

/// What AddBody builds: a scene file's body or one of its colliders.
using BuiltBody = std::variant<SceneBody, Collider>;

/// What a scene refuses to grow past.
struct SceneLimits {
  std::size_t max_bodies = 256;
  std::uint64_t max_particles = 4'000'000;
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
  SceneMembers& members() { return members_; }

  /// The scene's bodies now (never null). A body a request added is in it before the request's
  /// completion runs.
  std::shared_ptr<const BodyCatalog> bodies() const { return catalog_.load(); }
  /// Whether `client` may change body `body`: its owner, or anyone in a shared scene or once
  /// the owner has left the scene.
  bool may_change(ClientId client, const BodyInfo& body) const;
  /// Whether `client` may pause, step, reset or destroy the scene: by the same rule, with the
  /// client that loaded the scene as its owner.
  bool may_control(ClientId client) const;

  /// Queues a change, applied before the next step; `cancel` runs instead if the scene stops
  /// first.
  void post(SceneCommand command, std::function<void()> cancel = {},
            std::function<bool()> ready = {});

  // Requests answered through a completion once the physics thread has carried them out.
  // `by` is the client asking; the other clients in the scene hear of it as an event.
  void pause(ClientId by, Completion<SceneStatus> done);
  void resume(ClientId by, Completion<SceneStatus> done);
  /// Takes `steps` steps of a paused scene as fast as it can.
  void step(ClientId by, std::uint32_t steps, Completion<SceneStatus> done);
  /// Simulated seconds per wall second while running, (0, 100].
  void set_time_scale(ClientId by, double scale, Completion<SceneStatus> done);
  /// Builds the scene again from its source, as a job given to `build_on` (a loader thread:
  /// building can take long, and the scene steps on meanwhile), and swaps it in at the
  /// request's place among the others: the requests after it wait for it. Bodies added since
  /// are gone, time is 0.
  void reset(ClientId by, const Offload& build_on, Completion<SceneStatus> done);
  /// Keeps the state (the latest kMaxSavedStates saves) and returns it.
  void save_state(ClientId by, Completion<SavedState> done);
  void restore_state(ClientId by, std::uint32_t state_id, Completion<SceneStatus> done);
  void restore_state(ClientId by, std::shared_ptr<const WorldState> state,
                     Completion<SceneStatus> done);
  /// Builds a body with `build`, as a job given to `build_on` (a mesh may take long to
  /// voxelize), and adds it at the request's place among the others, as reset does.
  void add_body(ClientId by, const Offload& build_on,
                std::function<std::expected<BuiltBody, RunnerError>()> build,
                Completion<BodyInfo> done);
  void remove_body(ClientId by, BodyId body, Completion<BodyId> done);
  /// Runs `change` on a live body's world between steps and tells the other clients; answers
  /// kUnknownId instead if the body is gone by then.
  void change_body(ClientId by, BodyId body, std::function<void(World&)> change,
                   Completion<BodyId> done);
  /// `force` on each of `vertices` for `duration` simulated seconds (0: the next step); at most
  /// kMaxTimedForces at once in a scene (a paused scene's never expire).
  void apply_force(ClientId by, BodyId body, std::vector<std::uint32_t> vertices, const Vec3& force,
                   Real duration, Completion<BodyId> done);

  /// The latest published snapshot (never null).
  std::shared_ptr<const SceneSnapshot> latest() const { return latest_.load(); }

  /// A new proxy known to the scene as `key`, with the scene's haptics settings or `settings`.
  HapticProxy open_proxy(std::uint64_t key) const { return HapticProxy(key, haptics_); }
  HapticProxy open_proxy(std::uint64_t key, const ProxySettings& settings) const {
    return HapticProxy(key, settings);
  }
  /// Updates `proxy` with its device at `device` against the surfaces as rendered now, and
  /// records its reaction on the touched body (the reaction of `local`, when a local renderer
  /// felt it: HapticProxy::update). A local-model proxy gets the surface near it (near
  /// `local`'s proxy, else the server's) in the output when its feed has one due. Safe from any
  /// thread; one proxy is updated by one thread at a time.
  ProxyOutput render(HapticProxy& proxy, const Vec3& device, std::uint32_t buttons,
                     const LocalContact* local = nullptr);
  /// Forgets a closed proxy's pending reaction.
  void close_proxy(const HapticProxy& proxy) {
    reactions_.forget(proxy.key());
    presence_.forget(proxy.key());
  }
  /// The proxies rendered in the last `within`, as everyone in the scene may see them.
  std::vector<ProxyPresenceEntry> presence(std::chrono::steady_clock::duration within) const {
    return presence_.since(std::chrono::steady_clock::now() - within);
  }
  /// The surfaces proxies render against (made now from the latest snapshot if no proxy was
  /// used lately, after which the physics thread keeps them up to date).
  std::shared_ptr<const HapticFrame> haptic_frame();
  /// A client came that may touch the scene: the physics thread makes haptic frames between
  /// its steps for a while, as it does while proxies are in use, so that the client's first
  /// touch finds one, or refits one (a fraction of a millisecond), instead of building the
  /// structures on the network thread that answers it (5 ms for 20,000 triangles, in which that
  /// thread's other clients wait).
  void prepare_haptics();

  RunnerStats stats() const;
  /// The scripted devices' latest updates (empty without devices).
  std::vector<HapticRecord> device_states() const;

  static constexpr std::size_t kMaxSavedStates = 8;
  static constexpr std::size_t kMaxTimedForces = 256;
  /// A restored clock must stay below this (s), so that pacing arithmetic cannot overflow.
  static constexpr double kMaxSimTime = 1e9;
  static constexpr std::uint32_t kMaxStepsPerRequest = 100'000;

 private:
  struct StepRequest {
    std::uint64_t target = 0;
    Completion<SceneStatus> done;
  };

  void run(std::stop_token stop);
  /// One step: queued forces and reactions, the world's step, the health bookkeeping.
  void step_once();
  void publish();
  void publish_catalog();
  /// The scene's own bodies (all that are in it now) belong to its owner.
  void own_scene_bodies();
  /// A snapshot and a catalog for bodies that came or went.
  void publish_bodies();
  /// Makes the haptic frame for the snapshot just published, if proxies are in use.
  void publish_haptics(SteadyClock::time_point now);
  /// The latest snapshot's frame after `previous` (null: a still one), refitting a pooled frame
  /// nobody reads any more when there is one; with haptic_mutex_ held.
  std::shared_ptr<HapticFrame> make_pooled_haptic_frame(const HapticFrame* previous,
                                                        SteadyClock::time_point now);
  /// Reports rescued and unrecoverable steps not yet reported (HealthEvents::report).
  void report_health(bool at_once);
  SceneStatus status() const;
  /// Queues `run`; its completion gets kCancelled if the scene stops first.
  template <class T>
  void request(Completion<T> done, std::function<void(Scene&, Completion<T>&)> run,
               std::function<bool()> ready = {});
  /// A request whose `make` runs as a job given to `build_on` first; `apply` then gets what it
  /// made at the request's place among the others (those after it wait), or its error answers.
  template <class Made, class T>
  void request_made_elsewhere(Completion<T> done, const Offload& build_on,
                              std::function<std::expected<Made, RunnerError>()> make,
                              std::function<void(Scene&, Made&, Completion<T>&)> apply);
  /// Wakes the physics thread to look at its commands.
  void wake();
  std::expected<Scene, RunnerError> rebuild() const;
  SceneEvent event(SceneEvent::Kind kind, ClientId by) const;
  /// Whether the scene may have one more body (answers kLimitExceeded otherwise).
  bool room_for_body(Completion<BodyInfo>& done);
  /// Publishes body `id`, added by `by`, tells the others and answers with it.
  void added(ClientId by, BodyId id, Completion<BodyInfo>& done);
  void restore(ClientId by, const WorldState& state, Completion<SceneStatus>& done);

  Clock& clock_;
  Scene scene_;  ///< written by the physics thread only, once started
  std::string name_;
  SceneAccess access_;
  SceneReloader reload_;
  SceneLimits limits_;
  ProxySettings haptics_;
  Real time_step_;
  CommandQueue commands_;
  ReactionAccumulator reactions_;
  SceneMembers members_;
  Published<SceneSnapshot> latest_;
  std::uint64_t published_ = 0;  ///< snapshots published: the next one's version
  Published<BodyCatalog> catalog_;
  /// owner of each body, by id; the physics thread's, published through catalog_
  std::vector<std::pair<BodyId, ClientId>> owners_;

  // the physics thread's own
  TimedForces timed_forces_;
  std::deque<SavedState> saved_;
  std::uint32_t next_state_id_ = 1;
  std::vector<StepRequest> step_requests_;
  Pacer pacer_;
  HealthEvents health_{members_};

  TriangleQueryKind haptic_structure_;
  Published<HapticFrame> haptic_;
  /// the frames made lately; one nobody else holds any more is refitted, not copied
  std::vector<std::shared_ptr<HapticFrame>> haptic_pool_;
  std::mutex haptic_mutex_;  ///< held while a haptic frame is made
  /// steady-clock ticks of the latest render (or prepare_haptics)
  ProxyPresence presence_;
  std::atomic<SteadyClock::rep> last_render_{0};

  std::unique_ptr<HapticServo> servo_;  ///< null without scripted devices

  std::atomic<std::uint64_t> haptic_updates_{0};
  mutable std::mutex stats_mutex_;
  RunnerStats stats_;  ///< guarded by stats_mutex_, except haptic_updates

  std::mutex wake_mutex_;
  std::condition_variable_any wake_;
  std::mutex stop_mutex_;  ///< one stop() at a time: a second waits for the first to finish
  std::jthread thread_;
};

}  // namespace felt
