#include "net/web_listener.hpp"

#include "net/bind_acceptor.hpp"

namespace felt::net {

namespace asio = boost::asio;
using asio::ip::tcp;

WebListener::WebListener(IoPool& io, WebSettings settings)
    : io_(io), settings_(std::move(settings)), acceptor_(asio::make_strand(io.main())) {}

std::expected<tcp::endpoint, std::string> WebListener::listen(const std::string& host,
                                                              std::uint16_t port) {
  auto endpoint = bind_acceptor(acceptor_, host, port);
  if (endpoint) accept();
  return endpoint;
}

void WebListener::accept() {
  acceptor_.async_accept(asio::make_strand(io_.next()), [this](const boost::system::error_code& ec,
                                                               tcp::socket socket) {
    if (ec == asio::error::operation_aborted || !acceptor_.is_open()) return;
    if (!ec) {
      boost::system::error_code ignored;
      socket.set_option(tcp::no_delay(true), ignored);  // a ForceUpdate must not wait for Nagle
      std::make_shared<HttpConnection>(std::move(socket), settings_)->start();
    }
    accept();
  });
}

void WebListener::close() {
  // on the acceptor's strand, never while its handler runs on another thread
  asio::post(acceptor_.get_executor(), [this] {
    boost::system::error_code ignored;
    acceptor_.close(ignored);
  });
}

}  // namespace felt::net
