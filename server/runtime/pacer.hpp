#pragma once
// When a scene's steps are due. While it runs, simulated time follows `scale` times the time of
// a clock from an origin, set again whenever the scene starts, resumes, changes scale, jumps
// (a reset, a restored state, requested steps) or falls too far behind; a paused scene takes
// no paced steps. Simulated time is counted from the origin's, never from 0, and turned into
// the clock's integer ticks only once it is known to fit, so that no scale in (0, 100] and no
// clock overflows: a scale of 1e-300 makes the next step due "far ahead", not in the past.

#include "core/math/types.hpp"
#include "runtime/clock.hpp"

namespace felt {

class Pacer {
 public:
  /// Lagging further than this (simulated seconds, times the scale when it is above 1) behind
  /// the clock re-synchronises instead of catching up, so that a slow scene runs slower than
  /// real time rather than stepping in bursts.
  static constexpr double kMaxLagSeconds = 0.1;
  /// The furthest ahead a step is ever said to be due: a scale too slow for any step to fall
  /// due within it holds the scene as good as still (the physics thread wakes long before).
  static constexpr std::chrono::seconds kFarAhead{1'000'000};

  Pacer(const Clock& clock, Real time_step) : clock_(clock), time_step_(time_step) {}

  bool paused() const { return paused_; }
  double scale() const { return scale_; }
  void pause() { paused_ = true; }
  void resume() {
    paused_ = false;
    restart();
  }
  void set_scale(double scale) {
    scale_ = scale;
    restart();
  }
  /// The origin is set again at the next lag(): the scene's clock jumped, or it was stopped.
  void restart() { restarting_ = true; }
  bool restarting() const { return restarting_; }

  /// How far (simulated seconds) a scene at `sim_time` is behind the clock now: steps are due
  /// while it is at least one time step.
  double lag(double sim_time);
  /// When the step after `sim_time` is due (at most kFarAhead after the origin).
  Clock::time_point next_due(double sim_time) const;

 private:
  const Clock& clock_;
  Real time_step_;
  bool paused_ = false;
  double scale_ = 1;
  bool restarting_ = true;
  Clock::time_point origin_{};
  double sim_origin_ = 0;  ///< where the scene should be at origin_ (simulated seconds)
};

}  // namespace felt
