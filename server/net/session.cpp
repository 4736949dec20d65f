#include "net/session.hpp"

#include "net/dispatcher.hpp"
#include "net/frame_builder.hpp"
#include "wire/message_codec.hpp"

namespace felt::net {

namespace asio = boost::asio;
namespace v1 = felt::v1;

Session::Session(asio::ip::tcp::socket socket, ServerContext& context)
    : socket_(std::move(socket)),
      context_(context),
      id_(context.next_session_id.fetch_add(1)),
      decoder_(context.options.max_inbound_frame_bytes),
      frame_timer_(socket_.get_executor()) {}

Session::~Session() {
  leave_scene();
}

void Session::start() {
  asio::dispatch(socket_.get_executor(), [self = shared_from_this()] {
    if (self->context_.default_scene != 0) {
      if (auto scene = self->context_.scenes.find(self->context_.default_scene)) {
        self->join(self->context_.default_scene, std::move(scene));
      }
    }
    self->read();
  });
}

void Session::close() {
  asio::post(socket_.get_executor(), [self = shared_from_this()] { self->shutdown(); });
}

void Session::shutdown() {
  if (closed_) return;
  closed_ = true;
  frame_timer_.cancel();
  boost::system::error_code ignored;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
  leave_scene();
}

void Session::read() {
  socket_.async_read_some(
      asio::buffer(read_buffer_),
      [self = shared_from_this()](const boost::system::error_code& ec, std::size_t bytes) {
        self->on_read(ec, bytes);
      });
}

void Session::on_read(const boost::system::error_code& ec, std::size_t bytes) {
  if (ec || closed_) {
    shutdown();
    return;
  }
  decoder_.feed(std::span<const std::uint8_t>(read_buffer_.data(), bytes));
  while (!closing_) {
    const wire::DecodeResult frame = decoder_.next();
    if (frame.status == wire::DecodeStatus::kNeedMore) break;
    if (frame.status == wire::DecodeStatus::kTooLarge) {
      send_error(0, v1::ERROR_CODE_FRAME_TOO_LARGE,
                 "frame of " + std::to_string(frame.announced_length) +
                     " bytes exceeds the limit of " + std::to_string(decoder_.max_frame_bytes()));
      closing_ = true;  // flush the error, then the write path closes the socket
      break;
    }
    v1::ClientMessage message;
    if (frame.status == wire::DecodeStatus::kBadPrefix ||
        !wire::parse_message(frame.payload, message)) {
      send_error(0, v1::ERROR_CODE_MALFORMED_FRAME, "bytes that are not a felt.v1.ClientMessage");
      closing_ = true;
      break;
    }
    dispatch(*this, message);
  }
  if (closing_) {
    if (!writing_) shutdown();
    return;
  }
  read();
}

void Session::send(const v1::ServerMessage& message) {
  if (!socket_.is_open()) return;
  std::string bytes;
  wire::append_message(bytes, message);
  queued_reply_bytes_ += bytes.size();
  replies_.push_back(std::move(bytes));
  if (queued_reply_bytes_ > context_.options.max_queued_reply_bytes) {
    // the client does not read its replies; dropping them would break the protocol
    replies_.clear();
    shutdown();
    return;
  }
  write_next();
}

void Session::send_error(std::uint64_t request_id, v1::ErrorCode code, const std::string& text) {
  v1::ServerMessage reply;
  reply.set_request_id(request_id);
  v1::Error* error = reply.mutable_error();
  error->set_code(code);
  error->set_message(text);
  error->set_request_id(request_id);
  send(reply);
}

void Session::write_next() {
  if (writing_ || !socket_.is_open()) return;
  if (!replies_.empty()) {
    in_flight_ = std::move(replies_.front());
    replies_.pop_front();
    queued_reply_bytes_ -= in_flight_.size();
  } else if (frame_pending_ && !closing_) {
    in_flight_.swap(pending_frame_);
    frame_pending_ = false;
  } else {
    if (closing_) shutdown();
    return;
  }
  writing_ = true;
  asio::async_write(socket_, asio::buffer(in_flight_),
                    [self = shared_from_this()](const boost::system::error_code& ec, std::size_t) {
                      self->writing_ = false;
                      if (ec) {
                        self->shutdown();
                        return;
                      }
                      self->write_next();
                    });
}

void Session::join(SceneId id, std::shared_ptr<SceneRunner> scene) {
  leave_scene();
  // a frame of the previous scene that has not gone out yet is dropped
  frame_pending_ = false;
  pending_frame_.clear();
  pending_topology_.clear();
  scene_id_ = id;
  scene_ = std::move(scene);
  topology_sent_.assign(scene_ ? scene_->bodies().size() : 0, false);
  last_frame_step_ = ~std::uint64_t{0};
  // events from before the session joined are history it does not need
  const auto snapshot = scene_ ? scene_->latest() : nullptr;
  last_event_sequence_ =
      snapshot && snapshot->events ? snapshot->events->back().sequence : std::uint64_t{0};
}

void Session::leave_scene() {
  if (scene_) {
    for (const auto& [id, proxy] : proxies_) scene_->close_proxy(proxy);
  }
  proxies_.clear();
  scene_.reset();
  // a scene a client loaded lives as long as some session is in it
  if (scene_id_ != 0 && scene_id_ != context_.default_scene) {
    context_.scenes.remove_if_unused(scene_id_);
  }
  scene_id_ = 0;
}

std::uint64_t Session::key_of(std::uint32_t proxy_id) const {
  return (id_ << 32) | proxy_id;
}

HapticProxy* Session::open_proxy(std::uint32_t proxy_id) {
  const auto it = proxies_.find(proxy_id);
  if (it != proxies_.end()) return &it->second;
  if (proxies_.size() >= context_.options.max_proxies_per_session) return nullptr;
  return &proxies_.emplace(proxy_id, scene_->open_proxy(key_of(proxy_id))).first->second;
}

void Session::subscribe_frames(double rate_hz, bool normals) {
  stream_normals_ = normals;
  frame_period_ = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / rate_hz));
  std::fill(topology_sent_.begin(), topology_sent_.end(), false);
  last_frame_step_ = ~std::uint64_t{0};
  if (!streaming_) {
    streaming_ = true;
    on_frame_tick();
  }
}

