#include "runtime/stats_window.hpp"

#include <algorithm>

namespace felt {

using Seconds = std::chrono::duration<double>;

StatsWindow::StatsWindow(Clock::time_point start, double sim_time)
    : start_(start), sim_start_(sim_time) {}

void StatsWindow::add_step(Clock::duration took, const StepProfile& cloth,
                           const StepProfile& solid) {
  stepping_ += took;
  ++steps_;
  for (std::size_t s = 0; s < kStepStageCount; ++s) {
    cloth_.seconds[s] += cloth.seconds[s];
    solid_.seconds[s] += solid.seconds[s];
  }
}

std::optional<StepRates> StatsWindow::close_if_full(Clock::time_point now, double sim_time) {
  if (!full(now)) return std::nullopt;
  const double window = Seconds(now - start_).count();
  StepRates rates;
  rates.real_time_factor = (sim_time - sim_start_) / window;
  rates.ms_per_step = steps_ ? 1e3 * Seconds(stepping_).count() / static_cast<double>(steps_) : 0;
  const double steps = std::max<double>(1, static_cast<double>(steps_));
  for (std::size_t s = 0; s < kStepStageCount; ++s) {
    rates.cloth_profile.seconds[s] = cloth_.seconds[s] / steps;
    rates.solid_profile.seconds[s] = solid_.seconds[s] / steps;
  }
  *this = StatsWindow(now, sim_time);
  return rates;
}

}  // namespace felt
