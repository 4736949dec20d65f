#include "net/session.hpp"

#include <boost/asio/dispatch.hpp>

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
/// A session logs one refusal of a limit in this time at most.
constexpr auto kRefusalLogInterval = std::chrono::seconds(1);

/// The errors that refuse a limit (docs/protocol.md 4.2): those the log reports.
bool refuses_a_limit(v1::ErrorCode code) {
  return code == v1::ERROR_CODE_LIMIT_EXCEEDED || code == v1::ERROR_CODE_FRAME_TOO_LARGE;
}

std::string code_name(v1::ErrorCode code) {
  return v1::ErrorCode_Name(code).substr(std::string_view("ERROR_CODE_").size());
}

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
      Session& target = *session;
      target.post([session = std::move(session), scene = scene_, event] {
        session->on_scene_event(scene, event);
      });
    }
  }

 private:
  std::weak_ptr<Session> session_;
  SceneId scene_;
};

Session::Session(std::unique_ptr<Transport> transport, ServerContext& context)
    : transport_(std::move(transport)),
      context_(context),
      id_(context.next_client_id.fetch_add(1)),
      outbound_(*transport_, *this, context.options.max_queued_reply_bytes),
      frames_(id_, transport_->executor(), context.frame_encoder, context.frame_bodies, outbound_),
      hello_timer_(transport_->executor()),
      rate_(context.options.max_request_rate, request_burst(context.options.max_request_rate),
            RequestRate::Clock::now()),
      rate_timer_(transport_->executor()) {}

Session::~Session() {
  // a session normally leaves on its strand when its connection ends; one destroyed with the
  // io_context at exit must not post events into it
  leave_scene(true);
  if (counted_) --context_.clients;
}

void Session::hold_while_busy() {
  outbound_.set_owner(weak_from_this());
  frames_.set_owner(weak_from_this());
}

void Session::start() {
  context_.log.debug("connection from " + transport_->peer());
  counted_ = true;
  ++context_.clients;
  hold_while_busy();
  frames_.on_tick([this] { forget_idle_proxy_surfaces(SteadyClock::now()); });
  asio::dispatch(transport_->executor(), [self = shared_from_this()] {
    self->start_hello_deadline();
    self->read();
  });
}

void Session::start_hello_deadline() {
  hello_timer_.expires_after(std::chrono::milliseconds(context_.options.hello_timeout_ms));
  // weak: the timer never keeps a session alive; the session cancels it when greeted or closed
  hello_timer_.async_wait([weak = weak_from_this()](const boost::system::error_code& ec) {
    const auto self = weak.lock();
    if (ec || !self || self->greeted_ || self->closed_ || self->outbound_.closing()) return;
    self->context_.log.warning(
        self->who() + " from " + self->transport_->peer() + " closed: no Hello within " +
        std::to_string(self->context_.options.hello_timeout_ms) + " ms (--hello-timeout-ms)");
    self->send_error(0, v1::ERROR_CODE_HELLO_REQUIRED,
                     "no Hello within " + std::to_string(self->context_.options.hello_timeout_ms) +
                         " ms; the connection closes");
    self->close_after_replies();
  });
}

void Session::reject(v1::ErrorCode code, const std::string& message) {
  hold_while_busy();  // the refusal is written before the session goes
  asio::dispatch(transport_->executor(), [self = shared_from_this(), code, message] {
    self->send_error(0, code, message);
    self->close_after_replies();
  });
}

void Session::close() {
  post([self = shared_from_this()] { self->shutdown(false); });
}

void Session::close_gracefully() {
  post([self = shared_from_this()] {
    if (self->closed_) return;
    v1::ServerMessage goodbye;
    v1::SceneEvent& event = *goodbye.mutable_event();
    event.set_scene_id(self->scene_id_.value());
    event.set_kind(v1::EVENT_KIND_SERVER_SHUTDOWN);
    self->send(goodbye);
    self->close_after_replies();
  });
}

