#pragma once
// One browser connection to the web port: HTTP GETs of the page's files (keep-alive), until it
// asks to become a WebSocket at /ws; then it is handed over as a Transport and served as a
// session like any other.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http.hpp>

#include "net/transport.hpp"

namespace felt::net {

/// Where the web port's connections come from and go to.
struct WebSettings {
  std::filesystem::path page_root;    ///< the page's build folder: the only files served
  std::size_t max_message_bytes = 0;  ///< the sessions' inbound limit (--max-frame-bytes)
  /// takes a connection that became a WebSocket, on its strand
  std::function<void(std::unique_ptr<Transport>)> admit;
};

class HttpConnection : public std::enable_shared_from_this<HttpConnection> {
 public:
  /// `socket` has a strand as its executor; `settings` outlives the connection.
  HttpConnection(boost::asio::ip::tcp::socket socket, const WebSettings& settings);
  void start();

 private:
  using Request = boost::beast::http::request<boost::beast::http::string_body>;
  using Response = boost::beast::http::response<boost::beast::http::string_body>;

  void read();
  void on_request();
  void respond(Response response);
  /// The request asks for a WebSocket at /ws: hands the connection over after the handshake.
  void upgrade();

  boost::beast::tcp_stream stream_;
  const WebSettings& settings_;
  boost::beast::flat_buffer buffer_;
  std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
  Response response_;
};

}  // namespace felt::net
