#include "scheduling/thread_latency.hpp"

#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

namespace felt {
namespace {

// sched_setattr(2)'s argument; glibc before 2.41 declares neither it nor the calls
struct SchedAttr {
  std::uint32_t size = sizeof(SchedAttr);
  std::uint32_t policy = 0;
  std::uint64_t flags = 0;
  std::int32_t nice = 0;
  std::uint32_t priority = 0;
  std::uint64_t runtime_ns = 0;  // under the normal policy: the requested slice
  std::uint64_t deadline_ns = 0;
  std::uint64_t period_ns = 0;
};
constexpr std::uint64_t kResetOnFork = 0x01;  // SCHED_FLAG_RESET_ON_FORK

bool get_attr(SchedAttr& attr) {
  // tid 0 is the calling thread (Linux schedules threads, not processes)
  return ::syscall(SYS_sched_getattr, 0, &attr, sizeof attr, 0) == 0;
}

}  // namespace

std::expected<void, std::string> request_time_slice(std::chrono::microseconds slice,
                                                    SliceInheritance inheritance) {
  if (slice.count() != 0 && (slice < kMinTimeSlice || slice > kMaxTimeSlice)) {
    return std::unexpected("time slice " + std::to_string(slice.count()) + " us is not 0 or in " +
                           std::to_string(kMinTimeSlice.count()) + " to " +
                           std::to_string(kMaxTimeSlice.count()));
  }
  SchedAttr attr;
  if (!get_attr(attr))
    return std::unexpected(std::string("sched_getattr: ") + std::strerror(errno));
  if (attr.policy != SCHED_OTHER) {
    return std::unexpected("a time slice is for the normal policy; this thread has policy " +
                           std::to_string(attr.policy));
  }
  attr.size = sizeof attr;
  attr.flags = inheritance == SliceInheritance::kThisThreadOnly ? kResetOnFork : 0;
  // zero gives the default back
  attr.runtime_ns = static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(slice).count());
  if (::syscall(SYS_sched_setattr, 0, &attr, 0) != 0) {
    return std::unexpected(std::string("sched_setattr: ") + std::strerror(errno));
  }
  return {};
}

std::chrono::microseconds time_slice() {
  SchedAttr attr;
  if (!get_attr(attr)) return std::chrono::microseconds{0};
  return std::chrono::duration_cast<std::chrono::microseconds>(
      std::chrono::nanoseconds(attr.runtime_ns));
}

std::expected<void, std::string> set_this_thread_nice(int nice) {
  if (nice < 0 || nice > kMaxNice) {
    return std::unexpected("nice " + std::to_string(nice) + " is not in 0 to " +
                           std::to_string(kMaxNice));
  }
  // on Linux PRIO_PROCESS with a thread id is that thread alone
  if (setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), nice) != 0) {
    return std::unexpected(std::string("setpriority: ") + std::strerror(errno));
  }
  return {};
}

int this_thread_nice() {
  return getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
}

std::expected<void, std::string> step_this_thread_aside(int nice) {
  if (nice <= this_thread_nice()) return {};
  return set_this_thread_nice(nice);
}

std::expected<void, std::string> make_this_thread_realtime(int priority) {
  if (priority < 1 || priority > kMaxRealtimePriority) {
    return std::unexpected("real-time priority " + std::to_string(priority) + " is not in 1 to " +
                           std::to_string(kMaxRealtimePriority));
  }
  sched_param param{};
  param.sched_priority = priority;
  if (sched_setscheduler(0, SCHED_FIFO | SCHED_RESET_ON_FORK, &param) != 0) {
    const int error = errno;
    return std::unexpected(
        std::string("SCHED_FIFO priority ") + std::to_string(priority) +
        " refused: " + std::strerror(error) +
        (error == EPERM ? " (it takes root, CAP_SYS_NICE or an RLIMIT_RTPRIO)" : ""));
  }
  return {};
}

}  // namespace felt
