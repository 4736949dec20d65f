#pragma once
// The Verlet family (thesis 1 §4.5; Jakobsen 2001, schemes from [Mor01]). All three are the
// Störmer–Verlet method: second order, one force evaluation per step, symplectic, so on an
// undamped oscillator the energy error stays bounded, O((ωh)²), and they are stable for ωh < 2
// (Hairer, Lubich & Wanner, "Geometric numerical integration illustrated by the Störmer–Verlet
// method", Acta Numerica 12, 2003). They differ in what they keep between steps and so in how
// they take edits made to the state from outside (stretch limiting, pins, rollbacks). A pinned
// particle (inverse mass 0) never moves and keeps v = 0; once unpinned it starts afresh.

#include "core/integrate/integrator.hpp"

namespace felt {

/// Position (Störmer) Verlet, thesis 1 §4.5 [reconstructed there]: x(t+h) = 2x − x(t−h) + h² a,
/// with the velocity implicit in x − x_prev, so a position edited from outside (Jakobsen's
/// constraint projection) changes the velocity by itself. Its local error is O(h⁴) as the thesis
/// says, its global error O(h²).
///
/// - Start (first step, after reset()): x_prev = x − h v + ½h² a, which makes the first step the
///   Taylor step x + h v + ½h² a, exact for a constant force.
/// - A change of step size rescales the previous displacement, the time-corrected Verlet of
///   Dummer (2005), but with the acceleration term ½h(h + h_prev) a instead of his h² a:
///     x_new = x + (x − x_prev) h/h_prev + ½ h (h + h_prev) a.
///   That is the three-point second difference on an uneven grid solved for x_new; it is exact
///   for a constant force (Dummer's h² a is off by ½ a h (h − h_prev) on each change) and equals
///   2x − x_prev + h² a for equal steps.
/// - Reported velocity: state.v = (x_new − x)/h + ½h a, the backward difference (which is
///   v(t + ½h) + O(h²), only a first-order estimate of v(t+h)) corrected by the half step of
///   acceleration. It is v(t+h) + O(h²), exact for a constant force, and no force evaluation
///   more. The central difference (x(t+h) − x(t−h))/(2h) of the thesis would lag a step. The
///   velocity feeds only velocity-dependent forces (damping) at the next step; being second
///   order it keeps the scheme second order with damping.
/// - A velocity edited from outside (state.v differs from what the last step wrote) restarts
///   that particle as at the start, from the new velocity; so does unpinning a particle.
class PositionVerlet final : public Integrator {
 public:
  std::string_view name() const override { return "verlet"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  Real step_limit(const OscillatorMode& mode) const override {
    return second_order_verlet_step_limit(mode);
  }
  void reset() override { h_prev_ = 0; }

 private:
  std::vector<Vec3> force_;
  std::vector<Vec3> x_prev_;  ///< positions one step back
  std::vector<Vec3> v_out_;   ///< the velocities the last step wrote, to notice edits; NaN
                              ///< for a pinned particle, which no velocity equals
  Real h_prev_ = 0;           ///< the last step size; 0: no history, start afresh
};

/// Velocity Verlet (Swope et al. 1982; thesis 1 §4.5):
///   v(t+½h) = v + ½h a(t),  x(t+h) = x + h v(t+½h),  v(t+h) = v(t+½h) + ½h a(t+h).
/// The force at the end of a step is kept for the start of the next, so a step costs one
/// evaluation. It is recomputed after reset(), when the particle count changes, or when the
/// state is not the one the last step left (edited from outside). A force that depends on the
/// velocity is evaluated at the end of the step with the predicted v + h a(t), which is v(t+h)
/// + O(h²) and keeps the scheme second order (Groot & Warren 1997's modified velocity Verlet
/// with λ = 1; their λ = ½, the half-step velocity, would make it first order with damping).
/// Note: a kept force includes the external forces of its own step, so an external force that
/// lasts one step acts ½h at the end of its step and ½h at the start of the next: the same
/// impulse, half a step later.
class VelocityVerlet final : public Integrator {
 public:
  std::string_view name() const override { return "velocity_verlet"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  Real step_limit(const OscillatorMode& mode) const override {
    return second_order_verlet_step_limit(mode);
  }
  void reset() override { force_valid_ = false; }

 private:
  std::vector<Vec3> force_;  ///< f(t) at the start of the next step, once valid
  std::vector<Vec3> v_predicted_;
  std::vector<Vec3> x_out_, v_out_;  ///< the state the last step left, to notice edits
  bool force_valid_ = false;
};

/// Leapfrog, kick–drift (thesis 1 §4.5 in the standard form, see the note there):
///   v(t+½h) = v(t−½h_prev) + ½(h_prev + h) a(t),   x(t+h) = x + h v(t+½h).
/// The kick by the mean of the two steps is the same three-point difference as in
/// PositionVerlet; it is h a(t) for equal steps and ½h a(t) at the start, where v(t−0) = v.
/// The half-step velocity is kept as its offset from the reported whole-step velocity,
///   state.v = v(t+h) ≈ v(t+½h) + ½h a(t)   (second order, exact for a constant force),
/// so that a velocity edited from outside moves the half-step velocity with it, as an impulse
/// at the whole step would.
class Leapfrog final : public Integrator {
 public:
  std::string_view name() const override { return "leapfrog"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  Real step_limit(const OscillatorMode& mode) const override {
    return second_order_verlet_step_limit(mode);
  }
  void reset() override { h_prev_ = 0; }

 private:
  std::vector<Vec3> force_;
  std::vector<Vec3> offset_;  ///< state.v − v(t−½h_prev) = ½h_prev a(t−h_prev); NaN for a
                              ///< pinned particle: it starts afresh when unpinned
  Real h_prev_ = 0;           ///< the last step size; 0: no half-step velocity yet
};

}  // namespace felt
