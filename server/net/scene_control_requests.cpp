// Scene control: pause, resume, step, time scale, reset, save and restore. Each is carried out
// by the scene's physics thread between two steps and answered from there.

#include "net/requests.hpp"

namespace felt::net {
namespace {

/// The completion that answers with the scene's status.
Completion<SceneStatus> answer_status(std::shared_ptr<PendingReply> pending, SceneId scene) {
  return answer<SceneStatus>(std::move(pending),
                             [scene](const SceneStatus& status, v1::ServerMessage& message) {
                               fill_status(scene, status, *message.mutable_scene_status());
                             });
}

/// Runs `request` with a status completion if the session may control its scene.
template <class Request>
void control(Session& session, std::uint64_t id, Request request) {
  if (!may_control(session, id)) return;
  auto pending = defer_or_refuse(session, id);
  if (!pending) return;
  request(*session.scene(), session.client_id(), answer_status(pending, session.scene_id()));
}

}  // namespace

bool may_control(Session& session, std::uint64_t id) {
  const SceneRunner& scene = *session.scene();
  if (scene.may_control(session.client_id())) return true;
  session.send_error(id, v1::ERROR_CODE_PERMISSION_DENIED,
                     scene.access().controllable
                         ? "only the client that loaded the scene may control it (it is not shared)"
                         : "the server's own scenes are controlled by no client "
                           "(--server-scenes-control none)");
  return false;
}

void handle_pause(Session& session, std::uint64_t id) {
  control(session, id, [](SceneRunner& scene, ClientId by, Completion<SceneStatus> done) {
    scene.pause(by, std::move(done));
  });
}

void handle_resume(Session& session, std::uint64_t id) {
  control(session, id, [](SceneRunner& scene, ClientId by, Completion<SceneStatus> done) {
    scene.resume(by, std::move(done));
  });
}

void handle_step(Session& session, std::uint64_t id, const v1::StepScene& step) {
  if (step.steps() == 0 || step.steps() > SceneRunner::kMaxStepsPerRequest) {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST,
                       "steps must be 1 to " + std::to_string(SceneRunner::kMaxStepsPerRequest));
    return;
  }
  control(session, id,
          [steps = step.steps()](SceneRunner& scene, ClientId by, Completion<SceneStatus> done) {
            scene.step(by, steps, std::move(done));
          });
}

void handle_time_scale(Session& session, std::uint64_t id, const v1::SetTimeScale& scale) {
  if (!(scale.scale() > 0 && scale.scale() <= 100)) {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, "scale must be in (0, 100]");
    return;
  }
  control(session, id,
          [s = scale.scale()](SceneRunner& scene, ClientId by, Completion<SceneStatus> done) {
            scene.set_time_scale(by, s, std::move(done));
          });
}

void handle_reset(Session& session, std::uint64_t id) {
  control(session, id,
          [loader = on_loader(session.context(), session.scene())](SceneRunner& scene, ClientId by,
                                                                   Completion<SceneStatus> done) {
            // built again on the loader thread: the scene steps on until the new one is in
            scene.reset(by, loader, std::move(done));
          });
}

void handle_save_state(Session& session, std::uint64_t id, const v1::SaveState& save) {
  if (!may_control(session, id)) return;
  auto pending = defer_or_refuse(session, id);
  if (!pending) return;
  const Real time_step = session.scene()->time_step();
  session.scene()->save_state(
      session.client_id(),
      answer<SavedState>(pending, [time_step, data = save.include_data()](
                                      const SavedState& saved, v1::ServerMessage& message) {
        v1::StateSaved& out = *message.mutable_state_saved();
        out.set_state_id(saved.id);
        out.set_step(saved.state->step);
        out.set_sim_time(saved.sim_time);
        if (data) fill_state(*saved.state, time_step, *out.mutable_data());
      }));
}

void handle_restore_state(Session& session, std::uint64_t id, const v1::RestoreState& restore) {
  if (restore.source_case() == v1::RestoreState::SOURCE_NOT_SET) {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, "RestoreState needs a state_id or data");
    return;
  }
  std::shared_ptr<const WorldState> state;
  if (restore.has_data()) {
    auto converted = to_state(restore.data());
    if (!converted) {
      session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, converted.error());
      return;
    }
    state = std::move(*converted);
  }
  control(session, id,
          [state, state_id = restore.state_id()](SceneRunner& scene, ClientId by,
                                                 Completion<SceneStatus> done) {
            if (state) {
              scene.restore_state(by, state, std::move(done));
            } else {
              scene.restore_state(by, state_id, std::move(done));
            }
          });
}

}  // namespace felt::net
