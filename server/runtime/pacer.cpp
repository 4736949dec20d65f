#include "runtime/pacer.hpp"

#include <algorithm>

namespace felt {
namespace {

using Seconds = std::chrono::duration<double>;

}  // namespace

double Pacer::lag(double sim_time) {
  const Clock::time_point now = clock_.now();
  if (restarting_) {
    origin_ = now;
    sim_origin_ = sim_time;
    restarting_ = false;
  }
  // the clock's ticks since the origin fit a double; scaled, they only shrink or grow 100-fold
  double lag = scale_ * Seconds(now - origin_).count() - (sim_time - sim_origin_);
  if (lag > kMaxLagSeconds * std::max(1.0, scale_)) {
    // from now on, one step behind
    origin_ = now;
    sim_origin_ = sim_time + time_step_;
    lag = time_step_;
  }
  return lag;
}

Clock::time_point Pacer::next_due(double sim_time) const {
  const double after_origin = (sim_time - sim_origin_ + time_step_) / scale_;
  if (!(after_origin < Seconds(kFarAhead).count())) return origin_ + kFarAhead;
  // rounded up: a wake a tick early would find the step not yet due, and look again at once
  return origin_ + std::chrono::ceil<Clock::duration>(Seconds(after_origin));
}

}  // namespace felt
