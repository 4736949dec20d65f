#include "runtime/live_haptic_frames.hpp"

namespace felt {
namespace {

// retired frames kept for reuse: the latest, one a reader may still hold, one free
constexpr std::size_t kPoolSize = 3;

}  // namespace

std::shared_ptr<const HapticFrame> LiveHapticFrames::current() {
  const SteadyClock::time_point now = SteadyClock::now();
  const bool in_use = live_.render_haptics(now);
  auto frame = latest_.load();
  if (in_use && frame) return frame;
  // the physics thread may have stopped making frames: start from a still copy of the latest
  std::lock_guard lock(mutex_);
  frame = latest_.load();
  // unless another thread made one while this one waited for the lock
  if (!frame || (frame->to != live_.latest() && frame->published < now)) {
    frame = make_pooled(nullptr, now);
  }
  return frame;
}

void LiveHapticFrames::publish(SteadyClock::time_point now) {
  if (!live_.haptics_rendering(now)) return;
  std::lock_guard lock(mutex_);
  make_pooled(latest_.load().get(), now);
}

std::shared_ptr<HapticFrame> LiveHapticFrames::make_pooled(const HapticFrame* previous,
                                                           SteadyClock::time_point now) {
  std::shared_ptr<HapticFrame> recycled;
  for (const auto& retired : pool_) {
    if (retired.use_count() == 1) recycled = retired;
  }
  auto frame = make_haptic_frame(live_.latest(), previous, recycled, structure_, now);
  if (!recycled) {
    if (pool_.size() == kPoolSize) pool_.erase(pool_.begin());
    pool_.push_back(frame);
  }
  latest_.store(frame);
  return frame;
}

}  // namespace felt
