#include "fake_server.hpp"

#include "wire/message_codec.hpp"

namespace felt::test {

namespace asio = boost::asio;
namespace v1 = felt::v1;
using asio::ip::tcp;

FakeServer::FakeServer(Responder responder)
    : responder_(std::move(responder)),
      acceptor_(io_, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)),
      socket_(io_) {
  port_ = acceptor_.local_endpoint().port();
  acceptor_.async_accept(socket_, [this](const boost::system::error_code& ec) {
    if (!ec) read();
  });
  thread_ = std::thread([this] { io_.run(); });
}

FakeServer::~FakeServer() {
  io_.stop();
  thread_.join();
}

void FakeServer::read() {
  socket_.async_read_some(
      asio::buffer(buffer_), [this](const boost::system::error_code& ec, std::size_t n) {
        if (ec) return;
        decoder_.feed(std::span<const std::uint8_t>(buffer_.data(), n));
        for (wire::DecodeResult frame = decoder_.next(); frame.status == wire::DecodeStatus::kFrame;
             frame = decoder_.next()) {
          v1::ClientMessage request;
          if (!wire::parse_message(frame.payload, request)) return;
          const FakeAnswer answer = responder_(request);
          std::string bytes;
          for (const v1::ServerMessage& message : answer.messages)
            wire::append_message(bytes, message);
          boost::system::error_code written;
          asio::write(socket_, asio::buffer(bytes), written);
          if (written || answer.close) {
            socket_.close(written);
            return;
          }
        }
        read();
      });
}

}  // namespace felt::test
