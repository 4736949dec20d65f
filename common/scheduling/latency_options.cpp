#include "scheduling/latency_options.hpp"

#include <algorithm>

namespace felt {

void AppliedLatency::schedule(const LatencyOptions& options, AppliedLatency* report) {
  if (options.realtime_priority > 0) {
    const auto made = make_this_thread_realtime(options.realtime_priority);
    if (made) {
      if (report) {
        report->notes_.push_back(report->names_.threads + ": SCHED_FIFO priority " +
                                 std::to_string(options.realtime_priority));
      }
      return;
    }
    if (report) {
      report->errors_.push_back(report->names_.realtime + ": " + made.error() + "; the " +
                                report->names_.threads + " keep the normal policy");
    }
  }
  if (options.slice.count() == 0) return;
  const auto requested = request_time_slice(options.slice, options.slice_inheritance);
  if (!report) return;
  if (requested) {
    report->notes_.push_back(report->names_.threads + ": " + std::to_string(options.slice.count()) +
                             " us time slice");
  } else {
    report->errors_.push_back(report->names_.slice + ": " + requested.error());
  }
}

AppliedLatency apply(const LatencyOptions& options, const LatencyNames& names) {
  AppliedLatency applied(options, names);
  AppliedLatency::schedule(options, &applied);
  if (options.cpu_wakeup_latency) {
    const auto limit = *options.cpu_wakeup_latency;
    auto held = CpuWakeupLatencyLimit::hold(limit);
    if (held) {
      applied.wakeup_limit_ = std::move(*held);
      applied.notes_.push_back("idle cores: wake-up latency held at " +
                               std::to_string(limit.count()) + " us" +
                               (limit.count() == 0 ? " (they poll)" : ""));
    } else {
      applied.errors_.push_back(names.cpu_wakeup_latency + ": " + held.error());
    }
  }
  if (options.spin_idle_cores.count() > 0 || options.spin_until_exit) {
    auto started =
        IdleCoreSpinners::start(std::max(options.spin_idle_cores, std::chrono::milliseconds(1)));
    if (!started) {
      applied.errors_.push_back(names.spin_idle_cores + ": " + started.error());
      return applied;
    }
    applied.spinners_ = std::move(*started);
    const std::string spinners =
        " (" + std::to_string(applied.spinners_->cores()) + " SCHED_IDLE spinners)";
    if (options.spin_until_exit) {
      applied.spinners_->spin_until_destroyed();
      applied.notes_.push_back("idle cores: kept awake until exit" + spinners);
    } else {
      applied.notes_.push_back("idle cores: kept awake for " +
                               std::to_string(options.spin_idle_cores.count()) +
                               " ms after each haptic update" + spinners);
    }
  }
  return applied;
}

}  // namespace felt
