#pragma once
// Keeps idle cores awake while haptic updates stream, without privileges. On a virtual machine
// an idle core halts and hands its CPU back to the host, and waking it for an arriving update
// takes the host's scheduler: that is most of eight 1 kHz clients' round-trip tail
// (docs/results/service.md). Holding /dev/cpu_dma_latency at 0 makes idle cores poll, but it
// takes root. These threads do the same from user space: one per core, pinned to it, spinning
// under SCHED_IDLE, which any runnable thread of the normal policy preempts at once and which
// the kernel counts as an idle core when it places a woken thread. They spin for a while after
// each touch (a haptic update) and sleep otherwise, so a server nobody touches costs nothing.
// What they cost while they spin: the idle time of every core, a few percent of the physics
// thread's speed where cores share a physical one (a hyperthread, a host's core), and, with
// several clients, wake-ups placed behind the physics thread: a core with a runnable spinner is
// not idle to the kernel's wake-up shortcuts and balancing (docs/results/idle_core_spinners.md),
// which is why feltd leaves them off unless asked.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <ctime>
#include <expected>
#include <limits>
#include <memory>
#include <mutex>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

namespace felt {

class IdleCoreSpinners {
 public:
  using Clock = std::chrono::steady_clock;

  /// Starts a sleeping spinner on each core this process may run on; each touch makes them
  /// spin for `linger` (more than zero) after it. The error says why not (a core or the policy
  /// refused).
  static std::expected<std::unique_ptr<IdleCoreSpinners>, std::string> start(
      std::chrono::milliseconds linger);
  ~IdleCoreSpinners();
  IdleCoreSpinners(const IdleCoreSpinners&) = delete;
  IdleCoreSpinners& operator=(const IdleCoreSpinners&) = delete;

  /// Something on the haptic path happened at `now`: spin until `now + linger`. Cheap while
  /// they spin (a store and a load); wakes them when they sleep.
  void touch(Clock::time_point now);

  /// From now on they spin until destroyed, whatever the touches: for a process whose whole
  /// life is a haptic loop (felt's device emulator on the device's host).
  void spin_until_destroyed();

  std::size_t cores() const { return threads_.size(); }
  /// The CPU time the spinners have taken so far.
  std::chrono::nanoseconds cpu_time() const;

 private:
  explicit IdleCoreSpinners(std::chrono::milliseconds linger) : linger_(linger) {}
  void spin(std::stop_token stop);
  bool lingering() const;

  const std::chrono::milliseconds linger_;
  /// the last touch, Clock ticks since its epoch; the minimum: never touched
  std::atomic<Clock::rep> last_touch_{std::numeric_limits<Clock::rep>::min() / 2};
  std::atomic<int> sleepers_{0};
  std::mutex mutex_;
  std::condition_variable_any wake_;
  std::vector<std::jthread> threads_;
  std::vector<clockid_t> cpu_clocks_;  ///< the spinners' CPU-time clocks
};

}  // namespace felt
