#include "net/session.hpp"

#include "net/dispatcher.hpp"
#include "net/wire_convert.hpp"
#include "wire/message_codec.hpp"

namespace felt::net {

namespace asio = boost::asio;
namespace v1 = felt::v1;

namespace {

// requests handled per turn of a session before the others get theirs (fairness on the one
// network thread: a client flooding updates waits for its next turn, not everyone else)
constexpr int kRequestsPerTurn = 32;
/// A proxy not updated for this long lets go of the surface it kept from its last update.
constexpr auto kProxyIdle = std::chrono::seconds(1);
/// The reply buffer a session keeps between writes, bytes: ForceUpdates and the usual replies
/// fit many times over.
constexpr std::size_t kKeptReplyCapacity = 64 * 1024;

}  // namespace

/// How a scene reaches the session: held by the session while it is in the scene, known to
/// the scene only weakly, so a session that left hears nothing more.
class Session::Membership : public SceneListener {
 public:
  Membership(std::weak_ptr<Session> session, SceneId scene)
      : session_(std::move(session)), scene_(scene) {}
  void on_scene_event(const SceneEvent& event) override {
    if (auto session = session_.lock()) {
      // the reference moves into the handler: this (physics) thread must never hold the last
      // one, or the session would be destroyed here
      const auto executor = session->socket_.get_executor();
      asio::post(executor, [session = std::move(session), scene = scene_, event] {
        session->on_scene_event(scene, event);
      });
    }
  }

