#pragma once
// How stiff a local renderer may make a contact whose surface answers the device late (issue 26;
// Schuwerk et al. adapt the client's stiffness to the delay). The rule is the stability
// condition of a sampled, delayed virtual wall (Gil, Avello & Rubio, "Stability analysis of a
// 1 DOF haptic interface using the Routh-Hurwitz criterion", IEEE TCST 12(4), 2004): a wall of
// stiffness K rendered at period T, its force d seconds late, on a device with physical damping
// b, is stable (and, with this margin, passive) while b > K (T/2 + d). A local model renders
// the contact itself without delay, but the surface yields to the push, and moves, only a
// round trip later: that round trip (and the model's age) is the d the rule takes.

#include <algorithm>
#include <cmath>

#include "core/math/types.hpp"

namespace felt {

/// The stiffness to render with: `stiffness` (N/m), lowered to damping / (period/2 + delay)
/// where that is smaller; `damping` (N·s/m) is what the device and the hand holding it
/// provide, `period` the servo period and `delay` the surface's delay (s). Never above
/// `stiffness`, never negative; a non-finite or negative delay counts as none.
inline Real passive_stiffness(Real stiffness, Real damping, Real period, Real delay) {
  const Real late = std::isfinite(delay) ? std::max(delay, Real{0}) : Real{0};
  const Real lag = std::max(period, Real{0}) / 2 + late;
  if (!(lag > 0)) return stiffness;
  return std::clamp(std::max(damping, Real{0}) / lag, Real{0}, stiffness);
}

}  // namespace felt
