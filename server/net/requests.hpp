#pragma once
// The handlers of every request, one file per group (session, scenes, scene control, bodies,
// haptics, frames), and what they share. Each answers its request with one reply or Error,
// now or through a PendingReply.

#include <algorithm>
#include <functional>
#include <memory>
#include <type_traits>
#include <vector>

#include "felt/v1/envelope.pb.h"
#include "net/session.hpp"
#include "net/wire_convert.hpp"

namespace felt::net {

namespace v1 = felt::v1;

/// The protocol version this server speaks.
inline constexpr std::uint32_t kProtocolVersion = 1;

// session_requests.cpp
void handle_hello(Session& session, std::uint64_t id, const v1::Hello& hello);
void handle_get_stats(Session& session, std::uint64_t id);

// scene_requests.cpp
void handle_list_scenes(Session& session, std::uint64_t id);
void handle_load_scene(Session& session, std::uint64_t id, const v1::LoadScene& load);
void handle_create_scene(Session& session, std::uint64_t id, const v1::CreateScene& create);
void handle_join_scene(Session& session, std::uint64_t id, const v1::JoinScene& join);
void handle_leave_scene(Session& session, std::uint64_t id);
void handle_destroy_scene(Session& session, std::uint64_t id, const v1::DestroyScene& destroy);

// scene_control_requests.cpp (need a scene)
void handle_pause(Session& session, std::uint64_t id);
void handle_resume(Session& session, std::uint64_t id);
void handle_step(Session& session, std::uint64_t id, const v1::StepScene& step);
void handle_time_scale(Session& session, std::uint64_t id, const v1::SetTimeScale& scale);
void handle_reset(Session& session, std::uint64_t id);
void handle_save_state(Session& session, std::uint64_t id, const v1::SaveState& save);
void handle_restore_state(Session& session, std::uint64_t id, const v1::RestoreState& restore);

// body_requests.cpp (need a scene)
void handle_add_body(Session& session, std::uint64_t id, const v1::AddBody& add);
void handle_remove_body(Session& session, std::uint64_t id, const v1::RemoveBody& remove);
void handle_set_body_parameters(Session& session, std::uint64_t id,
                                const v1::SetBodyParameters& set);
void handle_pin_particles(Session& session, std::uint64_t id, const v1::PinParticles& pins);
void handle_apply_force(Session& session, std::uint64_t id, const v1::ApplyForce& force);

// haptic_requests.cpp (need a scene)
void handle_open_proxy(Session& session, std::uint64_t id, const v1::OpenProxy& open);
void handle_close_proxy(Session& session, std::uint64_t id, const v1::CloseProxy& close);
void handle_proxy_update(Session& session, std::uint64_t id, const v1::ProxyUpdate& update);

// frame_requests.cpp (need a scene, except unsubscribing)
void handle_subscribe(Session& session, std::uint64_t id, const v1::SubscribeFrames& subscribe);
void handle_unsubscribe(Session& session, std::uint64_t id);
void handle_ack_frame(Session& session, std::uint64_t id, const v1::AckFrame& ack);

/// Sends the reply `fill` writes (a template: this is on the haptic path, once per update).
template <class Fill>
void reply(Session& session, std::uint64_t id, Fill&& fill) {
  v1::ServerMessage message;
  message.set_request_id(id);
  fill(message);
  session.send(message);
}

/// Runs a scene's job on the loader thread, keeping the scene alive until it has run.
Offload on_loader(ServerContext& context, std::shared_ptr<SceneRunner> scene);

/// The ids a request lists, sorted, each once, as `Id`s (the wire's integers by default).
template <class Id = void, class Repeated>
auto sorted_unique(const Repeated& ids) {
  using Out = std::conditional_t<std::is_void_v<Id>, typename Repeated::value_type, Id>;
  std::vector<Out> out(ids.begin(), ids.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// A reply deferred past the session's turn, or null after answering LIMIT_EXCEEDED.
std::shared_ptr<PendingReply> defer_or_refuse(Session& session, std::uint64_t id);

/// Answers `pending` with `error`; one over a scene limit names the flag that sets it.
void fail(PendingReply& pending, const RunnerError& error);

/// Why a scene or body did not load: over a limit (LIMIT_EXCEEDED), or a bad document.
RunnerError load_error(const SceneError& error);

/// A completion that answers `pending`: its error, or the reply `fill` writes from the value.
template <class T>
Completion<T> answer(std::shared_ptr<PendingReply> pending,
                     std::function<void(const T&, v1::ServerMessage&)> fill) {
  return [pending = std::move(pending), fill = std::move(fill)](std::expected<T, RunnerError> r) {
    if (!r) {
      fail(*pending, r.error());
      return;
    }
    v1::ServerMessage message;
    fill(*r, message);
    pending->send(std::move(message));
  };
}

/// The body `body_id` of the session's scene, if the session may change it (answers
/// UNKNOWN_ID or PERMISSION_DENIED otherwise).
std::optional<BodyInfo> changeable_body(Session& session, std::uint64_t id, BodyId body_id);

/// Whether the session may control its scene (answers PERMISSION_DENIED otherwise).
bool may_control(Session& session, std::uint64_t id);

/// The scene's description as SceneLoaded carries it.
void fill_scene_loaded(SceneId scene_id, const SceneRunner& scene, v1::SceneLoaded& out);

}  // namespace felt::net
