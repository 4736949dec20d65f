#pragma once
// When something was last used, marked and asked by any thread without a lock: what keeps the
// work done for a use (haptic frames, vertex normals, snapshots after steps) going while it is
// in use, and stops it in a scene nobody uses that way.

#include <atomic>
#include <chrono>

namespace felt {

class RecentUse {
 public:
  using Clock = std::chrono::steady_clock;

  /// Marks a use at `now`; whether the one before it lay within `window` of it.
  bool use(Clock::duration window, Clock::time_point now = Clock::now()) {
    return within(last_.exchange(ticks(now), std::memory_order_relaxed), window, now);
  }
  /// Whether the latest use lies within `window` of `now`.
  bool recent(Clock::duration window, Clock::time_point now = Clock::now()) const {
    return within(last_.load(std::memory_order_relaxed), window, now);
  }

 private:
  static constexpr Clock::rep kNever = 0;
  static Clock::rep ticks(Clock::time_point t) { return t.time_since_epoch().count(); }
  static bool within(Clock::rep last, Clock::duration window, Clock::time_point now) {
    return last != kNever && now - Clock::time_point(Clock::duration(last)) < window;
  }

  std::atomic<Clock::rep> last_{kNever};
};

}  // namespace felt
