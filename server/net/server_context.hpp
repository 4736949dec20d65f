#pragma once
// What every session of a server shares: the scenes, the scene directory and the limits.

#include <atomic>
#include <cstddef>
#include <string>

#include "runtime/scene_registry.hpp"
#include "scene/scene_directory.hpp"

namespace felt::net {

struct ServerOptions {
  std::size_t max_inbound_frame_bytes = 4u << 20;  ///< a larger length prefix closes the connection
  std::size_t max_queued_reply_bytes = 8u << 20;   ///< a client that lets more pile up is dropped
  double default_frame_rate_hz = 60;
  double min_frame_rate_hz = 0.1;
  double max_frame_rate_hz = 240;
  std::size_t max_proxies_per_session = 16;
  std::size_t max_scenes = 32;  ///< scenes loaded at once, preloaded ones included
  std::size_t max_particles_per_scene = 250'000;
  std::string token;  ///< when not empty, Hello must carry it
};

struct ServerContext {
  SceneRegistry& scenes;
  SceneDirectory scene_directory;
  ServerOptions options;
  std::string server_version;
  SceneId default_scene = 0;  ///< joined by every new session; 0 when there is none
  std::atomic<std::uint64_t> next_session_id{1};
};

}  // namespace felt::net
