#include "support/websocket_client.hpp"

#include <boost/asio/connect.hpp>
#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/websocket.hpp>

#include "felt_client.hpp"

namespace felt::test {

namespace asio = boost::asio;
namespace websocket = boost::beast::websocket;
namespace v1 = felt::v1;
using client::ClientError;

WebSocketClient::WebSocketClient() : stream_(io_) {}

WebSocketClient::~WebSocketClient() {
  boost::system::error_code ignored;
  stream_.next_layer().close(ignored);
}

void WebSocketClient::connect(const std::string& host, std::uint16_t port,
                              const std::string& origin) {
  try {
    asio::ip::tcp::resolver resolver(io_);
    asio::connect(stream_.next_layer(), resolver.resolve(host, std::to_string(port)));
    stream_.next_layer().set_option(asio::ip::tcp::no_delay(true));
    if (!origin.empty()) {
      stream_.set_option(websocket::stream_base::decorator(
          [origin](websocket::request_type& request) { request.set("Origin", origin); }));
    }
    stream_.handshake(host + ":" + std::to_string(port), "/ws");
    stream_.binary(true);
    stream_.read_message_max(256u << 20);
  } catch (const boost::system::system_error& e) {
    throw ClientError(v1::ERROR_CODE_UNSPECIFIED, std::string("WebSocket: ") + e.what());
  }
}

std::uint64_t WebSocketClient::send(v1::ClientMessage& message) {
  message.set_request_id(next_request_id_++);
  send_raw(message.SerializeAsString());
  return message.request_id();
}

void WebSocketClient::send_raw(const std::string& bytes, bool binary) {
  stream_.binary(binary);
  boost::system::error_code ec;
  stream_.write(asio::buffer(bytes), ec);
  stream_.binary(true);
  if (ec) throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "connection lost: " + ec.message());
}

std::optional<v1::ServerMessage> WebSocketClient::receive(std::chrono::milliseconds timeout) {
  if (!reading_) {
    reading_ = true;
    read_done_ = false;
    stream_.async_read(buffer_, [this](const boost::system::error_code& ec, std::size_t) {
      read_error_ = ec;
      read_done_ = true;
    });
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  io_.restart();
  while (!read_done_ && io_.run_one_until(deadline) > 0) {
  }
  if (!read_done_) return std::nullopt;  // the read stays under way for the next call
  reading_ = false;
  if (read_error_) {
    close_code_ = static_cast<std::uint16_t>(stream_.reason().code);
    throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "connection lost: " + read_error_.message());
  }
  v1::ServerMessage message;
  const std::string bytes = boost::beast::buffers_to_string(buffer_.data());
  buffer_.consume(buffer_.size());
  if (!stream_.got_binary() || !message.ParseFromString(bytes)) {
    throw ClientError(v1::ERROR_CODE_MALFORMED_FRAME, "the server sent a malformed message");
  }
  return message;
}

v1::ServerMessage WebSocketClient::request(v1::ClientMessage& message,
                                           std::chrono::milliseconds timeout) {
  const std::uint64_t id = send(message);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    auto reply = receive(std::max(left, std::chrono::milliseconds(0)));
    if (!reply) break;
    if (reply->has_error() && (reply->request_id() == id || reply->request_id() == 0)) {
      throw ClientError(reply->error());
    }
    if (reply->request_id() == id) return *reply;
  }
  throw ClientError(v1::ERROR_CODE_UNSPECIFIED, "no reply within the timeout");
}

v1::Welcome WebSocketClient::hello(const std::string& client_name, const std::string& token) {
  v1::ClientMessage message;
  message.mutable_hello()->set_protocol_version(1);
  message.mutable_hello()->set_client_name(client_name);
  message.mutable_hello()->set_token(token);
  auto reply = request(message);
  client::check_reply(reply, v1::ServerMessage::kWelcome);
  return reply.welcome();
}

v1::Stats WebSocketClient::stats() {
  v1::ClientMessage message;
  message.mutable_get_stats();
  auto reply = request(message);
  client::check_reply(reply, v1::ServerMessage::kStats);
  return reply.stats();
}

v1::ForceUpdate WebSocketClient::proxy_update(std::uint32_t proxy_id,
                                              const std::array<double, 3>& position,
                                              std::uint32_t buttons) {
  v1::ClientMessage message;
  v1::ProxyUpdate& update = *message.mutable_proxy_update();
  update.set_proxy_id(proxy_id);
  update.mutable_position()->set_x(position[0]);
  update.mutable_position()->set_y(position[1]);
  update.mutable_position()->set_z(position[2]);
  update.set_buttons(buttons);
  update.set_client_time_us(client::steady_microseconds());
  auto reply = request(message);
  client::check_reply(reply, v1::ServerMessage::kForceUpdate);
  return reply.force_update();
}

}  // namespace felt::test
