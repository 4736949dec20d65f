#pragma once
// How a world judges the state a step leaves (docs/scenes.md, "Numerical health"), shared by the
// cloth and the solid systems; a scene sets them with its "health" keys (docs/scenes.md).

#include <limits>

#include "core/math/types.hpp"

namespace felt {

struct HealthSettings {
  /// Off, a step costs what its integrator and the scene's features cost, nothing more: no
  /// energy or speed check, no copy of the state to roll back to, no rescue. A body whose state
  /// turns non-finite still never reaches anyone: it starts over from its rest shape, at rest,
  /// reported unrecoverable.
  bool enabled = true;
  /// A body's mechanical energy (kinetic, elastic, gravitational) less the work applied forces
  /// did on it, at its lowest over a window, may lie above its lowest value since the body was
  /// last set (its start, an edit, a rescue) by at most this fraction of the body's energy scale
  /// (EnergyBalance): damping, collisions and stretch limiting only take energy away, so a rise
  /// beyond it is numerical growth, however slow. Infinity turns the check off.
  Real energy_tolerance = 0.25;
  /// s; the window (at least kMinWindowSteps steps)
  Real energy_window = 0.25;
  static constexpr int kMinWindowSteps = 8;
  /// A particle may leave a step at most this factor times faster than the fastest particle was
  /// before it, plus |g| h and the body's size over h (scaled_speed_limit): free fall is never
  /// flagged, a mode that grows geometrically within a step is.
  Real speed_growth = 4;
  /// A body rescued with k substeps keeps them; after this many seconds without a rescue it tries
  /// k/2, and twice as long before the next try each time a halving had to be undone.
  Real relax_after = 1;
  /// Explicit cloth integrators take as many substeps as their stable step needs
  /// (cloth_stable_step.hpp) instead of waiting for a step to fail.
  bool auto_substeps = true;
  /// The most work one step of a body may do: substeps, over every attempt of the step
  /// together (the first, the stable step's, the rescue's retries), each of adaptive_rk's
  /// internal steps counting as one. Each substep's integrator call and each part of its
  /// stretch limiting (sweeps, projection steps) get at most an even share of what is left.
  /// A step that reaches it is reported and goes on with what it can afford (docs/scenes.md
  /// "health").
  int step_budget = kDefaultStepBudget;
  static constexpr int kDefaultStepBudget = 1000;
};

}  // namespace felt