void Session::send_new_events(const SceneSnapshot& snapshot) {
  if (!snapshot.events) return;
  for (const SceneEvent& event : *snapshot.events) {
    if (event.sequence <= last_event_sequence_) continue;
    v1::ServerMessage message;
    v1::SceneEvent& out = *message.mutable_event();
    out.set_scene_id(scene_id_);
    out.set_sequence(event.sequence);
    out.set_kind(v1::EVENT_KIND_UNRECOVERABLE_STEP);
    out.set_step(event.step);
    out.set_sim_time(event.sim_time);
    out.set_count(event.unrecoverable_steps);
    for (std::uint32_t body : event.bodies) out.add_body_ids(body);
    send(message);
    last_event_sequence_ = event.sequence;
  }
}

void Session::schedule_frame() {
  frame_timer_.expires_after(frame_period_);
  frame_timer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (!ec) self->on_frame_tick();
  });
}

void Session::on_frame_tick() {
  if (closed_) return;
  if (scene_) {
    const auto snapshot = scene_->latest();
    send_new_events(*snapshot);
    if (snapshot->step != last_frame_step_) {
      std::uint64_t skipped = 0;
      if (frame_pending_) {
        // the client has not taken the previous frame: it is dropped, and so are the triangles
        // it carried, which the next frame must carry instead
        skipped = pending_frame_skipped_ + 1;
        for (std::uint32_t body : pending_topology_) topology_sent_[body] = false;
      }
      v1::ServerMessage message;
      pending_topology_ = build_frame(*snapshot, scene_id_, stream_normals_, topology_sent_,
                                      skipped, *message.mutable_frame());
      pending_frame_.clear();
      wire::append_message(pending_frame_, message);
      frame_pending_ = true;
      pending_frame_skipped_ = skipped;
      last_frame_step_ = snapshot->step;
      write_next();
    }
  }
  schedule_frame();
}

}  // namespace felt::net
