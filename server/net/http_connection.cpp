#include "net/http_connection.hpp"

#include <chrono>
#include <string_view>

#include <boost/asio/dispatch.hpp>
#include <fstream>
#include <sstream>

#include <boost/beast/websocket.hpp>

#include "net/page_files.hpp"
#include "net/websocket_transport.hpp"

namespace felt::net {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;

namespace {

/// An idle browser connection (or one that sends its request slowly) is closed after this.
constexpr auto kIdleTimeout = std::chrono::seconds(30);
/// The WebSocket opening handshake must be done within this.
constexpr auto kHandshakeTimeout = std::chrono::seconds(10);
constexpr std::uint32_t kMaxHeaderBytes = 8 * 1024;
constexpr std::uint64_t kMaxBodyBytes = 1024;  // the page only GETs

std::string_view view(boost::beast::string_view text) {
  return {text.data(), text.size()};
}

/// "host:port" of an Origin header ("http://host:port").
std::string_view origin_authority(std::string_view origin) {
  const std::size_t scheme = origin.find("://");
  return scheme == std::string_view::npos ? origin : origin.substr(scheme + 3);
}

}  // namespace

HttpConnection::HttpConnection(asio::ip::tcp::socket socket, const WebSettings& settings)
    : stream_(std::move(socket)), settings_(settings) {}

void HttpConnection::start() {
  asio::dispatch(stream_.get_executor(), [self = shared_from_this()] { self->read(); });
}

void HttpConnection::read() {
  parser_.emplace();
  parser_->header_limit(kMaxHeaderBytes);
  parser_->body_limit(kMaxBodyBytes);
  stream_.expires_after(kIdleTimeout);
  http::async_read(stream_, buffer_, *parser_,
                   [self = shared_from_this()](const beast::error_code& ec, std::size_t) {
                     if (ec) {
                       beast::error_code ignored;
                       self->stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_both,
                                                       ignored);
                       return;
                     }
                     self->on_request();
                   });
}

void HttpConnection::on_request() {
  const Request& request = parser_->get();
  const auto plain = [&](http::status status, std::string text) {
    Response response{status, request.version()};
    response.set(http::field::content_type, "text/plain; charset=utf-8");
    response.body() = std::move(text);
    return response;
  };
  const std::string_view target = view(request.target());
  if (target == "/ws" || target.starts_with("/ws?")) {
    if (!websocket::is_upgrade(request)) {
      return respond(plain(http::status::bad_request, "/ws is felt.v1 over a WebSocket\n"));
    }
    // a page of another site must not reach feltd through a browser on this machine
    const auto origin = request.find(http::field::origin);
    if (origin != request.end() &&
        origin_authority(view(origin->value())) != view(request[http::field::host])) {
      return respond(plain(http::status::forbidden, "a WebSocket from another origin\n"));
    }
    return upgrade();
  }
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    return respond(plain(http::status::method_not_allowed, "only GET\n"));
  }
  const std::optional<PageFile> file = page_file(settings_.page_root, target);
  std::ifstream in;
  if (file) in.open(file->path, std::ios::binary);
  if (!in.is_open()) return respond(plain(http::status::not_found, "not found\n"));
  std::ostringstream content;
  content << in.rdbuf();
  Response response{http::status::ok, request.version()};
  response.set(http::field::content_type, std::string(file->content_type));
  // the page is rebuilt in place: a browser asks again rather than run an old bundle
  response.set(http::field::cache_control, "no-cache");
  response.body() = std::move(content).str();
  respond(std::move(response));
}

void HttpConnection::respond(Response response) {
  const bool keep_alive = parser_->get().keep_alive();
  response.set(http::field::server, "feltd");
  response.set("X-Content-Type-Options", "nosniff");
  response.keep_alive(keep_alive);
  response.prepare_payload();
  // HEAD: the headers GET would have, without the body
  if (parser_->get().method() == http::verb::head) response.body().clear();
  response_ = std::move(response);
  http::async_write(
      stream_, response_,
      [self = shared_from_this(), keep_alive](const beast::error_code& ec, std::size_t) {
        if (ec || !keep_alive) {
          beast::error_code ignored;
          self->stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
          return;
        }
        self->read();
      });
}

void HttpConnection::upgrade() {
  stream_.expires_never();
  auto ws = std::make_unique<WebSocketTransport::Stream>(stream_.release_socket());
  ws->set_option(
      websocket::stream_base::timeout{kHandshakeTimeout, websocket::stream_base::none(), false});
  ws->set_option(websocket::stream_base::decorator(
      [](websocket::response_type& response) { response.set(http::field::server, "feltd"); }));
  WebSocketTransport::Stream& stream = *ws;
  stream.async_accept(parser_->get(), [self = shared_from_this(),
                                       ws = std::move(ws)](const beast::error_code& ec) mutable {
    if (ec) return;  // the client gave up or spoke something else: nothing to serve
    self->settings_.admit(
        std::make_unique<WebSocketTransport>(std::move(ws), self->settings_.max_message_bytes));
  });
}

}  // namespace felt::net