void Session::shutdown(bool gracefully) {
  if (closed_) return;
  closed_ = true;
  hello_timer_.cancel();
  rate_timer_.cancel();
  frames_.stop();
  outbound_.stop();
  if (gracefully) {
    transport_->finish();
  } else {
    transport_->close();
  }
  leave_scene();
  if (counted_) {
    counted_ = false;
    --context_.clients;
  }
  if (!greeted_) {
    context_.log.debug("connection from " + transport_->peer() + " closed before Hello");
    return;
  }
  std::string left = who() + " from " + transport_->peer() + " left after " +
                     std::to_string(requests_) + " requests";
  if (refusals_not_logged_ > 0) {
    left += " (" + std::to_string(refusals_not_logged_) + " more refusals not logged)";
  }
  context_.log.info(left);
}

void Session::on_backlog_exceeded(std::size_t max_backlog_bytes) {
  context_.log.warning(who() + " from " + transport_->peer() + " dropped: more than " +
                       std::to_string(max_backlog_bytes) +
                       " bytes of replies unread (--max-reply-backlog)");
  shutdown(false);
}

std::string Session::who() const {
  std::string text = "client " + std::to_string(id_.value());
  if (greeted_) text += " \"" + client_name_ + "\"";
  return text;
}

void Session::log_refusal(const std::string& what) {
  const auto now = SteadyClock::now();
  if (now - last_refusal_logged_ < kRefusalLogInterval) {
    ++refusals_not_logged_;
    return;
  }
  std::string line = who() + " from " + transport_->peer() + " refused: " + what;
  if (refusals_not_logged_ > 0) {
    line += " (and " + std::to_string(refusals_not_logged_) + " more not logged)";
  }
  context_.log.warning(line);
  last_refusal_logged_ = now;
  refusals_not_logged_ = 0;
}

void Session::read() {
  transport_->receive([self = shared_from_this()](const boost::system::error_code& ec,
                                                  std::size_t bytes) { self->on_read(ec, bytes); });
}

void Session::on_read(const boost::system::error_code& ec, std::size_t bytes) {
  if (ec || closed_) {
    shutdown(false);
    return;
  }
  bytes_received_ += bytes;
  process();
}

void Session::process() {
  for (int handled = 0; !outbound_.closing() && !closed_; ++handled) {
    if (handled == kRequestsPerTurn) {
      post([self = shared_from_this()] { self->process(); });
      return;
    }
    if (const auto wait = rate_.wait(RequestRate::Clock::now()); wait.count() > 0) {
      process_after(wait);
      return;
    }
    const wire::DecodeResult frame = transport_->next();
    if (frame.status == wire::DecodeStatus::kNeedMore) break;
    if (frame.status == wire::DecodeStatus::kTooLarge) {
      const std::string limit = std::to_string(context_.options.max_inbound_frame_bytes);
      // a WebSocket message's size is known only as far as it was read
      send_error(0, v1::ERROR_CODE_FRAME_TOO_LARGE,
                 frame.announced_length > 0 ? "frame of " + std::to_string(frame.announced_length) +
                                                  " bytes exceeds the limit of " + limit
                                            : "a message over the limit of " + limit + " bytes");
      close_after_replies();  // the error goes out, then the connection closes
      break;
    }
    v1::ClientMessage message;
    if (frame.status == wire::DecodeStatus::kBadPrefix ||
        !wire::parse_message(frame.payload, message)) {
      send_error(0, v1::ERROR_CODE_MALFORMED_FRAME, "bytes that are not a felt.v1.ClientMessage");
      close_after_replies();
      break;
    }
    rate_.take();
    ++requests_;
    dispatch(*this, message);
  }
  if (closed_ || outbound_.closing()) return;
  read();
}

void Session::process_after(RequestRate::Clock::duration wait) {
  if (!rate_logged_) {
    rate_logged_ = true;
    context_.log.warning(who() + " from " + transport_->peer() + " sends more than " +
                         std::to_string(static_cast<long long>(context_.options.max_request_rate)) +
                         " requests a second (--max-request-rate): they are read at that rate");
  }
  rate_timer_.expires_after(wait);
  rate_timer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (!ec && !self->closed_) self->process();
  });
}

