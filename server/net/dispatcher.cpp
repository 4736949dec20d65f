#include "net/dispatcher.hpp"

#include "net/requests.hpp"

namespace felt::net {

using v1::ClientMessage;

std::shared_ptr<PendingReply> defer_or_refuse(Session& session, std::uint64_t id) {
  auto pending = session.defer(id);
  if (!pending) {
    session.send_error(id, v1::ERROR_CODE_LIMIT_EXCEEDED,
                       "at most " +
                           std::to_string(session.context().options.max_requests_in_flight) +
                           " requests in flight per client (--max-requests-in-flight)");
  }
  return pending;
}

void fail(PendingReply& pending, const RunnerError& error) {
  switch (error.exceeded) {
    case SceneLimit::kNone:
      return pending.fail(error_code(error.code), error.message);
    case SceneLimit::kBodies:
      return pending.fail(error_code(error.code), error.message + " (--max-bodies)");
    case SceneLimit::kParticles:
      return pending.fail(error_code(error.code), error.message + " (--max-particles)");
  }
}

RunnerError load_error(const SceneError& error) {
  return {error.exceeded == SceneLimit::kNone ? RunnerError::Code::kBadScene
                                              : RunnerError::Code::kLimitExceeded,
          error.what(), error.exceeded};
}

namespace {

/// Requests that work without a scene; the rest answer NO_SCENE until the session has one.
bool needs_scene(ClientMessage::BodyCase body) {
  switch (body) {
    case ClientMessage::kHello:
    case ClientMessage::kListScenes:
    case ClientMessage::kLoadScene:
    case ClientMessage::kCreateScene:
    case ClientMessage::kJoinScene:
    case ClientMessage::kDestroyScene:
    case ClientMessage::kUnsubscribeFrames:
    case ClientMessage::kGetStats:
      return false;
    default:
      return true;
  }
}

}  // namespace

void dispatch(Session& session, const ClientMessage& message) {
  const std::uint64_t id = message.request_id();
  const ClientMessage::BodyCase body = message.body_case();
  if (body == ClientMessage::kHello) {
    handle_hello(session, id, message.hello());
    return;
  }
  if (!session.greeted()) {
    session.send_error(id, v1::ERROR_CODE_HELLO_REQUIRED, "send Hello first");
    return;
  }
  if (body == ClientMessage::BODY_NOT_SET) {
    session.send_error(id, v1::ERROR_CODE_UNKNOWN_MESSAGE,
                       "a ClientMessage with no body this server knows");
    return;
  }
  if (needs_scene(body) && !session.scene()) {
    session.send_error(id, v1::ERROR_CODE_NO_SCENE, "load or join a scene first");
    return;
  }
  switch (body) {
    case ClientMessage::kListScenes:
      return handle_list_scenes(session, id);
    case ClientMessage::kLoadScene:
      return handle_load_scene(session, id, message.load_scene());
    case ClientMessage::kCreateScene:
      return handle_create_scene(session, id, message.create_scene());
    case ClientMessage::kJoinScene:
      return handle_join_scene(session, id, message.join_scene());
    case ClientMessage::kLeaveScene:
      return handle_leave_scene(session, id);
    case ClientMessage::kDestroyScene:
      return handle_destroy_scene(session, id, message.destroy_scene());
    case ClientMessage::kPauseScene:
      return handle_pause(session, id);
    case ClientMessage::kResumeScene:
      return handle_resume(session, id);
    case ClientMessage::kStepScene:
      return handle_step(session, id, message.step_scene());
    case ClientMessage::kSetTimeScale:
      return handle_time_scale(session, id, message.set_time_scale());
    case ClientMessage::kResetScene:
      return handle_reset(session, id);
    case ClientMessage::kSaveState:
      return handle_save_state(session, id, message.save_state());
    case ClientMessage::kRestoreState:
      return handle_restore_state(session, id, message.restore_state());
    case ClientMessage::kAddBody:
      return handle_add_body(session, id, message.add_body());
    case ClientMessage::kRemoveBody:
      return handle_remove_body(session, id, message.remove_body());
    case ClientMessage::kSetBodyParameters:
      return handle_set_body_parameters(session, id, message.set_body_parameters());
    case ClientMessage::kPinParticles:
      return handle_pin_particles(session, id, message.pin_particles());
    case ClientMessage::kApplyForce:
      return handle_apply_force(session, id, message.apply_force());
    case ClientMessage::kOpenProxy:
      return handle_open_proxy(session, id, message.open_proxy());
    case ClientMessage::kCloseProxy:
      return handle_close_proxy(session, id, message.close_proxy());
    case ClientMessage::kProxyUpdate:
      return handle_proxy_update(session, id, message.proxy_update());
    case ClientMessage::kSubscribeFrames:
      return handle_subscribe(session, id, message.subscribe_frames());
    case ClientMessage::kUnsubscribeFrames:
      return handle_unsubscribe(session, id);
    case ClientMessage::kAckFrame:
      return handle_ack_frame(session, id, message.ack_frame());
    case ClientMessage::kGetStats:
      return handle_get_stats(session, id);
    case ClientMessage::kHello:
    case ClientMessage::BODY_NOT_SET:
      break;
  }
}

}  // namespace felt::net
