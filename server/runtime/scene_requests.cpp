#include "runtime/scene_requests.hpp"

#include <algorithm>
#include <mutex>
#include <optional>
#include <string>

namespace felt {
namespace {

// What a job makes on another thread for a command that waits for it.
template <class T>
class MadeElsewhere {
 public:
  bool ready() const {
    std::lock_guard lock(mutex_);
    return made_.has_value();
  }
  void set(std::expected<T, RunnerError> made) {
    std::lock_guard lock(mutex_);
    made_ = std::move(made);
  }
  std::expected<T, RunnerError> take() {
    std::lock_guard lock(mutex_);
    return std::move(*made_);
  }

 private:
  mutable std::mutex mutex_;
  std::optional<std::expected<T, RunnerError>> made_;
};

RunnerError error(RunnerError::Code code, std::string message) {
  return RunnerError{code, std::move(message)};
}

}  // namespace

SceneRequests::SceneRequests(LiveScene& live, CommandQueue& commands, SceneMembers& members,
                             SceneReloader reload, SceneLimits limits)
    : live_(live),
      commands_(commands),
      members_(members),
      reload_(std::move(reload)),
      limits_(limits) {}

template <class T>
void SceneRequests::request(Completion<T> done, std::function<void(Scene&, Completion<T>&)> run,
                            std::function<bool()> ready) {
  auto shared = std::make_shared<Completion<T>>(std::move(done));
  commands_.push(
      [shared, run = std::move(run)](Scene& scene) { run(scene, *shared); },
      [shared] {
        (*shared)(std::unexpected(error(RunnerError::Code::kCancelled, "the scene was stopped")));
      },
      std::move(ready));
}

template <class Made, class T>
void SceneRequests::request_made_elsewhere(
    Completion<T> done, const Offload& build_on,
    std::function<std::expected<Made, RunnerError>()> make,
    std::function<void(Scene&, Made&, Completion<T>&)> apply) {
  auto made = std::make_shared<MadeElsewhere<Made>>();
  request<T>(
      std::move(done),
      [made, apply = std::move(apply)](Scene& scene, Completion<T>& done) {
        auto value = made->take();
        if (!value) return done(std::unexpected(value.error()));
        apply(scene, *value, done);
      },
      [made] { return made->ready(); });
  build_on([&commands = commands_, made, make = std::move(make)] {
    made->set(make());
    commands.wake();
  });
}

void SceneRequests::pause(ClientId by, Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done), [this, by](Scene&, Completion<SceneStatus>& done) {
    if (!live_.pacer.paused()) {
      live_.pacer.pause();
      members_.broadcast(live_.event(SceneEvent::Kind::kPaused, by));
    }
    done(live_.status());
  });
}

void SceneRequests::resume(ClientId by, Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done), [this, by](Scene&, Completion<SceneStatus>& done) {
    if (live_.pacer.paused()) {
      live_.pacer.resume();
      members_.broadcast(live_.event(SceneEvent::Kind::kResumed, by));
    }
    done(live_.status());
  });
}

void SceneRequests::step(ClientId, std::uint32_t steps, Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done), [this, steps](Scene& scene, Completion<SceneStatus>& done) {
    if (!live_.pacer.paused()) {
      done(std::unexpected(
          error(RunnerError::Code::kWrongState, "the scene is running; pause it first")));
      return;
    }
    if (steps == 0 || steps > kMaxStepsPerRequest) {
      done(std::unexpected(error(RunnerError::Code::kBadRequest,
                                 "steps must be 1 to " + std::to_string(kMaxStepsPerRequest))));
      return;
    }
    // requests queue up: each starts where the one before it ends
    live_.step_requests.add(scene.world.step_count(), steps, std::move(done));
  });
}

void SceneRequests::set_time_scale(ClientId by, double scale, Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done), [this, by, scale](Scene&, Completion<SceneStatus>& done) {
    if (!(scale > 0 && scale <= 100)) {
      done(std::unexpected(error(RunnerError::Code::kBadRequest, "scale must be in (0, 100]")));
      return;
    }
    live_.pacer.set_scale(scale);
    members_.broadcast(live_.event(SceneEvent::Kind::kTimeScale, by));
    done(live_.status());
  });
}