void Session::send(const v1::ServerMessage& message) {
  if (closed_) return;
  outbound_.push(message);
}

void Session::send_error(std::uint64_t request_id, v1::ErrorCode code, const std::string& text) {
  if (refuses_a_limit(code)) log_refusal(text + " (" + code_name(code) + ")");
  v1::ServerMessage reply;
  fill_error(request_id, code, text, reply);
  send(reply);
}

void Session::close_after_replies() {
  frames_.drop_pending();
  outbound_.close_after_queued();
}

std::shared_ptr<PendingReply> Session::defer(std::uint64_t request_id) {
  if (in_flight_.load() >= context_.options.max_requests_in_flight) return nullptr;
  return std::make_shared<PendingReply>(shared_from_this(), request_id);
}

void Session::end_deferred(const v1::ServerMessage& reply) {
  --in_flight_;
  if (reply.has_error() && refuses_a_limit(reply.error().code())) {
    log_refusal(reply.error().message() + " (" + code_name(reply.error().code()) + ")");
  }
  send(reply);
}

void Session::on_frame_written() {
  frames_.written();
  ++frames_sent_;
}

Session::Counters Session::counters() const {
  return {requests_, frames_sent_, frames_.skipped(), outbound_.bytes_sent(), bytes_received_};
}

void Session::set_greeted(std::string client_name) {
  const bool first = !greeted_;
  greeted_ = true;
  hello_timer_.cancel();
  client_name_ = std::move(client_name);
  if (first) context_.log.info(who() + " connected from " + transport_->peer());
  // a client is in the server's default scene from its first Hello: before it, it hears nothing
  if (first && !scene_ && context_.default_scene != 0) join(context_.default_scene);
}

bool Session::refuse_hello() {
  return ++refused_hellos_ >= kMaxRefusedHellos;
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
  frames_.show(scene_, scene_id_);
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

void Session::forget_scene() {
  close_proxies();
  membership_.reset();
  scene_.reset();
  scene_id_ = 0;
  frames_.show(nullptr, 0);
}

void Session::leave_scene(bool quietly) {
  if (!scene_) return;
  if (!quietly) announce(SceneEvent::Kind::kClientLeft);
  const SceneId left = scene_id_;
  const std::string name = scene_->name();
  forget_scene();
  // a scene a client loaded lives as long as some session is in it
  if (context_.scenes.leave(left, id_)) {
    context_.log.info("scene " + std::to_string(left.value()) + " \"" + name +
                      "\" removed: its last client left");
  }
}

void Session::on_scene_event(SceneId scene, const SceneEvent& event) {
  // from a scene the session has left, or after its goodbye: nothing more
  if (closed_ || outbound_.closing() || scene != scene_id_) return;
  v1::ServerMessage message;
  fill_event(scene, event, *message.mutable_event());
  send(message);
  // the scene is gone from the registry already: only let go of it
  if (event.kind == SceneEvent::Kind::kDestroyed) forget_scene();
}

void Session::close_proxies() {
  proxies_.clear();
}

ProxyHandle* Session::proxy(ProxyId proxy_id) {
  const auto it = proxies_.find(proxy_id);
  if (it != proxies_.end()) return &it->second;
  if (proxies_.size() >= context_.options.max_proxies_per_session) return nullptr;
  return &proxies_.emplace(proxy_id, scene_->open_proxy({id_, proxy_id})).first->second;
}

ProxyId Session::open_proxy(const ProxySettings& settings) {
  if (proxies_.size() >= context_.options.max_proxies_per_session) return 0;
  std::uint32_t id = 1;
  while (proxies_.contains(id)) ++id;
  proxies_.emplace(id, scene_->open_proxy({id_, id}, settings));
  return id;
}

bool Session::close_proxy(ProxyId proxy_id) {
  const auto it = proxies_.find(proxy_id);
  if (it == proxies_.end()) return false;
  proxies_.erase(it);
  return true;
}

void Session::forget_idle_proxy_surfaces(SteadyClock::time_point now) {
  for (auto& [id, proxy] : proxies_) proxy.forget_surface_if_idle(now, kProxyIdle);
}

}  // namespace felt::net
