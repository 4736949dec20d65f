#pragma once
// The clock a scene's physics thread paces itself by, publishes by and measures its steps
// with: the steady wall clock in the server; in tests, a clock the test moves (so that pacing
// is checked exactly instead of by sleeping and loose ratios).

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <stop_token>

namespace felt {

class Clock {
 public:
  using time_point = std::chrono::steady_clock::time_point;
  using duration = std::chrono::steady_clock::duration;

  virtual ~Clock() = default;
  virtual time_point now() const = 0;
  /// Waits on `wake` (`lock` held on entry and on return) until `ready()` holds, `stop` is
  /// requested, or this clock reaches `due`. Whoever makes `ready()` true notifies `wake`
  /// while or after holding `lock`'s mutex.
  virtual void wait_until(std::unique_lock<std::mutex>& lock, std::condition_variable_any& wake,
                          std::stop_token stop, time_point due,
                          const std::function<bool()>& ready) = 0;
};

/// std::chrono::steady_clock.
class WallClock final : public Clock {
 public:
  time_point now() const override { return std::chrono::steady_clock::now(); }
  void wait_until(std::unique_lock<std::mutex>& lock, std::condition_variable_any& wake,
                  std::stop_token stop, time_point due,
                  const std::function<bool()>& ready) override {
    wake.wait_until(lock, stop, due, ready);
  }
};

/// The wall clock every scene runs by unless it is given another.
Clock& wall_clock();

}  // namespace felt
