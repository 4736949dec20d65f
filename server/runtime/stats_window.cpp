#include "runtime/stats_window.hpp"

namespace felt {

using Seconds = std::chrono::duration<double>;

StatsWindow::StatsWindow(Clock::time_point start, double sim_time)
    : start_(start), sim_start_(sim_time) {}

void StatsWindow::add_step(Clock::duration took) {
  stepping_ += took;
  ++steps_;
}

std::optional<StepRates> StatsWindow::close_if_full(Clock::time_point now, double sim_time) {
  if (!full(now)) return std::nullopt;
  const double window = Seconds(now - start_).count();
  StepRates rates;
  rates.real_time_factor = (sim_time - sim_start_) / window;
  rates.ms_per_step = steps_ ? 1e3 * Seconds(stepping_).count() / static_cast<double>(steps_) : 0;
  *this = StatsWindow(now, sim_time);
  return rates;
}

}  // namespace felt
