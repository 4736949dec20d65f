#include "core/integrate/implicit_euler.hpp"

#include "core/math/check.hpp"

namespace felt {

void ImplicitEuler::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  const std::size_t n = state.size();
  force_.resize(n);
  rhs_.resize(n);
  dv_.resize(n);
  dfdx_.resize(n);
  dfdv_.resize(n);
  inv_diagonal_.resize(n);
  filter_.resize(n);
  diag_dx_.resize(n);
  diag_dv_.resize(n);

  const auto inv_mass = system.inv_mass();
  system.compute_forces(state.x, state.v, t, force_);
  // a system without Jacobians is a programming error: every body type the loader builds
  // (cloth today) provides them
  FELT_CHECK(system.compute_jacobian(state.x, state.v, jacobian_));

  // right-hand side h (f₀ + h K v₀)
  jacobian_.multiply(state.v, dfdx_, dfdv_);
  for (std::size_t p = 0; p < n; ++p) rhs_[p] = h * (force_[p] + h * dfdx_[p]);

  // pins are filtered out (S = 0) and their Δv stays 0; the Jacobi preconditioner is the
  // diagonal of A = M − h D − h² K
  jacobian_.diagonal_blocks(diag_dx_, diag_dv_);
  for (std::size_t p = 0; p < n; ++p) {
    dv_[p].setZero();
    if (inv_mass[p] == 0) {
      filter_[p].setZero();
      inv_diagonal_[p].setOnes();
      continue;
    }
    filter_[p].setIdentity();
    const Vec3 diagonal = Vec3::Constant(1 / inv_mass[p]) - h * diag_dv_[p].diagonal() -
                          h * h * diag_dx_[p].diagonal();
    inv_diagonal_[p] = diagonal.cwiseInverse();
  }

  const auto apply = [&](std::span<const Vec3> y, std::span<Vec3> out) {
    jacobian_.multiply(y, dfdx_, dfdv_);
    for (std::size_t p = 0; p < n; ++p) {
      const Real mass = inv_mass[p] == 0 ? 0 : 1 / inv_mass[p];
      out[p] = mass * y[p] - h * dfdv_[p] - h * h * dfdx_[p];
    }
  };
  last_solve_ = solver_.solve(apply, rhs_, inv_diagonal_, filter_, dv_);

  for (std::size_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0) continue;
    state.v[p] += dv_[p];
    state.x[p] += h * state.v[p];
  }
}

}  // namespace felt