 private:
  std::weak_ptr<Session> session_;
  SceneId scene_;
};

PendingReply::PendingReply(std::shared_ptr<Session> session, std::uint64_t request_id)
    : session_(session), request_id_(request_id) {
  ++session->in_flight_;
}

PendingReply::~PendingReply() {
  // every deferred request is answered; one dropped unanswered is a server bug, reported as such
  if (!sent_) fail(v1::ERROR_CODE_INTERNAL, "the request was dropped");
}

void PendingReply::send(v1::ServerMessage message) {
  if (sent_.exchange(true)) return;
  auto session = session_.lock();
  if (!session) return;
  message.set_request_id(request_id_);
  // as for events: the reference moves into the handler, off the calling thread
  const auto executor = session->socket_.get_executor();
  asio::post(executor, [session = std::move(session), message = std::move(message)] {
    --session->in_flight_;
    session->send(message);
  });
}

void PendingReply::fail(v1::ErrorCode code, std::string message) {
  v1::ServerMessage reply;
  fill_error(request_id_, code, message, reply);
  send(std::move(reply));
}

Session::Session(asio::ip::tcp::socket socket, ServerContext& context)
    : socket_(std::move(socket)),
      context_(context),
      id_(context.next_client_id.fetch_add(1)),
      decoder_(context.options.max_inbound_frame_bytes),
      hello_timer_(socket_.get_executor()),
      frame_timer_(socket_.get_executor()) {
  // write_next writes from the handler that has something to send, and must never wait; a
  // socket that cannot be made so is closed, and the session ends at its first read
  boost::system::error_code ec;
  socket_.non_blocking(true, ec);
  if (ec) socket_.close(ec);
}

Session::~Session() {
  // a session normally leaves on its strand when its connection ends; one destroyed with the
  // io_context at exit must not post events into it
  leave_scene(true);
  if (counted_) --context_.clients;
}

void Session::start() {
  counted_ = true;
  ++context_.clients;
  asio::dispatch(socket_.get_executor(), [self = shared_from_this()] {
    self->start_hello_deadline();
    self->read();
  });
}

void Session::start_hello_deadline() {
  hello_timer_.expires_after(std::chrono::milliseconds(context_.options.hello_timeout_ms));
  // weak: the timer never keeps a session alive; the session cancels it when greeted or closed
  hello_timer_.async_wait([weak = weak_from_this()](const boost::system::error_code& ec) {
    const auto self = weak.lock();
    if (ec || !self || self->greeted_ || self->closed_ || self->closing_) return;
    self->send_error(0, v1::ERROR_CODE_HELLO_REQUIRED,
                     "no Hello within " + std::to_string(self->context_.options.hello_timeout_ms) +
                         " ms; the connection closes");
    self->close_after_replies();
  });
}

void Session::reject(v1::ErrorCode code, const std::string& message) {
  asio::dispatch(socket_.get_executor(), [self = shared_from_this(), code, message] {
    self->send_error(0, code, message);
    self->close_after_replies();
  });
}

void Session::post(std::function<void()> task) {
  asio::post(socket_.get_executor(), std::move(task));
}

void Session::close() {
  asio::post(socket_.get_executor(), [self = shared_from_this()] { self->shutdown(); });
}

void Session::close_gracefully() {
  asio::post(socket_.get_executor(), [self = shared_from_this()] {
    if (self->closed_) return;
    v1::ServerMessage goodbye;
    v1::SceneEvent& event = *goodbye.mutable_event();
    event.set_scene_id(self->scene_id_);
    event.set_kind(v1::EVENT_KIND_SERVER_SHUTDOWN);
    self->send(goodbye);
    self->close_after_replies();
  });
}

void Session::shutdown() {
  if (closed_) return;
  closed_ = true;
  hello_timer_.cancel();
  frame_timer_.cancel();
  boost::system::error_code ignored;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
  leave_scene();
  if (counted_) {
    counted_ = false;
    --context_.clients;
  }
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
  counters_.bytes_received += bytes;
  decoder_.feed(std::span<const std::uint8_t>(read_buffer_.data(), bytes));
  process();
}

void Session::process() {
  for (int handled = 0; !closing_ && !closed_; ++handled) {
    if (handled == kRequestsPerTurn) {
      asio::post(socket_.get_executor(), [self = shared_from_this()] { self->process(); });
      return;
    }
    const wire::DecodeResult frame = decoder_.next();
    if (frame.status == wire::DecodeStatus::kNeedMore) break;
    if (frame.status == wire::DecodeStatus::kTooLarge) {
      send_error(0, v1::ERROR_CODE_FRAME_TOO_LARGE,
                 "frame of " + std::to_string(frame.announced_length) +
                     " bytes exceeds the limit of " + std::to_string(decoder_.max_frame_bytes()));
      close_after_replies();  // the error goes out, then the write path closes the socket
      break;
    }
    v1::ClientMessage message;
    if (frame.status == wire::DecodeStatus::kBadPrefix ||
        !wire::parse_message(frame.payload, message)) {
      send_error(0, v1::ERROR_CODE_MALFORMED_FRAME, "bytes that are not a felt.v1.ClientMessage");
      close_after_replies();
      break;
    }
    ++counters_.requests;
    dispatch(*this, message);
  }
  if (closed_ || closing_) return;
  read();
}

void Session::send(const v1::ServerMessage& message) {
  if (closed_ || !socket_.is_open()) return;
  const bool backlog = !queued_replies_.empty();
  wire::append_message(queued_replies_, message);
  // one reply larger than the backlog on its own (a big saved state) still goes out
  if (queued_replies_.size() > context_.options.max_queued_reply_bytes && backlog) {
    // the client does not read its replies; dropping them would break the protocol
    std::string().swap(queued_replies_);
    shutdown();
    return;
  }
  write_next();
}

void Session::send_error(std::uint64_t request_id, v1::ErrorCode code, const std::string& text) {
  v1::ServerMessage reply;
  fill_error(request_id, code, text, reply);
  send(reply);
}

void Session::close_after_replies() {
  closing_ = true;
  drop_pending_frame();
  write_next();
}

std::shared_ptr<PendingReply> Session::defer(std::uint64_t request_id) {
  if (in_flight_.load() >= context_.options.max_requests_in_flight) return nullptr;
  return std::make_shared<PendingReply>(shared_from_this(), request_id);
}

void Session::set_greeted(std::string client_name) {
  const bool first = !greeted_;
  greeted_ = true;
  hello_timer_.cancel();
  client_name_ = std::move(client_name);
  // a client is in the server's default scene from its first Hello: before it, it hears nothing
  if (first && !scene_ && context_.default_scene != 0) join(context_.default_scene);
}

bool Session::refuse_hello() {
  return ++refused_hellos_ >= kMaxRefusedHellos;
}

void Session::write_next() {
  while (!writing_ && !closed_ && socket_.is_open()) {
    if (!queued_replies_.empty()) {
      // every queued reply goes out in one write, and the buffer written last takes their
      // place; one grown past what replies usually need (a burst, a frame) is let go
      in_flight_bytes_.swap(queued_replies_);
      queued_replies_.clear();
      if (queued_replies_.capacity() > kKeptReplyCapacity) std::string().swap(queued_replies_);
    } else if (frame_pending_ && !closing_) {
      in_flight_bytes_.swap(pending_frame_);
      frame_pending_ = false;
      frames_.written();
      ++counters_.frames_sent;
    } else {
      if (closing_) shutdown();
      return;
    }
    counters_.bytes_sent += in_flight_bytes_.size();
    // what the kernel takes at once is done here: a write left to finish in a completion
    // handler would hold the next ForceUpdate until that handler's thread gets a core (with
    // the physics thread busy, up to a millisecond: the outbound leg's tail)
    boost::system::error_code ec;
    const std::size_t written = socket_.write_some(asio::buffer(in_flight_bytes_), ec);
    if (ec && ec != asio::error::would_block && ec != asio::error::try_again) {
      shutdown();
      return;
    }
    if (written == in_flight_bytes_.size()) continue;
    writing_ = true;
    asio::async_write(
        socket_, asio::buffer(in_flight_bytes_) + written,
        [self = shared_from_this()](const boost::system::error_code& error, std::size_t) {
          self->writing_ = false;
          if (error) {
            self->shutdown();
            return;
          }
          self->write_next();
        });
  }
}

bool Session::join(SceneId id) {
  auto membership = std::make_shared<Membership>(weak_from_this(), id);
  auto scene = context_.scenes.join(id, {id_, client_name_, membership});
  if (!scene) return false;
  leave_scene();
  scene_id_ = id;
  scene_ = std::move(scene);
  membership_ = std::move(membership);
  // a frame of the previous scene that has not gone out yet is dropped
  drop_pending_frame();
  frames_.restart();
  scene_->prepare_haptics();
  announce(SceneEvent::Kind::kClientJoined);
  return true;
}

void Session::announce(SceneEvent::Kind kind) {
  SceneEvent event;
  event.kind = kind;
  event.client = id_;
  event.client_name = client_name_;
  scene_->members().broadcast(std::move(event));
}

void Session::drop_pending_frame() {
  frame_pending_ = false;
  pending_frame_.clear();
  frame_encoding_ = false;
  ++frame_generation_;
}

void Session::forget_scene() {
  close_proxies();
  membership_.reset();
  scene_.reset();
  scene_id_ = 0;
  drop_pending_frame();
  frames_.restart();
}

void Session::leave_scene(bool quietly) {
  if (!scene_) return;
  if (!quietly) announce(SceneEvent::Kind::kClientLeft);
  const SceneId left = scene_id_;
  forget_scene();
  // a scene a client loaded lives as long as some session is in it
  context_.scenes.leave(left, id_);
}

void Session::on_scene_event(SceneId scene, const SceneEvent& event) {
  // from a scene the session has left, or after its goodbye: nothing more
  if (closed_ || closing_ || scene != scene_id_) return;
  v1::ServerMessage message;
  fill_event(scene, event, *message.mutable_event());
  send(message);
  // the scene is gone from the registry already: only let go of it
  if (event.kind == SceneEvent::Kind::kDestroyed) forget_scene();
}

std::uint64_t Session::key_of(std::uint32_t proxy_id) const {
  return (std::uint64_t{id_} << 32) | proxy_id;
}

void Session::close_proxies() {
  if (scene_) {
    for (const auto& [id, proxy] : proxies_) scene_->close_proxy(proxy);
  }
  proxies_.clear();
}

HapticProxy* Session::proxy(std::uint32_t proxy_id) {
  const auto it = proxies_.find(proxy_id);
  if (it != proxies_.end()) return &it->second;
  if (proxies_.size() >= context_.options.max_proxies_per_session) return nullptr;
  return &proxies_.emplace(proxy_id, scene_->open_proxy(key_of(proxy_id))).first->second;
}

std::uint32_t Session::open_proxy(const ProxySettings& settings) {
  if (proxies_.size() >= context_.options.max_proxies_per_session) return 0;
  std::uint32_t id = 1;
  while (proxies_.contains(id)) ++id;
  proxies_.emplace(id, scene_->open_proxy(key_of(id), settings));
  return id;
}

bool Session::close_proxy(std::uint32_t proxy_id) {
  const auto it = proxies_.find(proxy_id);
  if (it == proxies_.end()) return false;
  scene_->close_proxy(it->second);
  proxies_.erase(it);
  return true;
}

void Session::subscribe_frames(const FrameOptions& options) {
  frames_.start(options);
  drop_pending_frame();
  if (!timer_running_) {
    timer_running_ = true;
    on_frame_tick();
  }
}

void Session::unsubscribe_frames() {
  frames_.stop();
  drop_pending_frame();
  frame_timer_.cancel();
  timer_running_ = false;
}

void Session::schedule_frame() {
  frame_timer_.expires_after(
      std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / frames_.options().rate_hz)));
  frame_timer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (!ec && self->timer_running_) self->on_frame_tick();
  });
}

