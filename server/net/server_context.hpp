#pragma once
// What every session of a server shares: the scenes, the scene directory, the limits and the
// workers that load scenes and bodies and encode frames off the network threads.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <string>

#include <boost/asio/thread_pool.hpp>

#include "net/server_log.hpp"
#include "net/shared_frame_bodies.hpp"
#include "runtime/scene_registry.hpp"
#include "scene/scene_directory.hpp"
#include "scheduling/idle_core_spinners.hpp"

namespace felt::net {

/// The server's limits (feltd serve --help names a flag for each).
struct ServerOptions {
  std::size_t max_inbound_frame_bytes = 4u << 20;  ///< a larger length prefix closes the connection
  std::size_t max_queued_reply_bytes = 8u << 20;   ///< a client that lets more pile up is dropped
  double default_frame_rate_hz = 60;
  double min_frame_rate_hz = 0.1;
  double max_frame_rate_hz = 240;
  std::size_t max_proxies_per_session = 16;
  std::size_t max_scenes = 32;  ///< scenes loaded at once, the server's own included
  /// scenes one client loaded with `keep` that run at once: kept scenes outlive their client, so
  /// without it one client could fill max_scenes for everyone
  std::size_t max_kept_scenes_per_client = 4;
  std::size_t max_clients = 64;
  std::size_t max_requests_in_flight = 16;  ///< per client: loads, steps, saves not yet answered
  /// per client, requests read a second (RequestRate): 16 proxies at 1 kHz with frames fit
  double max_request_rate = 20'000;
  std::size_t max_bodies_per_scene = 256;
  std::size_t max_particles_per_scene = 250'000;  ///< in scenes clients load or build
  std::string token;                              ///< when not empty, Hello must carry it
  /// a connection not greeted by then is closed: without it, connections that never say Hello
  /// (no token, or half a frame) would hold every --max-clients slot
  std::uint32_t hello_timeout_ms = 10'000;
  /// the busy threads off the haptic path (every scene's physics, the frame encoder) run
  /// at this nice, so that a woken network thread preempts them at once
  /// (docs/results/background_nice.md); 0: as the network threads
  int background_nice = 10;
};

struct ServerContext {
  SceneRegistry& scenes;
  SceneDirectory scene_directory;
  ServerOptions options;
  std::string server_version;
  /// what happens, one line each, on standard error (feltd serve --log-level)
  ServerLog log;
  SceneId default_scene = 0;  ///< joined by every new session; 0 when there is none
  std::atomic<std::uint32_t> next_client_id{1};
  std::atomic<std::uint32_t> clients{0};  ///< sessions with an open connection
  /// scene and body files are read and built here, so that a big one does not hold up the
  /// network thread that answers every client's haptic updates
  boost::asio::thread_pool loader{1};
  /// every session's frames are encoded here and its network thread only plans and writes
  /// them: encoding a 10,000-vertex body's 16-bit deltas takes 70 us (frame_stream_bench), in
  /// which the haptic updates of every client on that thread would wait
  boost::asio::thread_pool frame_encoder{1};
  /// the bodies of the frames being encoded, once per snapshot and encoding for every session
  SharedFrameBodies frame_bodies{};
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  /// touched by every haptic update, when the server keeps idle cores awake
  IdleCoreSpinners* idle_core_spinners = nullptr;
};

}  // namespace felt::net
