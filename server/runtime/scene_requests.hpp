#pragma once
// The requests a scene carries out between its steps: pause, resume, step, time scale, reset,
// save and restore states, add, remove and change bodies, timed forces. Each is queued for the
// physics thread, answered through its completion once carried out (or cancelled if the scene
// stops first), and told to the scene's other members as an event.

#include <cstdint>
#include <deque>
#include <expected>
#include <functional>
#include <memory>
#include <variant>
#include <vector>

#include "core/world/world_state.hpp"
#include "runtime/command_queue.hpp"
#include "runtime/live_scene.hpp"
#include "runtime/runner_error.hpp"
#include "runtime/scene_members.hpp"
#include "scene/scene.hpp"
#include "scene/scene_error.hpp"
#include "scene/scene_loader.hpp"

namespace felt {

/// Where the scene came from, to build it again for a reset (null: it cannot be reset).
using SceneReloader = std::function<std::expected<Scene, SceneError>()>;

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

class SceneRequests {
 public:
  static constexpr std::size_t kMaxSavedStates = 8;
  static constexpr std::size_t kMaxTimedForces = 256;
  /// A restored clock must stay below this (s), so that pacing arithmetic cannot overflow.
  static constexpr double kMaxSimTime = 1e9;
  static constexpr std::uint32_t kMaxStepsPerRequest = 100'000;

  /// Requests carried out on `live` by the physics thread that applies `commands`, told to
  /// `members`.
  SceneRequests(LiveScene& live, CommandQueue& commands, SceneMembers& members,
                SceneReloader reload, SceneLimits limits);

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

 private:
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
  std::expected<Scene, RunnerError> rebuild() const;
  /// Whether the scene may have one more body (answers kLimitExceeded otherwise).
  bool room_for_body(Completion<BodyInfo>& done);
  /// Publishes body `id`, added by `by`, tells the others and answers with it.
  void added(ClientId by, BodyId id, Completion<BodyInfo>& done);
  void restore(ClientId by, const WorldState& state, Completion<SceneStatus>& done);

  LiveScene& live_;
  CommandQueue& commands_;
  SceneMembers& members_;
  SceneReloader reload_;
  SceneLimits limits_;
  // the physics thread's own
  std::deque<SavedState> saved_;
  std::uint32_t next_state_id_ = 1;
};

}  // namespace felt
