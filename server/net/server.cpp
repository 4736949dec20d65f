#include "net/server.hpp"

#include <algorithm>

#include "net/bind_acceptor.hpp"
#include "net/session.hpp"
#include "net/tcp_transport.hpp"

namespace felt::net {

namespace asio = boost::asio;
using asio::ip::tcp;

Server::Server(IoPool& io, ServerContext& context)
    : io_(io), context_(context), acceptor_(asio::make_strand(io.main())) {}

std::expected<tcp::endpoint, std::string> Server::listen(const std::string& host,
                                                         std::uint16_t port) {
  auto endpoint = bind_acceptor(acceptor_, host, port);
  if (endpoint) accept();
  return endpoint;
}

std::expected<tcp::endpoint, std::string> Server::listen_web(
    const std::string& host, std::uint16_t port, const std::filesystem::path& page_root) {
  web_ = std::make_unique<WebListener>(
      io_,
      WebSettings{page_root, context_.options.max_inbound_frame_bytes,
                  [this](std::unique_ptr<Transport> transport) { admit(std::move(transport)); }});
  return web_->listen(host, port);
}

void Server::accept() {
  // each connection gets its own strand on the next network thread's io_context: its
  // handlers never run concurrently, and all on that thread
  acceptor_.async_accept(asio::make_strand(io_.next()), [this](const boost::system::error_code& ec,
                                                               tcp::socket socket) {
    if (ec == asio::error::operation_aborted || !acceptor_.is_open()) return;
    if (!ec) {
      socket.set_option(tcp::no_delay(true));  // a ForceUpdate must not wait for Nagle
      admit(std::make_unique<TcpTransport>(std::move(socket),
                                           context_.options.max_inbound_frame_bytes));
    }
    accept();
  });
}

void Server::admit(std::unique_ptr<Transport> transport) {
  auto session = std::make_shared<Session>(std::move(transport), context_);
  if (context_.clients.load() >= context_.options.max_clients) {
    session->reject(felt::v1::ERROR_CODE_LIMIT_EXCEEDED,
                    "the server already serves " + std::to_string(context_.options.max_clients) +
                        " clients (--max-clients)");
    return;
  }
  std::lock_guard lock(sessions_mutex_);
  std::erase_if(sessions_, [](const std::weak_ptr<Session>& s) { return s.expired(); });
  sessions_.push_back(session);
  session->start();
  // accepted while shutdown() went through the sessions: it hears the goodbye too
  if (shutting_down_) session->close_gracefully();
}

void Server::shutdown() {
  // the acceptor is closed on its own strand, never while its handler runs on another thread
  asio::post(acceptor_.get_executor(), [this] {
    boost::system::error_code ignored;
    acceptor_.close(ignored);
  });
  if (web_) web_->close();
  std::lock_guard lock(sessions_mutex_);
  shutting_down_ = true;
  for (const auto& session : live_sessions()) session->close_gracefully();
}

void Server::close_all() {
  std::lock_guard lock(sessions_mutex_);
  for (const auto& session : live_sessions()) session->close();
}

std::size_t Server::client_count() {
  std::lock_guard lock(sessions_mutex_);
  return live_sessions().size();
}

std::vector<std::shared_ptr<Session>> Server::live_sessions() {
  std::erase_if(sessions_, [](const std::weak_ptr<Session>& s) { return s.expired(); });
  std::vector<std::shared_ptr<Session>> live;
  for (const auto& weak : sessions_) {
    if (auto session = weak.lock()) live.push_back(std::move(session));
  }
  return live;
}

}  // namespace felt::net
