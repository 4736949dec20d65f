#include "core/integrate/approximate_implicit_integrators.hpp"

#include <algorithm>

#include <Eigen/QR>

namespace felt {

void DesbrunIntegrator::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  const auto inv_mass = system.inv_mass();
  linear_step_.assemble(system, state, t, h);
  linear_step_.solve(inv_mass, h, dv_);
  if (correct_angular_momentum_ && std::ranges::none_of(inv_mass, [](Real w) { return w == 0; })) {
    restore_angular_momentum(inv_mass, state.x, h);
  }
  apply_velocity_change(inv_mass, h, dv_, state);
}

void DesbrunIntegrator::restore_angular_momentum(std::span<const Real> inv_mass,
                                                 std::span<const Vec3> x, Real h) {
  const std::vector<Vec3>& force = linear_step_.forces();
  Real total_mass = 0;
  Vec3 centre = Vec3::Zero();
  for (std::size_t p = 0; p < x.size(); ++p) {
    total_mass += 1 / inv_mass[p];
    centre += x[p] / inv_mass[p];
  }
  if (total_mass == 0) return;  // no particles
  centre /= total_mass;

  // the filter's excess angular impulse τ and the inertia tensor I, both about the centre
  Vec3 excess = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
  for (std::size_t p = 0; p < x.size(); ++p) {
    const Real mass = 1 / inv_mass[p];
    const Vec3 r = x[p] - centre;
    const Vec3 dv = dv_.row(static_cast<Eigen::Index>(p)).transpose();
    excess += r.cross(mass * dv - h * force[p]);
    inertia += mass * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
  }
  const Vec3 omega = Eigen::CompleteOrthogonalDecomposition<Mat3>(inertia).solve(-excess);
  for (std::size_t p = 0; p < x.size(); ++p) {
    dv_.row(static_cast<Eigen::Index>(p)) += omega.cross(x[p] - centre).transpose();
  }
}

void KangIntegrator::step(const DynamicSystem& system, ParticleState& state, Real t, Real h) {
  const auto inv_mass = system.inv_mass();
  const std::size_t n = state.size();
  linear_step_.assemble(system, state, t, h);
  const LinearPairStep::Columns& rhs = linear_step_.rhs();  // zero on pinned rows
  const std::vector<LinearPair>& pairs = linear_step_.pairs();

  // m_i + h² K_i; a pinned row is eliminated (Δv = 0), its entry only keeps the division finite
  diagonal_.resize(n);
  for (std::size_t p = 0; p < n; ++p) diagonal_[p] = inv_mass[p] == 0 ? 1 : 1 / inv_mass[p];
  for (const LinearPair& pair : pairs) {
    diagonal_[pair.i] += h * h * pair.k;
    diagonal_[pair.j] += h * h * pair.k;
  }
  guess_.resize(rhs.rows(), 3);
  for (std::size_t p = 0; p < n; ++p) {
    guess_.row(static_cast<Eigen::Index>(p)) = rhs.row(static_cast<Eigen::Index>(p)) / diagonal_[p];
  }
  // the sweep: Δv_i = (b_i + h² Σ_j k_ij Δv⁰_j) / (m_i + h² K_i); pinned rows stay 0
  dv_ = rhs;
  for (const LinearPair& pair : pairs) {
    const Real w = h * h * pair.k;
    if (inv_mass[pair.i] != 0) dv_.row(pair.i) += w * guess_.row(pair.j);
    if (inv_mass[pair.j] != 0) dv_.row(pair.j) += w * guess_.row(pair.i);
  }
  for (std::size_t p = 0; p < n; ++p) dv_.row(static_cast<Eigen::Index>(p)) /= diagonal_[p];

  apply_velocity_change(inv_mass, h, dv_, state);
}

}  // namespace felt
