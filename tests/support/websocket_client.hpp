#pragma once
// felt.v1 over a WebSocket, for tests and benchmarks: what a browser's page does, from C++ (Beast).
// One binary message carries one ClientMessage or ServerMessage, with no length prefix.

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/websocket/stream.hpp>

#include "felt/v1/envelope.pb.h"

namespace felt::test {

class WebSocketClient {
 public:
  WebSocketClient();
  ~WebSocketClient();

  /// Connects to ws://HOST:PORT/ws and completes the opening handshake (sending `origin` as
  /// the Origin header when not empty); throws client::ClientError on failure.
  void connect(const std::string& host, std::uint16_t port, const std::string& origin = "");

  /// Sends `message` with a fresh request id and returns the id, without waiting.
  std::uint64_t send(felt::v1::ClientMessage& message);
  /// Sends `bytes` as one message, binary or text (tests send garbage this way).
  void send_raw(const std::string& bytes, bool binary = true);
  /// The next message, or nothing on timeout; throws client::ClientError when the connection
  /// has ended.
  std::optional<felt::v1::ServerMessage> receive(std::chrono::milliseconds timeout);
  /// Sends `message` and returns its reply, skipping frames and events; an Error reply (or the
  /// server's last Error, request id 0) throws client::ClientError.
  felt::v1::ServerMessage request(felt::v1::ClientMessage& message,
                                  std::chrono::milliseconds timeout = std::chrono::seconds(10));

  felt::v1::Welcome hello(const std::string& client_name, const std::string& token = "");
  felt::v1::Stats stats();
  felt::v1::ForceUpdate proxy_update(std::uint32_t proxy_id, const std::array<double, 3>& position,
                                     std::uint32_t buttons = 0);
  /// The status code of the server's closing handshake, once receive() found the end.
  std::uint16_t close_code() const { return close_code_; }

 private:
  boost::asio::io_context io_;
  boost::beast::websocket::stream<boost::asio::ip::tcp::socket> stream_;
  boost::beast::flat_buffer buffer_;
  /// a read left waiting by a receive() that timed out: the next one waits for it again
  bool reading_ = false;
  bool read_done_ = false;
  boost::system::error_code read_error_;
  std::uint64_t next_request_id_ = 1;
  std::uint16_t close_code_ = 0;
};

}  // namespace felt::test
