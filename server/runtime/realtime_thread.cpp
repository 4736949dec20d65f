#include "runtime/realtime_thread.hpp"

#include <sched.h>

#include <cerrno>
#include <cstring>

namespace felt {

std::expected<void, std::string> make_this_thread_realtime(int priority) {
  if (priority < 1 || priority > kMaxRealtimePriority) {
    return std::unexpected("real-time priority " + std::to_string(priority) + " is not in 1 to " +
                           std::to_string(kMaxRealtimePriority));
  }
  sched_param param{};
  param.sched_priority = priority;
  // pid 0 is the calling thread (Linux schedules threads, not processes)
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
