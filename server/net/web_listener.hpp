#pragma once
// The web port (feltd serve --web): the page's files over HTTP and felt.v1 over a WebSocket at
// /ws, each connection on the next network thread's strand.

#include <cstdint>
#include <expected>
#include <string>

#include <boost/asio/ip/tcp.hpp>

#include "net/http_connection.hpp"
#include "net/io_pool.hpp"

namespace felt::net {

class WebListener {
 public:
  WebListener(IoPool& io, WebSettings settings);

  /// Binds and starts accepting; port 0 picks a free port. Returns the bound endpoint.
  std::expected<boost::asio::ip::tcp::endpoint, std::string> listen(const std::string& host,
                                                                    std::uint16_t port);
  /// Stops accepting (from any thread).
  void close();

 private:
  void accept();

  IoPool& io_;
  WebSettings settings_;
  boost::asio::ip::tcp::acceptor acceptor_;
};

}  // namespace felt::net
