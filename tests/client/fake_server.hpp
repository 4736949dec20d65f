#pragma once
// A server that answers each request as a test says, on loopback port 0: for what feltd never
// sends (a reply of the wrong kind), to check how a client takes it.

#include <array>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

#include <boost/asio.hpp>

#include "felt/v1/envelope.pb.h"
#include "wire/frame_codec.hpp"

namespace felt::test {

/// What the fake server sends for one request; it hangs up after it when `close` is set.
struct FakeAnswer {
  std::vector<felt::v1::ServerMessage> messages;
  bool close = false;
};

class FakeServer {
 public:
  using Responder = std::function<FakeAnswer(const felt::v1::ClientMessage&)>;

  /// Listens at once; serves one connection on a thread of its own until either side closes
  /// or the server is destroyed.
  explicit FakeServer(Responder responder);
  ~FakeServer();
  FakeServer(const FakeServer&) = delete;
  FakeServer& operator=(const FakeServer&) = delete;

  std::uint16_t port() const { return port_; }

 private:
  void read();

  Responder responder_;
  boost::asio::io_context io_;
  boost::asio::ip::tcp::acceptor acceptor_;
  boost::asio::ip::tcp::socket socket_;
  std::uint16_t port_ = 0;
  wire::FrameDecoder decoder_{1u << 20};
  std::array<std::uint8_t, 4096> buffer_;
  std::thread thread_;
};

}  // namespace felt::test
