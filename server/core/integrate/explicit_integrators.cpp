#include "core/integrate/explicit_integrators.hpp"

#include <array>

namespace felt {

void ExplicitEuler::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  force_.resize(state.size());
  system.compute_forces(state.x, state.v, t, force_);
  const auto inv_mass = system.inv_mass();
  for (std::size_t p = 0; p < state.size(); ++p) {
    state.x[p] += h * state.v[p];
    state.v[p] += h * inv_mass[p] * force_[p];
  }
}

Real ExplicitEuler::step_limit(const OscillatorMode& mode) const {
  static constexpr std::array<Real, 2> kStabilityPolynomial{1, 1};
  return polynomial_step_limit(kStabilityPolynomial, mode);
}

void SymplecticEuler::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  force_.resize(state.size());
  system.compute_forces(state.x, state.v, t, force_);
  const auto inv_mass = system.inv_mass();
  for (std::size_t p = 0; p < state.size(); ++p) {
    state.v[p] += h * inv_mass[p] * force_[p];
    state.x[p] += h * state.v[p];
  }
}

}  // namespace felt
