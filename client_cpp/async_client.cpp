#include "async_client.hpp"

#include <cerrno>
#include <future>

#include <sys/socket.h>

#include "wire/message_codec.hpp"

namespace felt::client {

namespace asio = boost::asio;
namespace v1 = felt::v1;
using asio::ip::tcp;

namespace {

constexpr std::size_t kMaxInboundFrameBytes = 256u << 20;

}  // namespace

AsyncClient::AsyncClient() : socket_(io_), decoder_(kMaxInboundFrameBytes) {
  ended_.set_message("not connected");
}

AsyncClient::~AsyncClient() {
  close();
}

v1::Welcome AsyncClient::connect(const std::string& host, std::uint16_t port,
                                 const std::string& client_name, const std::string& token,
                                 std::chrono::milliseconds timeout) {
  boost::system::error_code ec;
  tcp::resolver resolver(io_);
  const auto endpoints = resolver.resolve(host, std::to_string(port), ec);
  if (!ec) asio::connect(socket_, endpoints, ec);
  if (ec) {
    throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "cannot connect to " + host + ":" +
                                                      std::to_string(port) + ": " + ec.message());
  }
  socket_.set_option(tcp::no_delay(true));
  {
    std::lock_guard lock(write_mutex_);
    open_ = true;
  }
  connected_ = true;
  read();
  thread_ = std::thread([this] { io_.run(); });
  v1::ClientMessage message;
  v1::Hello* hello = message.mutable_hello();
  hello->set_protocol_version(1);
  hello->set_client_name(client_name);
  hello->set_token(token);
  const v1::ServerMessage reply = request(std::move(message), timeout);
  check_reply(reply, v1::ServerMessage::kWelcome);
  return reply.welcome();
}

void AsyncClient::close() {
  if (thread_.joinable()) {
    asio::post(io_, [this] {
      closing_ = true;
      std::lock_guard lock(write_mutex_);
      open_ = false;
      boost::system::error_code ignored;
      socket_.shutdown(tcp::socket::shutdown_both, ignored);
      socket_.close(ignored);  // the pending read ends, and with it the connection
    });
    thread_.join();
  }
  connected_ = false;
}

std::uint64_t AsyncClient::send(v1::ClientMessage message, ReplyHandler on_reply) {
  const std::uint64_t id = next_request_id_++;
  message.set_request_id(id);
  if (on_reply) {
    std::unique_lock lock(handlers_mutex_);
    if (!connected_) {
      v1::ServerMessage reply;
      reply.set_request_id(id);
      *reply.mutable_error() = ended_;
      reply.mutable_error()->set_request_id(id);
      lock.unlock();
      on_reply(reply);
      return id;
    }
    handlers_.emplace(id, std::move(on_reply));
  }
  std::string bytes;
  wire::append_message(bytes, message);
  write(std::move(bytes));
  return id;
}

void AsyncClient::write(std::string bytes) {
  std::lock_guard lock(write_mutex_);
  if (!open_) return;
  if (outbox_.empty()) {
    // a plain non-blocking send on the descriptor: the client's thread only reads meanwhile
    const ssize_t sent =
        ::send(socket_.native_handle(), bytes.data(), bytes.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    if (sent == static_cast<ssize_t>(bytes.size())) return;
    if (sent < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
      open_ = false;  // the pending read fails too and ends the connection
      return;
    }
    bytes.erase(0, sent < 0 ? 0 : static_cast<std::size_t>(sent));
    outbox_.push_back(std::move(bytes));
    asio::post(io_, [this] { write_next(); });
    return;
  }
  outbox_.push_back(std::move(bytes));
}

void AsyncClient::send_proxy_update(std::uint32_t proxy_id, const Point& position,
                                    std::uint32_t buttons) {
  v1::ClientMessage message;
  v1::ProxyUpdate* update = message.mutable_proxy_update();
  update->set_proxy_id(proxy_id);
  update->mutable_position()->set_x(position[0]);
  update->mutable_position()->set_y(position[1]);
  update->mutable_position()->set_z(position[2]);
  update->set_buttons(buttons);
  update->set_client_time_us(steady_microseconds());
  send(std::move(message));
}

v1::ServerMessage AsyncClient::request(v1::ClientMessage message,
                                       std::chrono::milliseconds timeout) {
  auto promise = std::make_shared<std::promise<v1::ServerMessage>>();
  auto reply = promise->get_future();
  const std::uint64_t id =
      send(std::move(message), [promise](const v1::ServerMessage& m) { promise->set_value(m); });
  if (reply.wait_for(timeout) != std::future_status::ready) {
    std::lock_guard lock(handlers_mutex_);
    handlers_.erase(id);
    throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "no reply within the timeout");
  }
  v1::ServerMessage result = reply.get();
  if (result.has_error()) throw ClientError(result.error());
  return result;
}

