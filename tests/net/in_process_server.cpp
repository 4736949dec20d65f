#include "net/in_process_server.hpp"

#include <stdexcept>

namespace felt::net {

InProcessServer::InProcessServer(Scene scene, ServerOptions options)
    // errors only: the fuzz target would log a line for each of its many connections
    : context_{scenes_, SceneDirectory(FELT_SCENE_DIR), std::move(options), "test",
               ServerLog(LogLevel::kError)} {
  auto runner = std::make_shared<SceneRunner>(std::move(scene), SceneAccess{0, true, true});
  runner->start();
  context_.default_scene = scenes_.add(std::move(runner));
  const auto endpoint = server_.listen("127.0.0.1", 0);
  if (!endpoint) throw std::runtime_error("in-process server: " + endpoint.error());
  port_ = endpoint->port();
  thread_ = std::thread([this] { io_.run([] {}); });
}

// as feltd ends
InProcessServer::~InProcessServer() {
  scenes_.stop_all();
  server_.shutdown();
  io_.stop();
  thread_.join();
  context_.loader.join();
  context_.frame_encoder.join();
  server_.close_all();
  io_.run_down();
}

std::unique_ptr<client::Client> InProcessServer::greeted(const std::string& name) {
  auto client = std::make_unique<client::Client>();
  client->connect("127.0.0.1", port_);
  client->hello(name);
  return client;
}

}  // namespace felt::net
