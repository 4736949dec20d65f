#include "core/integrate/xpbd_integrator.hpp"

#include "core/math/check.hpp"

namespace felt {

XpbdIntegrator::XpbdIntegrator(int substeps) : substeps_(substeps) {
  FELT_CHECK(substeps >= 1 && substeps <= kMaxSubsteps);
}

void XpbdIntegrator::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  // read every step: the system's spring constants may change between steps
  system.distance_constraints(constraints_);
  const std::span<const Real> inv_mass = system.inv_mass();
  const std::size_t n = state.size();
  x_prev_.resize(n);
  f_.resize(n);
  const Real hs = h / substeps_;
  for (int s = 0; s < substeps_; ++s) {
    system.compute_forces_besides_constraints(state.x, state.v, t + s * hs, f_);
    for (std::size_t p = 0; p < n; ++p) {
      state.v[p] += hs * inv_mass[p] * f_[p];
      x_prev_[p] = state.x[p];
      state.x[p] += hs * state.v[p];  // a pin's velocity is 0, so it stays exactly put
    }
    project_constraints(inv_mass, hs, state);
    for (std::size_t p = 0; p < n; ++p) state.v[p] = (state.x[p] - x_prev_[p]) / hs;
  }
}

void XpbdIntegrator::project_constraints(std::span<const Real> inv_mass, Real h,
                                         ParticleState& state) const {
  std::vector<Vec3>& x = state.x;
  std::size_t begin = 0;
  // class by class; within a class no two constraints share a particle, so their order is moot
  for (const std::size_t end : constraints_.class_ends) {
    for (const DistanceConstraint& c :
         std::span(constraints_.constraints).subspan(begin, end - begin)) {
      project(c, inv_mass, h, x);
    }
    begin = end;
  }
}

void XpbdIntegrator::project(const DistanceConstraint& c, std::span<const Real> inv_mass, Real h,
                             std::vector<Vec3>& x) const {
  const Real w = inv_mass[c.i] + inv_mass[c.j];
  if (w == 0) return;
  const Vec3 d = x[c.i] - x[c.j];
  const Real length = d.norm();
  if (length <= Real{1e-12}) return;  // coincident particles: no direction to push along
  const Vec3 normal = d / length;     // ∇_i C; ∇_j C = −normal
  const Real violation = length - c.rest_length;
  const Real approach = normal.dot((x[c.i] - x_prev_[c.i]) - (x[c.j] - x_prev_[c.j]));
  // XPBD eq. 18 with the damping of eq. 26, λ = 0 (its one iteration this substep),
  // α̃ = α/h², α = 1/k, γ = α̃ β̃/h = c/(k h), all multiplied by k h² so that k = 0 (a pure
  // damper) and k → ∞ (a rigid rod) stay finite:
  //   Δλ = −(k h² C + c h ∇C·(x − x_prev)) / ((k h² + c h) w + 1)
  const Real kh2 = c.stiffness * h * h;
  const Real ch = c.damping * h;
  const Real delta_lambda = -(kh2 * violation + ch * approach) / ((kh2 + ch) * w + 1);
  x[c.i] += inv_mass[c.i] * delta_lambda * normal;
  x[c.j] -= inv_mass[c.j] * delta_lambda * normal;
}

}  // namespace felt
