#pragma once
// One client connection. Everything a session does runs on its own strand: reads, dispatch,
// writes and its frame timer, so a session needs no locks and one slow client cannot block
// another.

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <boost/asio.hpp>

#include "felt/v1/envelope.pb.h"
#include "net/server_context.hpp"
#include "wire/frame_codec.hpp"

namespace felt::net {

class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(boost::asio::ip::tcp::socket socket, ServerContext& context);
  ~Session();

  /// Starts reading. The session keeps itself alive until the connection ends.
  void start();
  /// Closes the connection from any thread.
  void close();

  // The rest is for the dispatcher, on the session's strand.
  ServerContext& context() { return context_; }
  std::uint64_t id() const { return id_; }

  /// Queues a reply; replies are never dropped, but a client that lets too many pile up is
  /// disconnected.
  void send(const felt::v1::ServerMessage& message);
  void send_error(std::uint64_t request_id, felt::v1::ErrorCode code, const std::string& message);

  bool greeted() const { return greeted_; }
  void set_greeted() { greeted_ = true; }

  /// The scene this session is in (nullptr when none).
  const std::shared_ptr<SceneRunner>& scene() const { return scene_; }
  SceneId scene_id() const { return scene_id_; }
  /// Joins a scene, leaving the previous one (its proxies are closed, frames restart).
  void join(SceneId id, std::shared_ptr<SceneRunner> scene);

  /// This session's proxy `proxy_id` in its scene, opened on first use; null when the session
  /// already has as many proxies as it may.
  HapticProxy* open_proxy(std::uint32_t proxy_id);

  /// Streams frames of the joined scene at up to `rate_hz`.
  void subscribe_frames(double rate_hz, bool normals);

 private:
  void read();
  void on_read(const boost::system::error_code& ec, std::size_t bytes);
  void write_next();
  void schedule_frame();
  void on_frame_tick();
  /// Sends the events of the scene the session has not sent yet.
  void send_new_events(const SceneSnapshot& snapshot);
  void leave_scene();
  void shutdown();
  std::uint64_t key_of(std::uint32_t proxy_id) const;

  boost::asio::ip::tcp::socket socket_;
  ServerContext& context_;
  const std::uint64_t id_;
  wire::FrameDecoder decoder_;
  std::array<std::uint8_t, 16 * 1024> read_buffer_;

  std::deque<std::string> replies_;
  std::size_t queued_reply_bytes_ = 0;
  std::string pending_frame_;  ///< latest-wins: a newer frame replaces one not yet written
  bool frame_pending_ = false;
  std::uint64_t pending_frame_skipped_ = 0;  ///< the `skipped` count the pending frame carries
  std::string in_flight_;                    ///< the bytes async_write is sending
  bool writing_ = false;
  bool closing_ = false;  ///< a fatal error was queued: close once it is written
  bool closed_ = false;

  bool greeted_ = false;
  SceneId scene_id_ = 0;
  std::shared_ptr<SceneRunner> scene_;
  std::map<std::uint32_t, HapticProxy> proxies_;

  boost::asio::steady_timer frame_timer_;
  bool streaming_ = false;
  bool stream_normals_ = false;
  std::chrono::nanoseconds frame_period_{0};
  std::uint64_t last_frame_step_ = ~std::uint64_t{0};
  std::uint64_t last_event_sequence_ = 0;  ///< of the scene's events, the last one sent
  std::vector<bool> topology_sent_;        ///< per body: has this subscription had its triangles
  std::vector<std::uint32_t> pending_topology_;  ///< bodies whose triangles the pending frame has
};

}  // namespace felt::net
