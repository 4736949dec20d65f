#pragma once
// The real-time factor, the wall time per step and where a step spent it, stage by stage, of a
// scene, each averaged over a window of half a second of its clock, so that a status line or
// GetStats shows how the scene runs now rather than since it started.

#include <cstdint>
#include <optional>

#include "core/step/step_profile.hpp"
#include "runtime/clock.hpp"

namespace felt {

struct StepRates {
  double real_time_factor = 0;  ///< simulated seconds per second of the clock
  double ms_per_step = 0;       ///< milliseconds of the clock one step took, on average
  StepProfile cloth_profile;    ///< seconds per step in each stage of the cloths' step
  StepProfile solid_profile;    ///< and of the solids'
};

class StatsWindow {
 public:
  static constexpr std::chrono::milliseconds kLength{500};

  /// A window that opens at `start` with the scene at `sim_time`.
  StatsWindow(Clock::time_point start, double sim_time);

  /// One step, which took `took`, of which the cloths' and the solids' stages took `cloth` and
  /// `solid`.
  void add_step(Clock::duration took, const StepProfile& cloth = {}, const StepProfile& solid = {});
  /// Whether the window is kLength long at `now`.
  bool full(Clock::time_point now) const { return now - start_ >= kLength; }
  /// The window's rates once it is at least kLength long, and then a new window from `now`
  /// with the scene at `sim_time`; nothing before.
  std::optional<StepRates> close_if_full(Clock::time_point now, double sim_time);

 private:
  Clock::time_point start_;
  double sim_start_;
  Clock::duration stepping_{};
  std::uint64_t steps_ = 0;
  StepProfile cloth_, solid_;  ///< summed over the window's steps
};

}  // namespace felt