std::expected<Scene, RunnerError> SceneRequests::rebuild() const {
  if (!reload_) {
    return std::unexpected(error(RunnerError::Code::kWrongState,
                                 "this scene was built by requests and has no source to reset to"));
  }
  auto fresh = reload_();
  if (!fresh) return std::unexpected(error(RunnerError::Code::kBadScene, fresh.error().what()));
  return std::move(*fresh);
}

void SceneRequests::reset(ClientId by, const Offload& build_on, Completion<SceneStatus> done) {
  request_made_elsewhere<Scene, SceneStatus>(
      std::move(done), build_on, [this] { return rebuild(); },
      [this, by](Scene& scene, Scene& fresh, Completion<SceneStatus>& done) {
        live_.step_requests.cancel_all("the scene was reset");
        fresh.world.continue_ids_from(scene.world);
        scene.world = std::move(fresh.world);
        live_.own_scene_bodies();
        live_.timed_forces.clear();
        live_.pacer.restart();
        live_.publish_bodies();
        SceneEvent e = live_.event(SceneEvent::Kind::kReset, by);
        e.bodies = live_.bodies()->bodies;
        members_.broadcast(std::move(e));
        done(live_.status());
      });
}

void SceneRequests::save_state(ClientId, Completion<SavedState> done) {
  request<SavedState>(std::move(done), [this](Scene& scene, Completion<SavedState>& done) {
    SavedState saved{next_state_id_++,
                     std::make_shared<const WorldState>(capture_state(scene.world)),
                     scene.world.time()};
    saved_.push_back(saved);
    if (saved_.size() > kMaxSavedStates) saved_.pop_front();
    done(std::move(saved));
  });
}

void SceneRequests::restore(ClientId by, const WorldState& state, Completion<SceneStatus>& done) {
  World& world = live_.scene.world;
  if (!(static_cast<double>(state.step) * world.settings().time_step < kMaxSimTime)) {
    done(std::unexpected(error(RunnerError::Code::kBadRequest,
                               "step is too large: the clock must stay below 1e9 s")));
    return;
  }
  if (auto restored = felt::restore_state(world, state); !restored) {
    done(std::unexpected(error(RunnerError::Code::kBadRequest, restored.error())));
    return;
  }
  live_.pacer.restart();
  live_.publish();
  members_.broadcast(live_.event(SceneEvent::Kind::kStateRestored, by));
  done(live_.status());
}

void SceneRequests::restore_state(ClientId by, std::uint32_t state_id,
                                  Completion<SceneStatus> done) {
  request<SceneStatus>(
      std::move(done), [this, by, state_id](Scene&, Completion<SceneStatus>& done) {
        const auto it = std::find_if(saved_.begin(), saved_.end(),
                                     [state_id](const SavedState& s) { return s.id == state_id; });
        if (it == saved_.end()) {
          done(std::unexpected(
              error(RunnerError::Code::kUnknownId, "no saved state " + std::to_string(state_id) +
                                                       " (a scene keeps its latest " +
                                                       std::to_string(kMaxSavedStates) + ")")));
          return;
        }
        const auto state = it->state;
        restore(by, *state, done);
      });
}

void SceneRequests::restore_state(ClientId by, std::shared_ptr<const WorldState> state,
                                  Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done),
                       [this, by, state = std::move(state)](Scene&, Completion<SceneStatus>& done) {
                         restore(by, *state, done);
                       });
}

bool SceneRequests::room_for_body(Completion<BodyInfo>& done) {
  if (live_.bodies()->bodies.size() < limits_.max_bodies) return true;
  done(std::unexpected(
      RunnerError{RunnerError::Code::kLimitExceeded,
                  "the scene already has " + std::to_string(limits_.max_bodies) + " bodies",
                  SceneLimit::kBodies}));
  return false;
}

