// Frames: subscribe, unsubscribe, acknowledge.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "net/requests.hpp"

namespace felt::net {

void handle_subscribe(Session& session, std::uint64_t id, const v1::SubscribeFrames& subscribe) {
  const ServerOptions& limits = session.context().options;
  const auto bad = [&](v1::ErrorCode code, const std::string& why) {
    session.send_error(id, code, why);
  };
  const double asked = subscribe.max_rate_hz();
  // a tiny rate would overflow the timer period; 0 asks for the default
  if (!std::isfinite(asked) || asked < 0 || (asked > 0 && asked < limits.min_frame_rate_hz)) {
    return bad(v1::ERROR_CODE_BAD_REQUEST, "max_rate_hz must be 0 (the default) or at least " +
                                               std::to_string(limits.min_frame_rate_hz));
  }
  if (asked > limits.max_frame_rate_hz) {
    std::ostringstream why;
    why << "max_rate_hz " << asked << " is above the limit of " << limits.max_frame_rate_hz
        << " (--max-frame-rate)";
    return bad(v1::ERROR_CODE_LIMIT_EXCEEDED, why.str());
  }
  if (!v1::FrameEncoding_IsValid(subscribe.encoding())) {
    return bad(v1::ERROR_CODE_BAD_REQUEST, "unknown encoding");
  }
  const bool quantized = subscribe.encoding() == v1::FRAME_ENCODING_QUANTIZED16;
  if (subscribe.deltas() && !quantized) {
    return bad(v1::ERROR_CODE_BAD_REQUEST, "deltas need the QUANTIZED16 encoding");
  }
  if (subscribe.max_unacknowledged() > FrameStream::kMaxWindow) {
    return bad(v1::ERROR_CODE_LIMIT_EXCEEDED,
               "max_unacknowledged " + std::to_string(subscribe.max_unacknowledged()) +
                   " is above the limit of " + std::to_string(FrameStream::kMaxWindow));
  }
  std::vector<BodyId> wanted = sorted_unique<BodyId>(subscribe.body_ids());
  const auto bodies = session.scene()->bodies();
  for (BodyId body : wanted) {
    if (!bodies->find(body)) {
      return bad(v1::ERROR_CODE_UNKNOWN_ID,
                 "no body " + std::to_string(body.value()) + " in this scene");
    }
  }
  FrameOptions options;
  options.rate_hz =
      asked == 0 ? std::min(limits.default_frame_rate_hz, limits.max_frame_rate_hz) : asked;
  options.normals = subscribe.normals();
  options.bodies = std::move(wanted);
  options.quantized = quantized;
  options.deltas = subscribe.deltas();
  options.scalars = subscribe.scalars();
  options.max_unacknowledged = subscribe.max_unacknowledged();
  session.subscribe_frames(options);
  reply(session, id, [&](v1::ServerMessage& message) {
    v1::Subscribed& subscribed = *message.mutable_subscribed();
    subscribed.set_scene_id(session.scene_id().value());
    subscribed.set_rate_hz(options.rate_hz);
    subscribed.set_encoding(subscribe.encoding());
    subscribed.set_deltas(options.deltas);
    subscribed.set_max_unacknowledged(options.max_unacknowledged);
  });
}

void handle_unsubscribe(Session& session, std::uint64_t id) {
  session.unsubscribe_frames();
  reply(session, id, [](v1::ServerMessage& message) { message.mutable_unsubscribed(); });
}

void handle_ack_frame(Session& session, std::uint64_t id, const v1::AckFrame& ack) {
  if (!session.frames().active()) {
    session.send_error(id, v1::ERROR_CODE_WRONG_STATE, "not subscribed to frames");
    return;
  }
  if (!session.frames().acknowledge(ack.sequence())) {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST,
                       "no frame " + std::to_string(ack.sequence()) + " was sent");
    return;
  }
  reply(session, id, [&](v1::ServerMessage& message) {
    message.mutable_frame_acked()->set_sequence(ack.sequence());
  });
}

}  // namespace felt::net
