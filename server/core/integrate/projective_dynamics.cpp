#include "core/integrate/projective_dynamics.hpp"

#include "core/math/check.hpp"

namespace felt {

ProjectiveDynamics::ProjectiveDynamics(int iterations, Real chebyshev_rho)
    : iterations_(iterations), chebyshev_rho_(chebyshev_rho) {
  FELT_CHECK(iterations >= 1 && iterations <= kMaxIterations);
  FELT_CHECK(chebyshev_rho >= 0 && chebyshev_rho <= kMaxChebyshevRho);
}

void ProjectiveDynamics::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  const auto inv_mass = system.inv_mass();
  const std::size_t n = state.size();
  if (!system.distance_constraints(springs_)) springs_.clear();
  pairs_.clear();
  for (const DistanceConstraint& s : springs_.constraints) {
    pairs_.push_back({s.i, s.j, s.stiffness, s.damping});
  }
  others_.resize(n);
  system.compute_forces_besides_constraints(state.x, state.v, t, others_);
  linear_step_.set_pairs(pairs_);
  iterate_ = state.x;
  previous_ = state.x;
  Real omega = 1;
  last_iterations_ = std::min(iterations_, cap_);
  for (int k = 0; k < last_iterations_; ++k) {
    project(state, iterate_);
    linear_step_.assemble(inv_mass, state, h, force_);
    linear_step_.solve(inv_mass, h, dv_);
    omega = chebyshev_weight(k, omega);
    for (std::size_t p = 0; p < n; ++p) {
      if (inv_mass[p] == 0) continue;
      const Vec3 solved =
          state.x[p] + h * (state.v[p] + dv_.row(static_cast<Eigen::Index>(p)).transpose());
      // Wang 2015, eq. 13: x⁺ = ω (γ (x̂ − x) + x − x⁻) + x⁻; ω = 1, γ = 1 is plain iteration
      const Vec3 next = omega == 1 ? solved
                                   : Vec3(omega * (kUnderRelaxation * (solved - iterate_[p]) +
                                                   iterate_[p] - previous_[p]) +
                                          previous_[p]);
      previous_[p] = iterate_[p];
      iterate_[p] = next;
    }
  }
  if (chebyshev_rho_ == 0) {
    apply_velocity_change(inv_mass, h, dv_, state);
    return;
  }
  for (std::size_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0) continue;
    state.v[p] = (iterate_[p] - state.x[p]) / h;
    state.x[p] = iterate_[p];
  }
}

Real ProjectiveDynamics::chebyshev_weight(int k, Real omega) const {
  // Wang 2015, eq. 12, after kChebyshevDelay plain iterations (its S: the first ones change
  // the projections too much for the linear estimate ρ to hold)
  const Real rho2 = chebyshev_rho_ * chebyshev_rho_;
  if (chebyshev_rho_ == 0 || k < kChebyshevDelay) return 1;
  if (k == kChebyshevDelay) return 2 / (2 - rho2);
  return 4 / (4 - rho2 * omega);
}

void ProjectiveDynamics::project(const ParticleState& start, const std::vector<Vec3>& iterate) {
  force_ = others_;
  for (const DistanceConstraint& s : springs_.constraints) {
    const Vec3 spring = start.x[s.i] - start.x[s.j];
    const Vec3 toward = iterate[s.i] - iterate[s.j];
    const Real length = toward.norm();
    // a spring of no length has no direction to project on: it pulls nothing this iteration
    if (!(length > Real{1e-12})) continue;
    const Vec3 direction = toward / length;
    const Vec3 pull = s.stiffness * (s.rest_length * direction - spring) -
                      s.damping * (start.v[s.i] - start.v[s.j]).dot(direction) * direction;
    force_[s.i] += pull;
    force_[s.j] -= pull;
  }
}

}  // namespace felt
