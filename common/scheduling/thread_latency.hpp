#pragma once
// How the threads on the haptic path ask the kernel to run them as soon as they are woken, and
// how a busy thread steps aside for them. On a
// machine whose cores are busy (the physics threads, other processes) a woken thread under the
// normal policy can wait a millisecond for a core: that is the tail of the ProxyUpdate ->
// ForceUpdate round trip (docs/results/service.md). Two ways out:
//  - a short time slice (Linux 6.12 and later, no privilege): the fair scheduler (EEVDF) lets
//    a waking thread that asked for a shorter slice than the running one preempt it at once,
//    instead of when the running thread's slice (1.4 ms on two cores by default) is used up;
//  - SCHED_FIFO (root or CAP_SYS_NICE): the thread runs ahead of every normal one.
// Threads started afterwards get the defaults back, so a scene whose physics thread is started
// from a network thread steps with the normal slice and policy; a process whose every thread is
// on the haptic path (felt's device emulator) may pass its slice on instead.

#include <chrono>
#include <expected>
#include <string>

namespace felt {

/// The slices the kernel accepts (sched_setattr(2): 0.1 to 100 ms).
constexpr std::chrono::microseconds kMinTimeSlice{100};
constexpr std::chrono::microseconds kMaxTimeSlice{100'000};

enum class SliceInheritance { kThisThreadOnly, kAlsoThreadsItStarts };

/// Asks for `slice` (kMinTimeSlice to kMaxTimeSlice, or zero: the kernel's default) as the
/// calling thread's time slice under the normal policy. Kernels before 6.12 accept the request
/// and keep their own slice.
std::expected<void, std::string> request_time_slice(
    std::chrono::microseconds slice,
    SliceInheritance inheritance = SliceInheritance::kThisThreadOnly);
/// The calling thread's slice as the kernel reports it: zero where it reports none (before
/// 6.12).
std::chrono::microseconds time_slice();

/// The nicest a thread can be (setpriority(2)).
constexpr int kMaxNice = 19;

/// Sets the calling thread's nice (0 to kMaxNice) under the normal policy: a physics thread
/// that steps aside for the threads of the haptic path (at nice 0), which then preempt it as
/// soon as they are woken instead of waiting until it has used its share. Raising a thread's
/// nice takes no privilege (lowering it again does); the threads it starts inherit it. Under
/// autogroup or a cgroup, a nice weighs only against the threads of the same group.
std::expected<void, std::string> set_this_thread_nice(int nice);
/// The calling thread's nice.
int this_thread_nice();
/// Raises the calling thread's nice to `nice` (0 to kMaxNice) to step aside for the threads of
/// the haptic path, and never lowers it: in a process started nicer than that (nice -n 15), a
/// privileged thread could lower its nice and so rise above the network threads it should yield
/// to.
std::expected<void, std::string> step_this_thread_aside(int nice);

/// The highest priority make_this_thread_realtime accepts (the kernel's SCHED_FIFO range).
constexpr int kMaxRealtimePriority = 99;

/// Puts the calling thread under SCHED_FIFO at `priority` (1 to kMaxRealtimePriority). The error
/// says why the system refused: it takes root, CAP_SYS_NICE or an RLIMIT_RTPRIO of at least
/// `priority`.
std::expected<void, std::string> make_this_thread_realtime(int priority);

}  // namespace felt
