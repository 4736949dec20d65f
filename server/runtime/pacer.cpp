#include "runtime/pacer.hpp"

#include <algorithm>

namespace felt {
namespace {

using Seconds = std::chrono::duration<double>;

}  // namespace

double Pacer::lag(double sim_time) {
  const Clock::time_point now = clock_.now();
  if (restarting_) {
    origin_ = now - std::chrono::duration_cast<Clock::duration>(Seconds(sim_time / scale_));
    restarting_ = false;
  }
  double lag = scale_ * Seconds(now - origin_).count() - sim_time;
  if (lag > kMaxLagSeconds * std::max(1.0, scale_)) {
    origin_ += std::chrono::duration_cast<Clock::duration>(Seconds((lag - time_step_) / scale_));
    lag = time_step_;
  }
  return lag;
}

Clock::time_point Pacer::next_due(double sim_time) const {
  return origin_ +
         std::chrono::duration_cast<Clock::duration>(Seconds((sim_time + time_step_) / scale_));
}

}  // namespace felt