void Session::forget_idle_proxy_surfaces(SteadyClock::time_point now) {
  for (auto& [id, proxy] : proxies_) proxy.forget_surface_if_idle(now, kProxyIdle);
}

void Session::on_frame_tick() {
  if (closed_ || !frames_.active()) {
    timer_running_ = false;
    return;
  }
  forget_idle_proxy_surfaces(SteadyClock::now());
  // a frame still with the encoder (a busy server) is the latest one: no other is planned
  if (scene_ && !frame_encoding_) {
    auto snapshot = scene_->latest();
    if (frames_.has_new(*snapshot)) {
      std::uint64_t skipped = 0;
      if (frame_pending_) {
        // the client has not taken the previous frame: it is dropped, and so are the triangles
        // it carried, which the next frame must carry instead
        skipped = pending_frame_skipped_ + 1;
        frames_.dropped();
        drop_pending_frame();
        ++counters_.frames_skipped;
      }
      encode_frame(frames_.plan(std::move(snapshot), scene_id_, skipped));
    }
  }
  schedule_frame();
}

void Session::encode_frame(FrameStream::Plan plan) {
  frame_encoding_ = true;
  asio::post(context_.frame_encoder, [weak = weak_from_this(), plan = std::move(plan),
                                      generation = frame_generation_] {
    v1::ServerMessage message;
    FrameStream::FrameRecord record;
    FrameStream::encode(plan, *message.mutable_frame(), record);
    std::string bytes;
    wire::append_message(bytes, message);
    auto session = weak.lock();
    if (!session) return;
    // as for events: the reference moves into the handler, so that the session is never
    // destroyed on this thread
    const auto executor = session->socket_.get_executor();
    asio::post(executor, [session = std::move(session), generation, skipped = plan.skipped,
                          record = std::move(record), bytes = std::move(bytes)]() mutable {
      session->on_frame_encoded(generation, skipped, std::move(record), std::move(bytes));
    });
  });
}

void Session::on_frame_encoded(std::uint64_t generation, std::uint64_t skipped,
                               FrameStream::FrameRecord record, std::string bytes) {
  // dropped while it was encoded (a new subscription, another scene, the connection's end)
  if (generation != frame_generation_ || closed_ || closing_) return;
  frame_encoding_ = false;
  frames_.encoded(std::move(record));
  pending_frame_ = std::move(bytes);
  frame_pending_ = true;
  pending_frame_skipped_ = skipped;
  write_next();
}

}  // namespace felt::net
