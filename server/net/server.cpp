#include "net/server.hpp"

#include <algorithm>

#include "net/session.hpp"

namespace felt::net {

namespace asio = boost::asio;
using asio::ip::tcp;

Server::Server(IoPool& io, ServerContext& context)
    : io_(io), context_(context), acceptor_(asio::make_strand(io.main())) {}

std::expected<tcp::endpoint, std::string> Server::listen(const std::string& host,
                                                         std::uint16_t port) {
  boost::system::error_code ec;
  tcp::resolver resolver(io_.main());
  const auto results = resolver.resolve(
      host, std::to_string(port), tcp::resolver::numeric_service | tcp::resolver::passive, ec);
  if (ec || results.empty()) return std::unexpected("cannot resolve " + host + ": " + ec.message());
  const tcp::endpoint endpoint = results.begin()->endpoint();
  acceptor_.open(endpoint.protocol(), ec);
  if (!ec) acceptor_.set_option(tcp::acceptor::reuse_address(true), ec);
  if (!ec) acceptor_.bind(endpoint, ec);
  if (!ec) acceptor_.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    return std::unexpected("cannot listen on " + endpoint.address().to_string() + ":" +
                           std::to_string(port) + ": " + ec.message());
  }
  accept();
  return acceptor_.local_endpoint();
}

void Server::accept() {
  // each connection gets its own strand on the next network thread's io_context: its
  // handlers never run concurrently, and all on that thread
  acceptor_.async_accept(asio::make_strand(io_.next()), [this](const boost::system::error_code& ec,
                                                               tcp::socket socket) {
    if (ec == asio::error::operation_aborted || !acceptor_.is_open()) return;
    if (!ec) {
      socket.set_option(tcp::no_delay(true));  // a ForceUpdate must not wait for Nagle
      auto session = std::make_shared<Session>(std::move(socket), context_);
      if (context_.clients.load() >= context_.options.max_clients) {
        session->reject(felt::v1::ERROR_CODE_LIMIT_EXCEEDED,
                        "the server already serves " +
                            std::to_string(context_.options.max_clients) +
                            " clients (--max-clients)");
      } else {
        std::lock_guard lock(sessions_mutex_);
        std::erase_if(sessions_, [](const std::weak_ptr<Session>& s) { return s.expired(); });
        sessions_.push_back(session);
        session->start();
        // accepted while shutdown() went through the sessions: it hears the goodbye too
        if (shutting_down_) session->close_gracefully();
      }
    }
    accept();
  });
}

void Server::shutdown() {
  // the acceptor is closed on its own strand, never while its handler runs on another thread
  asio::post(acceptor_.get_executor(), [this] {
    boost::system::error_code ignored;
    acceptor_.close(ignored);
  });
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
