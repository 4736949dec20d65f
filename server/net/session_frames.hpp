#pragma once
// A session's frame subscription at work: a timer at the subscription's rate plans a frame from
// the latest snapshot of the session's scene on the session's strand, the server's frame encoder
// encodes it, and the bytes come back into the outbound queue's slot (latest wins). The timer
// ticks on a grid of its period common to every session (multiples of the period on the steady
// clock), so that sessions at one rate take the same snapshot and share its encoded bodies
// (shared_frame_bodies.hpp). A frame that
// comes back after its subscription changed, ended or moved to another scene is not sent.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <boost/asio/steady_timer.hpp>
#include <boost/asio/thread_pool.hpp>

#include "net/frame_stream.hpp"
#include "net/outbound_queue.hpp"
#include "net/shared_frame_bodies.hpp"

namespace felt::net {

class SessionFrames {
 public:
  /// Frames for client `client`, whose own proxies they mark.
  SessionFrames(ClientId client, const Transport::Executor& strand,
                boost::asio::thread_pool& encoder, SharedFrameBodies& shared,
                OutboundQueue& outbound);
  /// `owner` (the session) is kept alive while a tick or an encoding is under way.
  void set_owner(std::weak_ptr<void> owner) { owner_ = std::move(owner); }
  /// Runs on every tick, before the frame is planned (the session's housekeeping).
  void on_tick(std::function<void()> housekeeping) { housekeeping_ = std::move(housekeeping); }

  /// Streams the session's scene with `options`, from a key frame with triangles.
  void subscribe(const FrameOptions& options);
  void unsubscribe();
  /// The session is in `scene` (`id`; null: in none) now: a frame of the previous one is not
  /// sent, and the stream starts again with triangles.
  void show(std::shared_ptr<SceneRunner> scene, SceneId id);
  /// The frame in the slot, or with the encoder, is not sent.
  void drop_pending();
  /// The frame in the slot went to the transport.
  void written() { stream_.written(); }
  /// Nothing more is planned.
  void stop();

  FrameStream& stream() { return stream_; }
  std::uint64_t skipped() const { return skipped_; }

 private:
  void schedule();
  /// Ticks again in kStaleRetry, off the grid: the scene's latest snapshot lacked steps
  /// nobody watched, which its physics thread publishes between its next two steps.
  void retry_soon();
  /// The scene's proxies as this client sees them.
  std::vector<ProxyView> proxies() const;
  void tick();
  /// Has the encoder encode `plan`; its bytes come back to encoded().
  void encode(FrameStream::Plan plan);
  void encoded(std::uint64_t generation, std::uint64_t skipped, FrameStream::FrameRecord record,
               std::string bytes);

  const ClientId client_;
  Transport::Executor strand_;
  boost::asio::thread_pool& encoder_;
  SharedFrameBodies& shared_;
  OutboundQueue& outbound_;
  std::weak_ptr<void> owner_;
  std::function<void()> housekeeping_;
  boost::asio::steady_timer timer_;
  bool timer_running_ = false;
  FrameStream stream_;
  std::shared_ptr<SceneRunner> scene_;
  SceneId scene_id_ = 0;
  std::uint64_t slot_skipped_ = 0;  ///< the `skipped` count the frame in the slot carries
  bool encoding_ = false;           ///< a frame is with the encoder: no other is planned
  /// counts the frames dropped unsent: a frame encoded under an older count is not sent
  std::uint64_t generation_ = 0;
  /// frames not sent at the granted rate, in all: replaced in the slot unsent, or never built
  /// because the encoder still had the one before or the timer came late
  std::uint64_t skipped_ = 0;
  /// frames the scene had for this session that were not built, to be told with the next one
  std::uint64_t lost_ = 0;
  /// the timer's next tick: on a fixed grid of the subscription's period (its multiples on the
  /// steady clock), so that a late tick does not lower the rate after it
  std::chrono::steady_clock::time_point due_{};
  std::uint64_t late_ticks_ = 0;  ///< whole periods the timer came late by, before this tick
};

}  // namespace felt::net
