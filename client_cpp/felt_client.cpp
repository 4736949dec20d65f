#include "felt_client.hpp"

#include <algorithm>

#include <google/protobuf/descriptor.h>

#include "wire/message_codec.hpp"

namespace felt::client {

namespace asio = boost::asio;
namespace v1 = felt::v1;
using asio::ip::tcp;

namespace {

// Frames kept while the caller is busy with requests; older ones are dropped (latest wins,
// as on the server).
constexpr std::size_t kMaxBufferedFrames = 64;
constexpr std::size_t kMaxBufferedEvents = 256;
// Replies the server may send are bounded by its own limits; this only stops a broken peer.
constexpr std::size_t kMaxInboundFrameBytes = 256u << 20;

/// Runs `io` until `done` or `deadline`; on timeout cancels `socket`'s operations and waits
/// for their handlers. Returns whether `done` was reached.
bool run_until(asio::io_context& io, tcp::socket& socket, const bool& done,
               std::chrono::steady_clock::time_point deadline) {
  io.restart();
  while (!done && io.run_one_until(deadline) > 0) {
  }
  if (done) return true;
  boost::system::error_code ignored;
  socket.cancel(ignored);
  io.restart();
  io.run();
  return done;
}

}  // namespace

Client::Client() : socket_(io_), decoder_(kMaxInboundFrameBytes) {}

Client::~Client() {
  close();
}

void Client::connect(const std::string& host, std::uint16_t port,
                     std::chrono::milliseconds timeout) {
  boost::system::error_code ec;
  tcp::resolver resolver(io_);
  const auto endpoints = resolver.resolve(host, std::to_string(port), ec);
  if (ec)
    throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "cannot resolve " + host + ": " + ec.message());
  bool done = false;
  asio::async_connect(socket_, endpoints,
                      [&](const boost::system::error_code& result, const tcp::endpoint&) {
                        ec = result;
                        done = true;
                      });
  if (!run_until(io_, socket_, done, std::chrono::steady_clock::now() + timeout) || ec) {
    throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "cannot connect to " + host + ":" +
                                                      std::to_string(port) +
                                                      (ec ? ": " + ec.message() : ": timed out"));
  }
  socket_.set_option(tcp::no_delay(true));
}

void Client::close() {
  boost::system::error_code ignored;
  socket_.shutdown(tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
}

void Client::send_raw(const std::string& bytes) {
  boost::system::error_code ec;
  asio::write(socket_, asio::buffer(bytes), ec);
  if (ec) throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "send failed: " + ec.message());
}

std::optional<v1::ServerMessage> Client::receive(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    const wire::DecodeResult frame = decoder_.next();
    if (frame.status == wire::DecodeStatus::kFrame) {
      v1::ServerMessage message;
      if (!wire::parse_message(frame.payload, message)) {
        throw ClientError(v1::ERROR_CODE_MALFORMED_FRAME, "the server sent a malformed message");
      }
      return message;
    }
    if (frame.status != wire::DecodeStatus::kNeedMore) {
      throw ClientError(v1::ERROR_CODE_MALFORMED_FRAME, "the server sent a malformed frame");
    }
    bool done = false;
    boost::system::error_code ec;
    std::size_t received = 0;
    socket_.async_read_some(asio::buffer(buffer_),
                            [&](const boost::system::error_code& result, std::size_t n) {
                              ec = result;
                              received = n;
                              done = true;
                            });
    if (!run_until(io_, socket_, done, deadline) || ec == asio::error::operation_aborted) {
      if (received > 0) decoder_.feed(std::span<const std::uint8_t>(buffer_.data(), received));
      return std::nullopt;
    }
    if (ec) throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "connection lost: " + ec.message());
    decoder_.feed(std::span<const std::uint8_t>(buffer_.data(), received));
  }
}

std::uint64_t Client::send(v1::ClientMessage& message) {
  const std::uint64_t id = next_request_id_++;
  message.set_request_id(id);
  std::string bytes;
  wire::append_message(bytes, message);
  send_raw(bytes);
  return id;
}

v1::ServerMessage Client::request(v1::ClientMessage& message) {
  const std::uint64_t id = send(message);
  const auto deadline = std::chrono::steady_clock::now() + reply_timeout_;
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    auto reply = receive(std::max(left, std::chrono::milliseconds(0)));
    if (!reply) throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "no reply within the timeout");
    if (keep_streamed(*reply)) continue;
    // the server's last word: it closes the connection, so the reply will never come
    if (reply->has_error() && reply->request_id() == 0) throw ClientError(reply->error());
    if (reply->request_id() != id) continue;  // a late reply to an earlier, timed-out request
    if (reply->has_error()) throw ClientError(reply->error());
    return std::move(*reply);
  }
}

v1::ServerMessage Client::request(v1::ClientMessage& message,
                                  v1::ServerMessage::BodyCase expected) {
  v1::ServerMessage reply = request(message);
  check_reply(reply, expected);
  return reply;
}

void check_reply(const v1::ServerMessage& reply, v1::ServerMessage::BodyCase expected) {
  if (reply.body_case() == expected) return;
  // the oneof's cases are its field numbers
  const auto name = [](v1::ServerMessage::BodyCase kind) {
    const auto* field = v1::ServerMessage::descriptor()->FindFieldByNumber(kind);
    return field ? field->name() : std::string("an empty message");
  };
  throw ClientError(
      v1::ERROR_CODE_UNSPECIFIED,
      "the server answered with " + name(reply.body_case()) + " instead of " + name(expected));
}

bool Client::keep_streamed(v1::ServerMessage& message) {
  if (message.has_frame()) {
    if (frames_.size() == kMaxBufferedFrames) frames_.pop_front();
    frames_.push_back(std::move(*message.mutable_frame()));
    return true;
  }
  if (message.has_event()) {
    if (events_.size() == kMaxBufferedEvents) events_.erase(events_.begin());
    events_.push_back(std::move(*message.mutable_event()));
    return true;
  }
  return false;
}

std::vector<v1::SceneEvent> Client::take_events() {
  return std::exchange(events_, {});
}

bool Client::receive_streamed(std::chrono::steady_clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
      deadline - std::chrono::steady_clock::now());
  if (left.count() <= 0) return false;
  auto message = receive(left);
  if (!message) return false;
  keep_streamed(*message);
  return true;
}

std::optional<v1::Frame> Client::next_frame(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (frames_.empty()) {
    if (!receive_streamed(deadline)) return std::nullopt;
  }
  v1::Frame frame = std::move(frames_.front());
  frames_.pop_front();
  return frame;
}

std::optional<v1::SceneEvent> Client::wait_event(v1::EventKind kind,
                                                 std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    const auto it = std::find_if(events_.begin(), events_.end(),
                                 [kind](const v1::SceneEvent& e) { return e.kind() == kind; });
    if (it != events_.end()) {
      v1::SceneEvent event = std::move(*it);
      events_.erase(it);
      return event;
    }
    if (!receive_streamed(deadline)) return std::nullopt;
  }
}

std::uint64_t steady_microseconds() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                        std::chrono::steady_clock::now().time_since_epoch())
                                        .count());
}

}  // namespace felt::client
