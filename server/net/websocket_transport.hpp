#pragma once
// felt.v1 over a WebSocket: one binary message carries one message, with no length prefix
// (the WebSocket frames it). Browsers reach feltd this way (the page, web/).

#include <memory>
#include <string>
#include <vector>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/websocket/stream.hpp>

#include "net/transport.hpp"

namespace felt::net {

class WebSocketTransport final : public Transport {
 public:
  using Stream = boost::beast::websocket::stream<boost::asio::ip::tcp::socket>;

  /// `stream` has completed its opening handshake; its socket has a strand as its executor.
  /// A message larger than `max_message_bytes` is refused the way TCP refuses one (kTooLarge),
  /// after at most that many bytes of it were read.
  WebSocketTransport(std::unique_ptr<Stream> stream, std::size_t max_message_bytes);

  const Executor& executor() const override { return executor_; }
  void receive(ReadHandler done) override;
  wire::DecodeResult next() override;
  bool send(const std::string& frames, WriteHandler done, boost::system::error_code& ec) override;
  void close() override;
  void finish() override;
  bool is_open() const override { return stream_->is_open(); }
  const std::string& peer() const override { return peer_; }

 private:
  /// Sends the frame at `offset` of `frames`, then the ones after it.
  void send_from(const std::string& frames, std::size_t offset);

  /// shared with a closing handshake that may outlive the transport
  std::shared_ptr<Stream> stream_;
  Executor executor_;
  std::size_t max_message_bytes_;
  std::vector<std::uint8_t> message_;  ///< the message being read, or read and not yet taken
  bool message_done_ = false;
  bool message_taken_ = false;
  wire::DecodeStatus failure_ = wire::DecodeStatus::kNeedMore;
  WriteHandler write_done_;
  std::string peer_;
};

}  // namespace felt::net
