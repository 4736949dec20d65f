#pragma once
// First-order explicit schemes (thesis 1 §4.2 and §4.5).

#include "core/integrate/integrator.hpp"

namespace felt {

/// Forward Euler: x += h v(t), v += h a(t). First order; gains energy on any oscillation.
class ExplicitEuler final : public Integrator {
 public:
  std::string_view name() const override { return "explicit_euler"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  /// R(z) = 1 + z: h ≤ c/ω² on an underdamped mode, no step at all on an undamped one.
  Real step_limit(const OscillatorMode& mode) const override;

 private:
  std::vector<Vec3> force_;
};

/// Semi-implicit (symplectic) Euler: v += h a(x(t)), x += h v(t+h). First order, symplectic:
/// its energy error stays bounded, stable for h < 2/ω on an undamped oscillator.
class SymplecticEuler final : public Integrator {
 public:
  std::string_view name() const override { return "symplectic_euler"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  /// Its amplification matrix has the trace and determinant of position Verlet's.
  Real step_limit(const OscillatorMode& mode) const override { return verlet_step_limit(mode); }

 private:
  std::vector<Vec3> force_;
};

}  // namespace felt
