#pragma once
// The step an explicit integrator can take on a cloth (issue 27, "stable steps chosen, not
// hoped for"): from the fastest mode of its springs and anchors, as the solids' stable step
// comes from theirs, and the integrator's stability limit on that mode.

#include <array>
#include <functional>
#include <optional>
#include <string_view>

#include "core/cloth/cloth_body.hpp"
#include "core/integrate/stability_limit.hpp"

namespace felt {

/// The fastest mode of a cloth at its rest shape and the least and most damping it can feel.
struct ClothFastestMode {
  Real omega_squared = 0;  ///< λ_max(M⁻¹K), 1/s²
  /// 1/s: drag over the heaviest free particle's mass plus the smallest damping-to-stiffness
  /// ratio d/k among its spring kinds and anchors times ω² (the springs damp along themselves
  /// only, so D ⪰ (d/k)_min K at rest and the mode's Rayleigh quotient of M⁻¹D is at least this)
  Real least_rate = 0;
  Real most_rate = 0;  ///< λ_max(M⁻¹D), 1/s
};

/// From the eigenvalues (Lanczos, largest_eigenvalue) of the cloth's Jacobian at its rest shape
/// with its pins, anchors and current spring constants.
ClothFastestMode fastest_mode(const ClothBody& body);

/// How far below its integrator's limit a cloth's step stays. The rest shape's Jacobian has no
/// transverse stiffness; a spring stretched by ε gains ε/(1 + ε) of k across itself (0.09 k at
/// the stretch limiter's 10 %), and its damping acts along it only. Measured by bisection
/// (cloth_stable_step_margin_test), the estimate without the margin is where the symplectic and
/// Verlet schemes blow up, within 0.5 %, at rest and stretched 10 % alike (rk4 4-7 % later):
/// the margin is for what no rest shape shows (a grab's anchor, contact, a cloth far from its
/// rest shape), not for the estimate's error.
inline constexpr Real kClothStepMargin = 0.8;

/// kClothStepMargin times the longest step with which the body's integrator keeps its fastest
/// mode from growing, at the least and at the most damping that mode can feel; 0 when no step
/// can (explicit Euler on undamped springs), kNoStepLimit when the integrator has no limit.
Real stable_cloth_step(const ClothBody& body);

/// kClothStepMargin times the longest step `limit` allows the body's fastest mode, at the least
/// and at the most damping it can feel (the steps of a scheme other than the body's integrator:
/// adaptive_rk's internal ones); kNoStepLimit when the body has no mode to limit.
Real stable_cloth_step(const ClothBody& body,
                       const std::function<Real(const OscillatorMode&)>& limit);

/// stable_cloth_step of one cloth, found again only when what it depends on changes: the
/// integrator, the spring constants, the drag, the anchors' constants and the pins (a grab
/// moves its anchor's target every step, which changes nothing here).
class CachedStableStep {
 public:
  Real of(const ClothBody& body);

 private:
  struct Inputs {
    std::string_view integrator;
    std::array<SpringParams, kSpringKindCount> springs{};
    Real drag = 0;
    std::size_t anchors = 0;
    Real anchor_stiffness = 0;
    Real anchor_damping = 0;
    std::size_t pinned = 0;

    bool operator==(const Inputs&) const = default;
  };
  static Inputs inputs_of(const ClothBody& body);

  std::optional<Inputs> inputs_;
  Real step_ = kNoStepLimit;
};

}  // namespace felt
