#pragma once
// The longest step with which an explicit integrator keeps one damped mode from growing: the
// stable step of a body is that of its fastest mode (issue 27, "stable steps chosen").

#include <limits>
#include <span>

#include "core/math/types.hpp"

namespace felt {

/// A mode of M ẍ = −K x − D ẋ in its own coordinate: ẍ = −ω² x − c ẋ, with ω² an eigenvalue of
/// M⁻¹K and c the damping rate the mode feels, 1/s.
struct OscillatorMode {
  Real omega_squared = 0;
  Real rate = 0;
};

/// No step limit: implicit schemes, and explicit ones that choose their own steps.
inline constexpr Real kNoStepLimit = std::numeric_limits<Real>::infinity();

/// The largest step with which symplectic Euler and position Verlet with the backward-difference
/// velocity (the solids' time-corrected Verlet) stay stable on `mode`: ω² h² + 2 c h ≤ 4 (the
/// Jury conditions on their 2 × 2 amplification matrix, whose trace is 2 − hc − h²ω² and whose
/// determinant is 1 − hc; ωh ≤ 2 undamped, Hairer, Lubich & Wanner, Geometric Numerical
/// Integration, §I.5).
Real verlet_step_limit(const OscillatorMode& mode);

/// The same for the cloth's Verlet family (verlet, velocity_verlet, leapfrog), whose damping
/// sees a second-order velocity (verlet_integrators.hpp): ω² h² + 4 c h ≤ 4. The damping
/// term counts twice as much as with the backward difference; fitted to the three schemes'
/// bisected limits at ζ = 0.02 to 1.5 (within 1e-4, all three alike) and checked there by
/// stability_limit_test. Undamped, ωh ≤ 2 as above.
Real second_order_verlet_step_limit(const OscillatorMode& mode);

/// The largest H such that a one-step method with stability polynomial R(z) = Σ aₖ zᵏ
/// (`coefficients` a₀, a₁, ...) keeps |R(hλ)| ≤ 1 for every h in (0, H] and both roots λ of
/// λ² + cλ + ω² = 0 (Hairer & Wanner, Solving ODEs II, §IV.2). 0 when even the shortest step
/// grows the mode (explicit Euler or midpoint on an undamped one), kNoStepLimit when ω and c
/// are both 0.
Real polynomial_step_limit(std::span<const Real> coefficients, const OscillatorMode& mode);

}  // namespace felt
