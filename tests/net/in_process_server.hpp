#pragma once
// A server in this process on a free loopback port, with one network thread, serving `scene`
// as its own scene (shared and persistent, as feltd serves a --scene file) that every client
// joins at its Hello, and scenes/ as its scene directory. Stops as feltd does when destroyed.
// For tests that need to reach into the server (its frame encoder) and for the fuzz target
// that drives the request handlers.

#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "felt_client.hpp"
#include "net/io_pool.hpp"
#include "net/server.hpp"
#include "net/server_context.hpp"

namespace felt::net {

class InProcessServer {
 public:
  explicit InProcessServer(Scene scene, ServerOptions options = {});
  ~InProcessServer();
  InProcessServer(const InProcessServer&) = delete;
  InProcessServer& operator=(const InProcessServer&) = delete;

  std::uint16_t port() const { return port_; }
  /// A client connected and greeted as `name`.
  std::unique_ptr<client::Client> greeted(const std::string& name);
  ServerContext& context() { return context_; }

 private:
  SceneRegistry scenes_;
  ServerContext context_;
  IoPool io_{1};
  Server server_{io_, context_};
  std::thread thread_;
  std::uint16_t port_ = 0;
};

}  // namespace felt::net