void SceneRequests::added(ClientId by, BodyId id, Completion<BodyInfo>& done) {
  live_.add_owner(id, by);
  live_.publish_bodies();
  const BodyInfo info = *live_.bodies()->find(id);
  SceneEvent e = live_.event(SceneEvent::Kind::kBodyAdded, by);
  e.body_ids = {id};
  e.bodies = {info};
  members_.broadcast(std::move(e));
  done(info);
}

void SceneRequests::add_body(ClientId by, const Offload& build_on,
                             std::function<std::expected<BuiltBody, RunnerError>()> build,
                             Completion<BodyInfo> done) {
  request_made_elsewhere<BuiltBody, BodyInfo>(
      std::move(done), build_on, std::move(build),
      [this, by](Scene& scene, BuiltBody& built, Completion<BodyInfo>& done) {
        if (!room_for_body(done)) return;
        if (const Collider* collider = std::get_if<Collider>(&built)) {
          return added(by, scene.world.add_collider(*collider), done);
        }
        SceneBody& body = std::get<SceneBody>(built);
        const std::uint64_t used = live_.bodies()->particles();
        const std::uint64_t particles =
            std::visit([](const auto& b) { return b.surface_vertex_count(); }, body);
        if (used + particles > limits_.max_particles) {
          done(std::unexpected(RunnerError{RunnerError::Code::kLimitExceeded,
                                           std::to_string(particles) + " particles exceed the " +
                                               std::to_string(limits_.max_particles - used) +
                                               " the scene's particle limit leaves",
                                           SceneLimit::kParticles}));
          return;
        }
        added(by,
              std::visit([&](auto&& b) { return scene.world.add_body(std::move(b)); },
                         std::move(body)),
              done);
      });
}

void SceneRequests::remove_body(ClientId by, BodyId body, Completion<BodyId> done) {
  request<BodyId>(std::move(done), [this, by, body](Scene& scene, Completion<BodyId>& done) {
    if (!scene.world.contains(body)) {
      done(std::unexpected(
          error(RunnerError::Code::kUnknownId, "no body " + std::to_string(body.value()))));
      return;
    }
    scene.world.remove_body(body);
    live_.forget_owner(body);
    live_.publish_bodies();
    SceneEvent e = live_.event(SceneEvent::Kind::kBodyRemoved, by);
    e.body_ids = {body};
    members_.broadcast(std::move(e));
    done(body);
  });
}

void SceneRequests::change_body(ClientId by, BodyId body, std::function<void(World&)> change,
                                Completion<BodyId> done) {
  request<BodyId>(std::move(done), [this, by, body, change = std::move(change)](
                                       Scene& scene, Completion<BodyId>& done) {
    // removed by a request queued before this one, after this one was checked
    if (!scene.world.contains(body)) {
      done(std::unexpected(error(RunnerError::Code::kUnknownId,
                                 "no body " + std::to_string(body.value()) + " any more")));
      return;
    }
    change(scene.world);
    SceneEvent e = live_.event(SceneEvent::Kind::kBodyChanged, by);
    e.body_ids = {body};
    members_.broadcast(std::move(e));
    done(body);
  });
}

void SceneRequests::apply_force(ClientId, BodyId body, std::vector<std::uint32_t> vertices,
                                const Vec3& force, Real duration, Completion<BodyId> done) {
  auto shared_vertices = std::make_shared<std::vector<std::uint32_t>>(std::move(vertices));
  request<BodyId>(std::move(done), [this, body, shared_vertices, force, duration](
                                       Scene& scene, Completion<BodyId>& done) {
    if (live_.timed_forces.size() >= kMaxTimedForces) {
      done(std::unexpected(error(RunnerError::Code::kLimitExceeded,
                                 "the scene already holds " + std::to_string(kMaxTimedForces) +
                                     " forces; wait for some to end")));
      return;
    }
    live_.timed_forces.add(body, std::move(*shared_vertices), force, scene.world.time() + duration);
    done(body);
  });
}

}  // namespace felt
