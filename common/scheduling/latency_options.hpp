#pragma once
// How a program's threads on the haptic path ask for a core: feltd's network threads and every
// thread of felt. One set of options and one apply() for both programs; each names its own flags
// in what it reports, and each prints the lines itself.

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scheduling/cpu_wakeup_latency.hpp"
#include "scheduling/idle_core_spinners.hpp"
#include "scheduling/thread_latency.hpp"

namespace felt {

/// What a program asks of the scheduler for its threads on the haptic path.
struct LatencyOptions {
  /// Their time slice (kMinTimeSlice to kMaxTimeSlice); zero: the kernel's.
  std::chrono::microseconds slice{100};
  /// Whether the threads they start get the same slice (felt: all its threads are on the path).
  SliceInheritance slice_inheritance = SliceInheritance::kThisThreadOnly;
  /// SCHED_FIFO priority for them instead of a slice; 0: the normal policy.
  int realtime_priority = 0;
  /// Every idle core's wake-up latency, held while the program runs; nullopt: the system's.
  std::optional<std::chrono::microseconds> cpu_wakeup_latency;
  /// Idle cores spin this long after each touch; zero: they halt as usual.
  std::chrono::milliseconds spin_idle_cores{0};
  /// The spinners spin from the start until the program ends, whatever the touches.
  bool spin_until_exit = false;
};

/// How apply() names the threads and the flags that set the options in what it reports.
struct LatencyNames {
  std::string threads = "haptic threads";
  std::string slice = "--slice-us";
  std::string realtime = "--realtime";
  std::string cpu_wakeup_latency = "--cpu-wakeup-latency-us";
  std::string spin_idle_cores = "--spin-idle-cores-ms";
};

/// What apply() holds while the program runs, and what it got.
class AppliedLatency {
 public:
  /// Puts the calling thread on the haptic path as asked (SCHED_FIFO, else the slice), as
  /// apply() did for its caller, whose notes and errors say what that got.
  void schedule_this_thread() const { schedule(options_, nullptr); }

  /// The spinners to touch at every haptic update; nullptr when idle cores halt.
  IdleCoreSpinners* spinners() const { return spinners_.get(); }
  /// What the program got, a line each, for its standard output.
  const std::vector<std::string>& notes() const { return notes_; }
  /// What it asked for and did not get, a line each ("FLAG: why"), for its standard error.
  const std::vector<std::string>& errors() const { return errors_; }

 private:
  friend AppliedLatency apply(const LatencyOptions&, const LatencyNames&);
  AppliedLatency(const LatencyOptions& options, const LatencyNames& names)
      : options_(options), names_(names) {}

  /// Schedules the calling thread; with `report`, says in it what it got or why not.
  static void schedule(const LatencyOptions& options, AppliedLatency* report);

  LatencyOptions options_;
  LatencyNames names_;
  std::optional<CpuWakeupLatencyLimit> wakeup_limit_;
  std::unique_ptr<IdleCoreSpinners> spinners_;
  std::vector<std::string> notes_;
  std::vector<std::string> errors_;
};

/// Holds the process-wide requests (the cores' wake-up latency, the spinners) and schedules the
/// calling thread. What could not be had is reported, never fatal: the program runs without it.
AppliedLatency apply(const LatencyOptions& options, const LatencyNames& names = {});

}  // namespace felt
