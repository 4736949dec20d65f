#pragma once
// Real-time scheduling for the threads on the haptic path. On a machine whose cores are busy
// (the physics threads, other processes) a woken thread under the normal policy can wait a
// millisecond for a core: that is the tail of the ProxyUpdate -> ForceUpdate round trip
// (docs/results/service.md). Under SCHED_FIFO it runs as soon as it is woken, ahead of the
// physics threads, which keep the normal policy.

#include <expected>
#include <string>

namespace felt {

/// The highest priority make_this_thread_realtime accepts (the kernel's SCHED_FIFO range).
constexpr int kMaxRealtimePriority = 99;

/// Puts the calling thread under SCHED_FIFO at `priority` (1 to kMaxRealtimePriority). Threads
/// it starts afterwards get the normal policy (SCHED_RESET_ON_FORK), so a scene started from a
/// real-time network thread does not step at real-time priority. The error says why the system
/// refused: it takes root, CAP_SYS_NICE or an RLIMIT_RTPRIO of at least `priority`.
std::expected<void, std::string> make_this_thread_realtime(int priority);

}  // namespace felt
