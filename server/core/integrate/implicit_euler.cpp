#include "core/integrate/implicit_euler.hpp"

#include "core/math/check.hpp"

namespace felt {

void ImplicitEuler::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  const std::size_t n = state.size();
  force_.resize(n);
  rhs_.resize(n);
  dfdx_.resize(n);
  dfdv_.resize(n);
  inv_diagonal_.resize(n);
  filter_.resize(n);
  // warm start: the last step's Δv, scaled to this step's length (Δv ≈ h a, and a changes
  // little from one step to the next); none after a reset or a change of size
  const bool warm = dv_.size() == n && last_h_ > 0;
  if (!warm) dv_.assign(n, Vec3::Zero());
  const Real scale = warm ? h / last_h_ : 0;

  const auto inv_mass = system.inv_mass();
  system.compute_forces(state.x, state.v, t, force_);
  // a system without Jacobians is a programming error: every body type the loader builds
  // (cloth today) provides them
  FELT_CHECK(system.compute_jacobian(state.x, state.v, jacobian_));
  matrix_.assemble(jacobian_, inv_mass, h);

  // right-hand side h (f₀ + h K v₀)
  jacobian_.multiply(state.v, dfdx_, dfdv_);
  for (std::size_t p = 0; p < n; ++p) rhs_[p] = h * (force_[p] + h * dfdx_[p]);

  // pins are filtered out (S = 0) and their Δv stays 0; the Jacobi preconditioner is the
  // diagonal of A
  matrix_.diagonal(inv_diagonal_);
  for (std::size_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0) {
      dv_[p].setZero();
      filter_[p].setZero();
      inv_diagonal_[p].setOnes();
      continue;
    }
    dv_[p] *= scale;
    filter_[p].setIdentity();
    inv_diagonal_[p] = inv_diagonal_[p].cwiseInverse();
  }

  last_solve_ = solver_.solve(
      [this](std::span<const Vec3> y, std::span<Vec3> out) { matrix_.multiply(y, out); }, rhs_,
      inv_diagonal_, filter_, dv_);
  last_h_ = h;

  for (std::size_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0) continue;
    state.v[p] += dv_[p];
    state.x[p] += h * state.v[p];
  }
}

}  // namespace felt
