#pragma once
// One client connection. Everything a session does runs on its own strand: reads, dispatch,
// writes, its frame timer and the events and late replies other threads post to it, so a
// session needs no locks and one slow client cannot block another.

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include <boost/asio.hpp>

#include "felt/v1/envelope.pb.h"
#include "net/frame_stream.hpp"
#include "net/server_context.hpp"
#include "wire/frame_codec.hpp"

namespace felt::net {

class Session;

/// A reply that comes later, from another thread (the loader, a scene's physics thread). Safe
/// to use from any thread; the reply is sent on the session's strand, once. Holding one takes
/// one of the session's requests in flight until it is sent.
class PendingReply {
 public:
  PendingReply(std::shared_ptr<Session> session, std::uint64_t request_id);
  ~PendingReply();
  PendingReply(const PendingReply&) = delete;
  PendingReply& operator=(const PendingReply&) = delete;

  std::uint64_t request_id() const { return request_id_; }
  void send(felt::v1::ServerMessage message);
  void fail(felt::v1::ErrorCode code, std::string message);

 private:
  std::weak_ptr<Session> session_;
  std::uint64_t request_id_;
  std::atomic<bool> sent_{false};
};

class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(boost::asio::ip::tcp::socket socket, ServerContext& context);
  ~Session();

  /// Starts reading. The session keeps itself alive until the connection ends.
  void start();
  /// Refuses the connection: sends `message` as an Error with request id 0, then closes.
  void reject(felt::v1::ErrorCode code, const std::string& message);
  /// Closes the connection from any thread at once.
  void close();
  /// From any thread: tells the client the server is stopping, flushes what is queued, closes.
  void close_gracefully();

  /// Runs `task` on the session's strand, from any thread.
  void post(std::function<void()> task);

  // The rest is for the request handlers, on the session's strand.
  ServerContext& context() { return context_; }
  ClientId client_id() const { return id_; }

  /// Queues a message; replies and events are never dropped, but a client that lets too many
  /// pile up is disconnected.
  void send(const felt::v1::ServerMessage& message);
  void send_error(std::uint64_t request_id, felt::v1::ErrorCode code, const std::string& message);
  /// Reads no more requests; closes once the queued replies are written.
  void close_after_replies();
  /// A reply that another thread will send; null when the client already has as many requests
  /// in flight as it may (the caller answers LIMIT_EXCEEDED).
  std::shared_ptr<PendingReply> defer(std::uint64_t request_id);

  bool greeted() const { return greeted_; }
  /// The connection has ended.
  bool closed() const { return closed_; }
  /// The first successful Hello also joins the server's default scene.
  void set_greeted(std::string client_name);
  /// Counts a Hello with a wrong token; true when the connection must close (no endless
  /// guessing on one connection).
  bool refuse_hello();
  static constexpr int kMaxRefusedHellos = 3;

  /// The scene this session is in (nullptr when none).
  const std::shared_ptr<SceneRunner>& scene() const { return scene_; }
  SceneId scene_id() const { return scene_id_; }
  /// Joins scene `id`, leaving the one it is in (its proxies close, frames restart); false for
  /// an unknown id.
  bool join(SceneId id);
  /// Leaves the session's scene, if any, telling the others unless `quietly`.
  void leave_scene(bool quietly = false);

  /// The open proxy `proxy_id`, opening it with the scene's settings if it is not open; null
  /// when the session already has as many proxies as it may.
  HapticProxy* proxy(std::uint32_t proxy_id);
  /// Opens a proxy with `settings` under a fresh id; 0 when the session has as many as it may.
  std::uint32_t open_proxy(const ProxySettings& settings);
  bool close_proxy(std::uint32_t proxy_id);
  std::size_t open_proxies() const { return proxies_.size(); }
  /// Proxies not updated for a second before `now` let go of the surface (and snapshots) they
  /// kept.
  void forget_idle_proxy_surfaces(SteadyClock::time_point now);

  /// Streams frames of the joined scene (again, from a key frame).
  void subscribe_frames(const FrameOptions& options);
  void unsubscribe_frames();
  FrameStream& frames() { return frames_; }

  struct Counters {
    std::uint64_t requests = 0;
    std::uint64_t frames_sent = 0;
    std::uint64_t frames_skipped = 0;
    std::uint64_t bytes_sent = 0;
    std::uint64_t bytes_received = 0;
  };
  const Counters& counters() const { return counters_; }
  std::size_t requests_in_flight() const { return in_flight_.load(); }
  std::size_t queued_reply_bytes() const { return queued_replies_.size(); }

 private:
  friend class PendingReply;
  class Membership;

  void read();
  /// Closes the connection if it has not said Hello in time.
  void start_hello_deadline();
  void on_read(const boost::system::error_code& ec, std::size_t bytes);
  /// Handles buffered requests, a bounded number per turn so that other sessions get theirs.
  void process();
  void write_next();
  void schedule_frame();
  void on_frame_tick();
  /// Has the server's frame encoder encode `plan`; the frame comes back to on_frame_encoded.
  void encode_frame(FrameStream::Plan plan);
  void on_frame_encoded(std::uint64_t generation, std::uint64_t skipped,
                        FrameStream::FrameRecord record, std::string bytes);
  void on_scene_event(SceneId scene, const SceneEvent& event);
  void shutdown();
  /// Tells the others in the scene that this client joined or left.
  void announce(SceneEvent::Kind kind);
  /// The frame waiting in the slot, or being encoded, is not sent.
  void drop_pending_frame();
  /// Lets go of the scene: proxies, membership, frames (the registry is the caller's).
  void forget_scene();
  std::uint64_t key_of(std::uint32_t proxy_id) const;
  void close_proxies();

  boost::asio::ip::tcp::socket socket_;
  ServerContext& context_;
  const ClientId id_;
  wire::FrameDecoder decoder_;
  std::array<std::uint8_t, 16 * 1024> read_buffer_;
  Counters counters_;
  std::atomic<std::size_t> in_flight_{0};

  /// replies and events not yet handed to the socket, back to back as they go on the wire:
  /// they go out in one write, and cost their bytes and no allocation each
  std::string queued_replies_;
  std::string pending_frame_;  ///< latest-wins: a newer frame replaces one not yet written
  bool frame_pending_ = false;
  std::uint64_t pending_frame_skipped_ = 0;  ///< the `skipped` count the pending frame carries
  bool frame_encoding_ = false;              ///< a frame is with the encoder: no other is planned
  /// counts the frames dropped unsent: a frame encoded under an older count is not sent
  std::uint64_t frame_generation_ = 0;
  std::string in_flight_bytes_;  ///< the bytes async_write is sending
  bool writing_ = false;
  bool closing_ = false;  ///< a fatal error or goodbye was queued: close once it is written
  bool closed_ = false;
  bool counted_ = false;  ///< counted in context_.clients

  bool greeted_ = false;
  int refused_hellos_ = 0;
  boost::asio::steady_timer hello_timer_;
  std::string client_name_;
  SceneId scene_id_ = 0;
  std::shared_ptr<SceneRunner> scene_;
  std::shared_ptr<Membership> membership_;  ///< how the scene reaches this session
  std::map<std::uint32_t, HapticProxy> proxies_;

  boost::asio::steady_timer frame_timer_;
  FrameStream frames_;
  bool timer_running_ = false;
};

}  // namespace felt::net
