#pragma once
// A clock that moves on by a fixed tick at every reading: a machine on which everything the
// physics thread does between two looks at its clock takes time, so that a test sees what a
// scene does when its steps cannot keep up, exactly and without sleeping. Only the physics
// thread should read it.

#include <atomic>
#include <chrono>

#include "runtime/clock.hpp"

namespace felt {

class TickingClock final : public Clock {
 public:
  explicit TickingClock(duration tick) : tick_(tick) {}

  time_point now() const override { return start_ + tick_ * readings_.fetch_add(1); }

  void wait_until(std::unique_lock<std::mutex>& lock, std::condition_variable_any& wake,
                  std::stop_token stop, time_point due,
                  const std::function<bool()>& ready) override {
    // every look moves the clock, so waiting is looking (a short wait apart) until it is late
    // enough
    while (!stop.stop_requested() && !ready() && now() < due) {
      wake.wait_for(lock, std::chrono::microseconds(20));
    }
  }

 private:
  duration tick_;
  time_point start_ = time_point{} + std::chrono::hours(24);
  mutable std::atomic<std::int64_t> readings_{0};
};

}  // namespace felt
