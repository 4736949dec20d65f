#pragma once
// How stiff a local renderer may make a contact whose surface answers the device late (issue 26;
// Schuwerk et al. adapt the client's stiffness to the delay). The rule is the stability
// condition of a sampled, delayed virtual wall (Gil, Avello & Rubio, "Stability analysis of a
// 1 DOF haptic interface using the Routh-Hurwitz criterion", IEEE TCST 12(4), 2004): a wall of
// stiffness K rendered at period T, its force d seconds late, on a device with physical damping
// b, is stable while b > K (T/2 + d); with d = 0 it is Colgate & Schenkel's passivity condition
// b > K T/2 (1997). A local model renders the contact at once against its copy of the surface;
// what comes a round trip late is the surface's give under the push. Against a surface of
// stiffness k_o the contact is the series spring k_eff = K k_o / (K + k_o), so the part of K
// that is late is K − k_eff = K · K / (K + k_o), and the rule becomes
// b > K T/2 + K · K / (K + k_o) · d (this split is ours: the wall's condition applied to the late
// part alone). k_o unknown (0) counts as a surface that gives entirely (the whole K late: Gil's
// rule as it stands); a rigid surface (k_o → ∞) leaves only the sampling's K ≤ 2b/T.

#include <algorithm>
#include <cmath>

#include "core/math/types.hpp"

namespace felt {

/// The stiffness to render with: `stiffness` (N/m), lowered to the largest K that keeps
/// damping > K (period/2 + delay · K / (K + surface_stiffness)) where that is smaller;
/// `damping` (N·s/m) is what the device and the hand holding it provide, `period` the servo
/// period, `delay` the surface's delay (s) and `surface_stiffness` the touched surface's (N/m;
/// 0: unknown). Never above `stiffness`, never negative; a non-finite or negative delay counts
/// as none, a non-finite or negative surface stiffness as unknown.
inline Real passive_stiffness(Real stiffness, Real damping, Real period, Real delay,
                              Real surface_stiffness = 0) {
  const Real b = std::max(damping, Real{0});
  const Real half_period = std::max(period, Real{0}) / 2;
  const Real late = std::isfinite(delay) ? std::max(delay, Real{0}) : Real{0};
  const Real k_o = std::isfinite(surface_stiffness) ? std::max(surface_stiffness, Real{0}) : 0;
  const Real lag = half_period + late;
  if (!(lag > 0)) return stiffness;
  // the positive root of K² lag + K (k_o T/2 − b) − b k_o = 0 (the rule's equality multiplied
  // by K + k_o), in the form that does not cancel when k_o T/2 ≫ b
  const Real linear = k_o * half_period - b;
  const Real spread = std::sqrt(linear * linear + 4 * lag * b * k_o);
  const Real root = linear > 0 ? 2 * b * k_o / (linear + spread) : (spread - linear) / (2 * lag);
  const Real bound = k_o > 0 ? root : b / lag;
  return std::clamp(bound, Real{0}, stiffness);
}

}  // namespace felt
