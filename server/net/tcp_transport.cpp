#include "net/tcp_transport.hpp"

#include <boost/asio/write.hpp>

#include "net/endpoint_text.hpp"

namespace felt::net {

namespace asio = boost::asio;

TcpTransport::TcpTransport(asio::ip::tcp::socket socket, std::size_t max_message_bytes)
    : socket_(std::move(socket)), executor_(socket_.get_executor()), decoder_(max_message_bytes) {
  // send() writes from the handler that has something to send, and must never wait; a socket
  // that cannot be made so is closed, and the session ends at its first read
  boost::system::error_code ec;
  const auto remote = socket_.remote_endpoint(ec);
  peer_ = (ec ? std::string("a closed connection") : endpoint_text(remote)) + " over TCP";
  socket_.non_blocking(true, ec);
  if (ec) socket_.close(ec);
}

void TcpTransport::receive(ReadHandler done) {
  socket_.async_read_some(
      asio::buffer(read_buffer_),
      [this, done = std::move(done)](const boost::system::error_code& ec, std::size_t bytes) {
        if (!ec) decoder_.feed(std::span(read_buffer_.data(), bytes));
        done(ec, bytes);
      });
}

bool TcpTransport::send(const std::string& frames, WriteHandler done,
                        boost::system::error_code& ec) {
  // what the kernel takes at once is done here: a write left to finish in a completion handler
  // would hold the next ForceUpdate until that handler's thread gets a core (with the physics
  // thread busy, up to a millisecond: the outbound leg's tail)
  std::size_t written = socket_.write_some(asio::buffer(frames), ec);
  if (ec == asio::error::would_block || ec == asio::error::try_again) {
    ec = {};
    written = 0;
  }
  if (ec || written == frames.size()) return true;
  asio::async_write(socket_, asio::buffer(frames) + written,
                    [done = std::move(done)](const boost::system::error_code& error, std::size_t) {
                      done(error);
                    });
  return false;
}

void TcpTransport::close() {
  boost::system::error_code ignored;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
}

}  // namespace felt::net
