#pragma once
// Accepts connections, on the TCP port and (with --web) the web port, and owns the list of live
// sessions, whatever their transport.

#include <cstdint>
#include <expected>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <boost/asio.hpp>

#include "net/io_pool.hpp"
#include "net/server_context.hpp"
#include "net/transport.hpp"
#include "net/web_listener.hpp"

namespace felt::net {

class Session;

class Server {
 public:
  /// Accepts on the pool's main io_context and serves each connection on the next in turn.
  Server(IoPool& io, ServerContext& context);

  /// Binds and starts accepting; port 0 picks a free port. Returns the bound endpoint.
  std::expected<boost::asio::ip::tcp::endpoint, std::string> listen(const std::string& host,
                                                                    std::uint16_t port);
  /// Serves the page's files from `page_root` and WebSocket sessions at /ws on HOST:PORT; port
  /// 0 picks a free port. Returns the bound endpoint.
  std::expected<boost::asio::ip::tcp::endpoint, std::string> listen_web(
      const std::string& host, std::uint16_t port, const std::filesystem::path& page_root);
  /// Stops accepting, tells every session's client that the server stops and closes the
  /// session once what it has queued is written (client_count() falls to 0 as they finish).
  void shutdown();
  /// Closes every session at once (after shutdown(), for those that did not finish in time).
  void close_all();
  /// Sessions whose connection is still open.
  std::size_t client_count();

 private:
  void accept();
  /// Serves a new connection as a session, or refuses it past --max-clients (on its strand).
  void admit(std::unique_ptr<Transport> transport);
  /// Forgets the sessions that ended and returns the others; the caller holds sessions_mutex_.
  std::vector<std::shared_ptr<Session>> live_sessions();

  IoPool& io_;
  ServerContext& context_;
  boost::asio::ip::tcp::acceptor acceptor_;
  std::unique_ptr<WebListener> web_;
  std::mutex sessions_mutex_;
  std::vector<std::weak_ptr<Session>> sessions_;
  bool shutting_down_ = false;  ///< shutdown() ran: new sessions are told goodbye at once
};

}  // namespace felt::net
