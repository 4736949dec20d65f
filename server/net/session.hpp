#pragma once
// One client connection, over any transport (TCP, WebSocket). Everything a session does runs on
// its transport's strand: reads, dispatch, writes, its frame timer and the events and late
// replies other threads post to it, so a session needs no locks and one slow client cannot
// block another. What it sends goes through its OutboundQueue, its frames through SessionFrames;
// the session itself holds the greeting, the scene it is in and its proxies.

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>

#include "felt/v1/envelope.pb.h"
#include "net/outbound_queue.hpp"
#include "net/pending_reply.hpp"
#include "net/request_rate.hpp"
#include "net/server_context.hpp"
#include "net/session_frames.hpp"
#include "net/transport.hpp"
#include "runtime/proxy_key.hpp"

namespace felt::net {

class Session final : public std::enable_shared_from_this<Session>,
                      private OutboundQueue::Listener {
 public:
  Session(std::unique_ptr<Transport> transport, ServerContext& context);
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
  template <class Task>
  void post(Task&& task) {
    boost::asio::post(transport_->executor(), std::forward<Task>(task));
  }

  // The rest is for the request handlers, on the session's strand.
  ServerContext& context() { return context_; }
  ClientId client_id() const { return id_; }
  /// The client as the log names it: client 3 "felt-cli" (the name once it said Hello).
  std::string who() const;
  /// Where its connection comes from: "127.0.0.1:40112 over TCP".
  const std::string& peer() const { return transport_->peer(); }

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
  ProxyHandle* proxy(ProxyId proxy_id);
  /// Opens a proxy with `settings` under a fresh id; 0 when the session has as many as it may.
  ProxyId open_proxy(const ProxySettings& settings);
  bool close_proxy(ProxyId proxy_id);
  std::size_t open_proxies() const { return proxies_.size(); }
  /// Proxies not updated for a second before `now` let go of the surface (and snapshots) they
  /// kept.
  void forget_idle_proxy_surfaces(SteadyClock::time_point now);

  /// Streams frames of the joined scene (again, from a key frame).
  void subscribe_frames(const FrameOptions& options) { frames_.subscribe(options); }
  void unsubscribe_frames() { frames_.unsubscribe(); }
  FrameStream& frames() { return frames_.stream(); }

  struct Counters {
    std::uint64_t requests = 0;
    std::uint64_t frames_sent = 0;
    std::uint64_t frames_skipped = 0;
    std::uint64_t bytes_sent = 0;
    std::uint64_t bytes_received = 0;
  };
  Counters counters() const;
  std::size_t requests_in_flight() const { return in_flight_.load(); }
  std::size_t queued_reply_bytes() const { return outbound_.queued_bytes(); }

 private:
  friend class PendingReply;
  class Membership;

  /// A PendingReply was made; its reply came back (on the strand).
  void begin_deferred() { ++in_flight_; }
  void end_deferred(const felt::v1::ServerMessage& reply);

  // OutboundQueue::Listener
  void on_frame_written() override;
  void on_connection_lost() override { shutdown(false); }
  void on_backlog_exceeded(std::size_t max_backlog_bytes) override;
  void on_drained() override { shutdown(true); }

  /// Lets the outbound queue and the frames keep the session alive while they write or encode.
  void hold_while_busy();
  void read();
  /// Closes the connection if it has not said Hello in time.
  void start_hello_deadline();
  void on_read(const boost::system::error_code& ec, std::size_t bytes);
  /// Handles received requests, a bounded number per turn so that other sessions get theirs,
  /// and no faster than --max-request-rate.
  void process();
  /// Handles the next requests after `wait`, the time until the rate lets one be read.
  void process_after(RequestRate::Clock::duration wait);
  void on_scene_event(SceneId scene, const SceneEvent& event);
  /// Ends the connection: after what was written (`gracefully`), or at once.
  void shutdown(bool gracefully);
  /// Tells the others in the scene that this client joined or left.
  void announce(SceneEvent::Kind kind);
  /// Lets go of the scene: proxies, membership, frames (the registry is the caller's).
  void forget_scene();
  void close_proxies();
  /// Logs a refusal of a limit, at most one a second per session (the rest are counted and
  /// said with the next), so that a client that keeps hitting a limit cannot flood the log.
  void log_refusal(const std::string& what);

  std::unique_ptr<Transport> transport_;
  ServerContext& context_;
  const ClientId id_;
  std::uint64_t requests_ = 0;
  std::uint64_t frames_sent_ = 0;
  std::uint64_t bytes_received_ = 0;
  std::atomic<std::size_t> in_flight_{0};
  OutboundQueue outbound_;
  SessionFrames frames_;
  bool closed_ = false;
  bool counted_ = false;  ///< counted in context_.clients

  bool greeted_ = false;
  int refused_hellos_ = 0;
  boost::asio::steady_timer hello_timer_;
  RequestRate rate_;
  boost::asio::steady_timer rate_timer_;
  bool rate_logged_ = false;  ///< the first wait for the rate is logged, once
  std::string client_name_;
  SceneId scene_id_ = 0;
  std::shared_ptr<SceneRunner> scene_;
  std::shared_ptr<Membership> membership_;  ///< how the scene reaches this session
  std::map<ProxyId, ProxyHandle> proxies_;  ///< after scene_: closed before it goes
  SteadyClock::time_point last_refusal_logged_{};
  std::uint64_t refusals_not_logged_ = 0;
};

}  // namespace felt::net
