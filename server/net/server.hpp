#pragma once
// Accepts connections and owns the list of live sessions.

#include <cstdint>
#include <expected>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <boost/asio.hpp>

#include "net/io_pool.hpp"
#include "net/server_context.hpp"

namespace felt::net {

class Session;

class Server {
 public:
  /// Accepts on the pool's main io_context and serves each connection on the next in turn.
  Server(IoPool& io, ServerContext& context);

  /// Binds and starts accepting; port 0 picks a free port. Returns the bound endpoint.
  std::expected<boost::asio::ip::tcp::endpoint, std::string> listen(const std::string& host,
                                                                    std::uint16_t port);
  /// Stops accepting, tells every session's client that the server stops and closes the
  /// session once what it has queued is written (client_count() falls to 0 as they finish).
  void shutdown();
  /// Closes every session at once (after shutdown(), for those that did not finish in time).
  void close_all();
  /// Sessions whose connection is still open.
  std::size_t client_count();

 private:
  void accept();
  /// Forgets the sessions that ended and returns the others; the caller holds sessions_mutex_.
  std::vector<std::shared_ptr<Session>> live_sessions();

  IoPool& io_;
  ServerContext& context_;
  boost::asio::ip::tcp::acceptor acceptor_;
  std::mutex sessions_mutex_;
  std::vector<std::weak_ptr<Session>> sessions_;
  bool shutting_down_ = false;  ///< shutdown() ran: new sessions are told goodbye at once
};

}  // namespace felt::net