void AsyncClient::write_next() {
  std::lock_guard lock(write_mutex_);
  if (outbox_.empty() || !open_) return;
  // the front stays put while others are queued behind it (a deque keeps its elements)
  asio::async_write(socket_, asio::buffer(outbox_.front()),
                    [this](const boost::system::error_code& ec, std::size_t) {
                      {
                        std::lock_guard lock(write_mutex_);
                        outbox_.pop_front();
                        if (ec) {
                          open_ = false;  // what is queued can never go out
                          outbox_.clear();
                          return;
                        }
                      }
                      write_next();
                    });
}

void AsyncClient::read() {
  socket_.async_read_some(
      asio::buffer(buffer_), [this](const boost::system::error_code& ec, std::size_t n) {
        if (ec) {
          v1::Error why;
          why.set_message(closing_                 ? "the connection was closed"
                          : ec == asio::error::eof ? "the server closed the connection"
                                                   : "the connection failed: " + ec.message());
          end(why);
          return;
        }
        decoder_.feed(std::span<const std::uint8_t>(buffer_.data(), n));
        while (true) {
          const wire::DecodeResult frame = decoder_.next();
          if (frame.status == wire::DecodeStatus::kNeedMore) break;
          v1::ServerMessage message;
          if (frame.status != wire::DecodeStatus::kFrame ||
              !wire::parse_message(frame.payload, message)) {
            v1::Error why;
            why.set_code(v1::ERROR_CODE_MALFORMED_FRAME);
            why.set_message("the server sent a malformed message");
            end(why);
            return;
          }
          deliver(message);
        }
        read();
      });
}

void AsyncClient::deliver(v1::ServerMessage& message) {
  if (message.has_frame()) {
    if (on_frame_) on_frame_(message.frame());
    return;
  }
  if (message.has_event()) {
    if (on_event_) on_event_(message.event());
    return;
  }
  ReplyHandler handler;
  {
    std::lock_guard lock(handlers_mutex_);
    const auto it = handlers_.find(message.request_id());
    if (it != handlers_.end()) {
      handler = std::move(it->second);
      handlers_.erase(it);
    }
  }
  if (handler) {
    handler(message);
  } else if (message.has_force_update()) {
    if (on_force_) on_force_(message.force_update(), steady_microseconds());
  } else if (message.has_error()) {
    if (message.request_id() == 0) last_word_ = message.error();
    if (on_error_) on_error_(message.error());
  }
}

void AsyncClient::end(const v1::Error& why) {
  {
    std::lock_guard lock(write_mutex_);
    open_ = false;
    boost::system::error_code ignored;
    socket_.close(ignored);
  }
  // the server's last Error says better why than the closed socket
  const v1::Error& reason = last_word_ ? *last_word_ : why;
  std::unordered_map<std::uint64_t, ReplyHandler> waiting;
  {
    // send() checks connected_ under this lock: a request is either waiting here or told at once
    std::lock_guard lock(handlers_mutex_);
    connected_ = false;
    ended_ = reason;
    waiting.swap(handlers_);
  }
  v1::ServerMessage reply;
  *reply.mutable_error() = reason;
  for (auto& [id, handler] : waiting) {
    reply.set_request_id(id);
    reply.mutable_error()->set_request_id(id);
    handler(reply);
  }
  if (!closing_ && !last_word_ && on_error_) on_error_(why);
}

}  // namespace felt::client
