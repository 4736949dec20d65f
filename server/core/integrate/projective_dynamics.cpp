#include "core/integrate/projective_dynamics.hpp"

#include "core/math/check.hpp"

namespace felt {

ProjectiveDynamics::ProjectiveDynamics(int iterations) : iterations_(iterations) {
  FELT_CHECK(iterations >= 1 && iterations <= kMaxIterations);
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
  iterate_ = state.x;
  for (int k = 0; k < iterations_; ++k) {
    project(state, iterate_);
    linear_step_.assemble(inv_mass, state, h, pairs_, force_);
    linear_step_.solve(inv_mass, h, dv_);
    for (std::size_t p = 0; p < n; ++p) {
      if (inv_mass[p] == 0) continue;
      iterate_[p] =
          state.x[p] + h * (state.v[p] + dv_.row(static_cast<Eigen::Index>(p)).transpose());
    }
  }
  apply_velocity_change(inv_mass, h, dv_, state);
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
