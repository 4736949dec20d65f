#pragma once
// How long an idle core may take to wake up. On a virtual machine an idle core halts and hands
// its CPU back to the host, and waking it for an arriving update takes the host's scheduler:
// on this project's two-core VM the raw-TCP round trip of eight 1 kHz clients had a p99 of
// 1.7 ms with halting cores and 70 us with polling ones (docs/results/service.md). The kernel's
// PM QoS request (/dev/cpu_dma_latency, as cyclictest and tuned's latency profiles use it) caps
// that wake-up time for as long as a process holds it; 0 makes idle cores poll. It is system-
// wide, takes root (the device is root's), and costs what polling costs: idle cores stay busy.

#include <chrono>
#include <expected>
#include <optional>
#include <string>

namespace felt {

/// The largest limit the kernel takes (PM_QOS_CPU_LATENCY_DEFAULT_VALUE, 2000 s).
constexpr std::chrono::microseconds kMaxCpuWakeupLatency{2'000'000'000};

/// A held limit on the wake-up latency of every core; released when destroyed.
class CpuWakeupLatencyLimit {
 public:
  /// Asks the kernel that no idle core takes longer than `limit` (0 to kMaxCpuWakeupLatency)
  /// to wake up. The error says why not (no such device, not root, a bad limit).
  static std::expected<CpuWakeupLatencyLimit, std::string> hold(std::chrono::microseconds limit);

  CpuWakeupLatencyLimit(CpuWakeupLatencyLimit&& other) noexcept;
  CpuWakeupLatencyLimit& operator=(CpuWakeupLatencyLimit&& other) noexcept;
  CpuWakeupLatencyLimit(const CpuWakeupLatencyLimit&) = delete;
  CpuWakeupLatencyLimit& operator=(const CpuWakeupLatencyLimit&) = delete;
  ~CpuWakeupLatencyLimit();

 private:
  explicit CpuWakeupLatencyLimit(int fd) : fd_(fd) {}
  int fd_ = -1;  ///< the request lasts as long as the descriptor is open
};

/// The limit in force now, the strictest of every holder's (the kernel's default when nobody
/// holds one); nullopt when it cannot be read.
std::optional<std::chrono::microseconds> cpu_wakeup_latency_limit();

}  // namespace felt
