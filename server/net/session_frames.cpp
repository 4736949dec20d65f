#include "net/session_frames.hpp"

#include <utility>

#include <boost/asio/post.hpp>

namespace felt::net {

namespace asio = boost::asio;

namespace {

/// A proxy not updated for this long is not shown to the others.
constexpr auto kPresenceWindow = std::chrono::seconds(1);

// how soon a tick that found a stale snapshot looks again: a step or two of most scenes
constexpr auto kStaleRetry = std::chrono::milliseconds(2);

}  // namespace

SessionFrames::SessionFrames(ClientId client, const Transport::Executor& strand,
                             asio::thread_pool& encoder, SharedFrameBodies& shared,
                             OutboundQueue& outbound)
    : client_(client),
      strand_(strand),
      encoder_(encoder),
      shared_(shared),
      outbound_(outbound),
      timer_(strand) {}

void SessionFrames::subscribe(const FrameOptions& options) {
  stream_.start(options);
  drop_pending();
  if (scene_) scene_->prepare_frames();
  if (!timer_running_) {
    timer_running_ = true;
    due_ = std::chrono::steady_clock::now();
    late_ticks_ = 0;
    lost_ = 0;
    tick();
  }
}

void SessionFrames::unsubscribe() {
  stream_.stop();
  drop_pending();
  timer_.cancel();
  timer_running_ = false;
}

void SessionFrames::show(std::shared_ptr<SceneRunner> scene, SceneId id) {
  scene_ = std::move(scene);
  scene_id_ = id;
  drop_pending();
  stream_.restart();
  if (scene_ && stream_.active()) scene_->prepare_frames();
}

void SessionFrames::drop_pending() {
  outbound_.drop_frame();
  encoding_ = false;
  ++generation_;
}

void SessionFrames::stop() {
  timer_.cancel();
  timer_running_ = false;
  scene_.reset();
  drop_pending();
}

void SessionFrames::schedule() {
  const auto period =
      std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / stream_.options().rate_hz));
  due_ += period;
  // on the grid of the period's multiples on the steady clock, which every session shares
  due_ -= due_.time_since_epoch() % period;
  const auto now = std::chrono::steady_clock::now();
  if (due_ < now) {
    // a starved thread: the ticks that should have come meanwhile are lost, not made up for
    const std::int64_t late = (now - due_) / period;
    late_ticks_ += static_cast<std::uint64_t>(late);
    due_ += late * period;
  }
  timer_.expires_at(due_);
  timer_.async_wait([this, owner = owner_.lock()](const boost::system::error_code& ec) {
    if (!ec && timer_running_) tick();
  });
}

void SessionFrames::retry_soon() {
  timer_.expires_after(kStaleRetry);
  timer_.async_wait([this, owner = owner_.lock()](const boost::system::error_code& ec) {
    if (!ec && timer_running_) tick();
  });
}

void SessionFrames::tick() {
  if (!stream_.active() || outbound_.closing()) {
    timer_running_ = false;
    return;
  }
  if (housekeeping_) housekeeping_();
  const std::uint64_t late = std::exchange(late_ticks_, 0);
  if (scene_) {
    auto snapshot = scene_->latest();
    if (scene_->stale()) {
      // a scene nobody watched lately (a subscription slower than LiveScene::kReadersKept, or
      // just made): its steps are published before its next one
      late_ticks_ += late;
      scene_->prepare_frames();
      retry_soon();
      return;
    }
    // with nothing new to show no frame is due, and none was lost while the timer was late
    if (stream_.has_new(*snapshot)) {
      lost_ += late;
      skipped_ += late;
      if (encoding_ || stream_.window_full()) {
        // a frame still with the encoder (a busy server) is the latest one, and a client with
        // its window of unacknowledged frames full has not drawn the ones it has: no other is
        // planned, and this one is lost
        ++lost_;
        ++skipped_;
      } else {
        std::uint64_t skipped = std::exchange(lost_, 0);
        if (outbound_.frame_waiting()) {
          // the client has not taken the previous frame: it is dropped, and so are the
          // triangles it carried, which the next frame must carry instead
          skipped += slot_skipped_ + 1;
          stream_.dropped();
          drop_pending();
          ++skipped_;
        }
        FrameStream::Plan plan = stream_.plan(std::move(snapshot), scene_id_, skipped);
        plan.proxies = proxies();
        encode(std::move(plan));
      }
    }
  }
  schedule();
}

std::vector<ProxyView> SessionFrames::proxies() const {
  std::vector<ProxyView> out;
  for (const ProxyPresenceEntry& entry : scene_->presence(kPresenceWindow)) {
    out.push_back(
        {scene_->members().name_of(entry.key.client), entry.key.client == client_, entry});
  }
  return out;
}

void SessionFrames::encode(FrameStream::Plan plan) {
  encoding_ = true;
  asio::post(encoder_, [this, owner = owner_, plan = std::move(plan), generation = generation_] {
    FrameStream::FrameRecord record;
    std::string bytes;
    FrameStream::encode(plan, shared_, bytes, record);
    auto session = owner.lock();
    if (!session) return;
    // the reference moves into the handler, so that the session is never destroyed on this
    // thread
    asio::post(strand_, [this, session = std::move(session), generation, skipped = plan.skipped,
                         record = std::move(record), bytes = std::move(bytes)]() mutable {
      encoded(generation, skipped, std::move(record), std::move(bytes));
    });
  });
}

void SessionFrames::encoded(std::uint64_t generation, std::uint64_t skipped,
                            FrameStream::FrameRecord record, std::string bytes) {
  // dropped while it was encoded (a new subscription, another scene, the connection's end)
  if (generation != generation_ || outbound_.closing()) return;
  encoding_ = false;
  stream_.encoded(std::move(record));
  slot_skipped_ = skipped;
  outbound_.put_frame(std::move(bytes));
}

}  // namespace felt::net
