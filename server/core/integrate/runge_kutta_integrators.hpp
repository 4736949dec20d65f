#pragma once
// Higher-order explicit Runge–Kutta schemes on the state X = [x, v] with derivative
// F(X) = [v, M⁻¹ f] (thesis 1 §4.1–§4.2). A pinned particle (inverse mass 0) has F = 0: it
// stays where it is with v = 0.

#include <algorithm>
#include <array>
#include <limits>

#include "core/integrate/integrator.hpp"

namespace felt {

/// Explicit midpoint (thesis 1 §4.2): X(t+h) = X + h F(X + ½h F(X), t + ½h). Second order, two
/// force evaluations per step. On an undamped oscillator its amplification factor is
/// R(iωh) = 1 + iωh − (ωh)²/2, so the energy grows by exactly 1 + (ωh)⁴/4 per step: unstable for
/// every h, only slowly for small ωh.
class Midpoint final : public Integrator {
 public:
  std::string_view name() const override { return "midpoint"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  /// R(z) = 1 + z + z²/2: no step on an undamped mode, a damped one up to where its damping
  /// outweighs the growth.
  Real step_limit(const OscillatorMode& mode) const override;

 private:
  std::vector<Vec3> dx_, dv_, x_mid_, v_mid_;
};

/// Classic fourth-order Runge–Kutta (thesis 1 §4.2), four force evaluations per step. On an
/// undamped oscillator |R(iωh)|² = 1 − (ωh)⁶/72 + (ωh)⁸/576 (R(z) = Σₖ₌₀⁴ zᵏ/k!; Hairer &
/// Wanner, Solving ODEs II, §IV.2): energy decays slowly for ωh < 2√2 and the scheme is
/// unstable beyond (2.785 is the limit on the negative real axis, i.e. for pure damping).
class RungeKutta4 final : public Integrator {
 public:
  std::string_view name() const override { return "rk4"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  Real step_limit(const OscillatorMode& mode) const override;

 private:
  std::vector<Vec3> dx_, dv_, x_stage_, v_stage_, dx_sum_, dv_sum_;
};

/// Adaptive Runge–Kutta with the Dormand–Prince 5(4) embedded pair (Dormand & Prince 1980,
/// coefficients as in Hairer, Nørsett & Wanner, Solving ODEs I, §II.5 Table 5.2): the fifth-order
/// solution is kept (local extrapolation), the fourth-order one only estimates the error. Chosen
/// over Bogacki–Shampine 3(2) because tight tolerances (1e-8 m) then need far fewer force
/// evaluations. Its stability region reaches −3.31 on the real axis (BS3: −2.51) but only ±1.0i
/// on the imaginary one (BS3: ±√3 i); the error control keeps ω dt far below either (≈ 0.1 at
/// 1e-8 m on a 1 m oscillation) unless the step cap forces longer steps.
///
/// Each step() advances exactly h, subdivided into internal steps whose size the error control
/// picks (thesis 1 §4.2 "adaptive step", which estimates the error by one step of h against two
/// of h/2; the embedded pair gets it from the same stages, HNW I §II.4). The last accepted
/// internal step size is kept between calls. A call takes at most max_internal_steps() internal
/// steps, rejected ones included: an internal step is never shorter than the remaining interval
/// divided by the steps left, and a step of that smallest size is accepted whatever its error,
/// so a call always finishes.
class AdaptiveRungeKutta final : public Integrator {
 public:
  static constexpr Real kDefaultTolerance = 1e-6;  ///< m
  static constexpr int kDefaultMaxInternalSteps = 10000;

  /// `tolerance`: the largest position error, in metres, allowed on any particle per internal
  /// step (an absolute tolerance; relative tolerance 0 in HNW I (4.10)).
  explicit AdaptiveRungeKutta(Real tolerance = kDefaultTolerance,
                              int max_internal_steps = kDefaultMaxInternalSteps);

  std::string_view name() const override { return "adaptive_rk"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  /// Forgets the internal step size: the next call starts by trying one internal step of h.
  void reset() override { internal_step_ = 0; }

  Real tolerance() const { return tolerance_; }
  Real position_tolerance() const override { return tolerance_; }
  int max_internal_steps() const { return max_internal_steps_; }
  /// Lowers the internal steps of each later call below max_internal_steps() (the world's step
  /// budget); a cap below 1 counts as 1.
  void limit_internal_steps(int cap) override { internal_step_cap_ = std::max(1, cap); }
  /// Internal steps the last call took, rejected ones included (each costs six force
  /// evaluations).
  int last_internal_steps() const override { return last_internal_steps_; }
  /// The last call accepted an internal step whose error was beyond the tolerance, because
  /// its cap of internal steps left no shorter one.
  bool last_step_capped() const override { return last_step_capped_; }
  /// How many of those were rejected.
  int last_rejected_steps() const { return last_rejected_steps_; }
  /// The internal step size the next call tries first; 0 before the first call.
  Real internal_step() const { return internal_step_; }
  /// The longest internal step with which the kept fifth-order solution keeps `mode` from
  /// growing, R(z) = Σₖ₌₀⁵ zᵏ/k! + z⁶/600 (Hairer & Wanner, Solving ODEs II, §IV.2). The error
  /// control keeps far below it; only the cap of internal steps forces longer ones, and a body
  /// whose fastest mode needs more of them a step than its budget can never be stepped stably.
  Real internal_step_limit(const OscillatorMode& mode) const;

  static constexpr int kStages = 7;

 private:
  /// Evaluates stage `s` (1…6) of an internal step of size `dt` from the state (x, v) at time t.
  void evaluate_stage(const DynamicSystem& system, const ParticleState& state, int s, Real t,
                      Real dt);

  Real tolerance_;
  int max_internal_steps_;
  int internal_step_cap_ = std::numeric_limits<int>::max();
  Real internal_step_ = 0;
  bool last_step_capped_ = false;
  int last_internal_steps_ = 0;
  int last_rejected_steps_ = 0;
  std::array<std::vector<Vec3>, kStages> dx_, dv_;  ///< the stage derivatives k_s = [v, a]
  std::vector<Vec3> x_stage_, v_stage_;
};

}  // namespace felt
