#include "core/integrate/imex_integrator.hpp"

namespace felt {

void ImexIntegrator::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  // without linear forces A = M and the scheme is symplectic Euler
  linear_step_.assemble(system, state, t, h);
  linear_step_.solve(system.inv_mass(), h, dv_);
  apply_velocity_change(system.inv_mass(), h, dv_, state);
}

}  // namespace felt
