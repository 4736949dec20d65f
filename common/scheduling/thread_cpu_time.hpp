#pragma once
// The CPU time the calling thread has used: what the benchmarks and a run's statistics measure
// work by on a shared machine, where wall time also counts the waits for a core.

#include <time.h>

namespace felt {

/// s
inline double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace felt
