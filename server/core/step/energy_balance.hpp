#pragma once
// The energy check that slow growth cannot fool (issue 27): a passive body's mechanical energy
// E = kinetic + elastic + gravitational changes only by the work W that applied forces (a user's
// push, the wind) do on it, less what damping, collisions and constraints take away. So the
// budget B = E − W never rises in exact arithmetic; numerical growth makes it rise, slowly
// (explicit midpoint: by (ωh)⁴/4 of the energy per step) or fast. A rise of B, over a window of
// steps, above its lowest value since the body was last set, by more than a tolerance of the
// body's energy scale, is growth, whatever its rate per step.

#include <algorithm>
#include <limits>

#include "core/math/types.hpp"

namespace felt {

/// J; keeps rounding noise of a body at rest (or weightless) from counting as growth.
constexpr Real kEnergyFloor = 1e-9;

class EnergyBalance {
 public:
  /// How much larger a window's scale may count than the last closed window's. The scale of a
  /// window judged by its own largest energy grew with the growth it was to catch: a budget
  /// rising x times a window stayed within (1 − 1/x)/x ≤ 1/4 of it, so no steady exponential
  /// growth was ever flagged at the default tolerance of 1/4 (RK4 on an undamped spring at
  /// ωh = 2.87, 1.6 % above its limit: 10²¹ J after 1 s, no step flagged). Capped at twice the
  /// last window's scale, growth by more than a factor 2 a window is flagged.
  static constexpr Real kScaleGrowthPerWindow = 2;

  /// Starts over from mechanical energy `energy`: no work done yet, no window open.
  void reset(Real energy) {
    lowest_ = energy;
    work_ = 0;
    window_ = {};
    closed_scale_ = std::numeric_limits<Real>::infinity();
  }

  /// B after a step that leaves mechanical energy `energy` and in which applied forces did
  /// `work`.
  Real budget_after(Real energy, Real work) const { return energy - (work_ + work); }

  /// False when the step that leaves budget `budget` (budget_after) and energy scale `scale`
  /// closes a window of `window` steps whose lowest budget lies more than `tolerance` times the
  /// window's largest scale (at most kScaleGrowthPerWindow times the last window's) above the
  /// lowest budget before it. The scale is the body's kinetic and elastic energy plus its weight
  /// times its size (Mgℓ, so that a body at rest has one). Judging a window's lowest value, not
  /// each step's, lets a symplectic scheme's energy swing within a period (±ωh/2 of it) without
  /// counting as growth.
  bool within(Real budget, Real scale, Real tolerance, int window) const {
    if (window_.steps + 1 < window) return true;
    const Real lowest = std::min(window_.lowest, budget);
    const Real judged =
        std::min(std::max(window_.scale, scale), kScaleGrowthPerWindow * closed_scale_);
    return lowest - lowest_ <= tolerance * judged;
  }

  /// How far budget `budget` lies above the lowest since the balance started, J (0 below it):
  /// after a rescue, the growth the step before it could not undo.
  Real excess(Real budget) const { return std::max(Real{0}, budget - lowest_); }

  /// Takes a healthy step (as judged by within with the same arguments).
  void accept(Real energy, Real work, Real scale, int window) {
    work_ += work;
    const Real budget = energy - work_;
    window_.lowest = std::min(window_.lowest, budget);
    window_.scale = std::max(window_.scale, scale);
    if (++window_.steps < window) return;
    lowest_ = std::min(lowest_, window_.lowest);
    closed_scale_ = window_.scale;
    window_ = {};
  }

 private:
  struct Window {
    int steps = 0;
    Real lowest = std::numeric_limits<Real>::infinity();
    Real scale = 0;
  };
  Real lowest_ = 0;  ///< the lowest B of the closed windows since reset
  Real work_ = 0;    ///< applied work since reset
  /// the largest scale of the last closed window; none (infinite) before the first closes
  Real closed_scale_ = std::numeric_limits<Real>::infinity();
  Window window_;
};

/// What a step may give a particle at most, m/s: the speed `fastest` of the fastest particle
/// before the step, the acceleration `acceleration` (gravity and applied forces) times h, and
/// `reachable`, the speed the lightest particle would have with all the body's kinetic and
/// elastic energy.
struct SpeedSources {
  Real fastest = 0;
  Real acceleration = 0;
  Real reachable = 0;
};

/// The speed no particle may exceed after a step of length `h` of a body of size `size` (m):
/// `growth` times what the step could give a particle (`sources`) plus size / h, and never more
/// than `cap`. Free fall gains g h a step and passes at any length of the fall; a particle that
/// outruns its own body in a step and several times what its energy allows is exploding.
inline Real scaled_speed_limit(const SpeedSources& sources, Real size, Real h, Real growth,
                               Real cap) {
  return std::min(
      cap, growth * (sources.fastest + sources.acceleration * h + sources.reachable) + size / h);
}

}  // namespace felt
