#pragma once
// A clock that moves only when the test moves it, so that a scene's pacing, publication and
// statistics can be checked exactly: what a scene does in 10 ms of its clock does not depend on
// how fast the machine is. A physics thread waiting on it wakes when the test advances it past
// the time it waits for, and the test can tell when the thread is asleep again.

#include <algorithm>
#include <mutex>
#include <vector>

#include "runtime/clock.hpp"

namespace felt {

class ManualClock final : public Clock {
 public:
  time_point now() const override {
    std::lock_guard lock(mutex_);
    return now_;
  }

  void advance(duration by) {
    std::vector<Waiter> waiters;
    {
      std::lock_guard lock(mutex_);
      now_ += by;
      waiters = waiters_;
    }
    for (const Waiter& waiter : waiters) {
      // taking the waiter's mutex orders the new time before its next look at the clock
      { std::lock_guard lock(*waiter.mutex); }
      waiter.wake->notify_all();
    }
  }

  /// Whether some thread waits on this clock for a time still ahead (and none for one that
  /// has come): a physics thread that has done what was due and sleeps until the clock moves.
  bool sleeping() const {
    std::lock_guard lock(mutex_);
    return !waiters_.empty() && std::all_of(waiters_.begin(), waiters_.end(),
                                            [&](const Waiter& w) { return w.due > now_; });
  }

  void wait_until(std::unique_lock<std::mutex>& lock, std::condition_variable_any& wake,
                  std::stop_token stop, time_point due,
                  const std::function<bool()>& ready) override {
    {
      std::lock_guard guard(mutex_);
      waiters_.push_back({lock.mutex(), &wake, due});
    }
    wake.wait(lock, stop, [&] { return ready() || now() >= due; });
    std::lock_guard guard(mutex_);
    std::erase_if(waiters_, [&](const Waiter& waiter) { return waiter.wake == &wake; });
  }

 private:
  struct Waiter {
    std::mutex* mutex;
    std::condition_variable_any* wake;
    time_point due;
  };

  mutable std::mutex mutex_;
  // far from the steady clock's epoch, so that "an hour ago" is a time too
  time_point now_ = time_point{} + std::chrono::hours(24);
  std::vector<Waiter> waiters_;
};

}  // namespace felt
