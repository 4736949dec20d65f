#pragma once
// felt.v1 over plain TCP: each message behind its varint length (protocol/wire/frame_codec.hpp).

#include <array>

#include <boost/asio/ip/tcp.hpp>

#include "net/transport.hpp"

namespace felt::net {

class TcpTransport final : public Transport {
 public:
  /// `socket` is connected and has a strand as its executor.
  TcpTransport(boost::asio::ip::tcp::socket socket, std::size_t max_message_bytes);

  const Executor& executor() const override { return executor_; }
  void receive(ReadHandler done) override;
  wire::DecodeResult next() override { return decoder_.next(); }
  bool send(const std::string& frames, WriteHandler done, boost::system::error_code& ec) override;
  void close() override;
  void finish() override { close(); }
  bool is_open() const override { return socket_.is_open(); }
  const std::string& peer() const override { return peer_; }

 private:
  boost::asio::ip::tcp::socket socket_;
  Executor executor_;
  wire::FrameDecoder decoder_;
  std::array<std::uint8_t, 16 * 1024> read_buffer_;
  std::string peer_;
};

}  // namespace felt::net
