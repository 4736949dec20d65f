#include "core/integrate/implicit_system_matrix.hpp"

namespace felt {

void ImplicitSystemMatrix::assemble(const ForceJacobian& jacobian, std::span<const Real> inv_mass,
                                    Real h) {
  const std::vector<ForceJacobian::Pair>& pairs = jacobian.pairs();
  i_.resize(pairs.size());
  j_.resize(pairs.size());
  direction_.resize(pairs.size());
  along_.resize(pairs.size());
  across_.resize(pairs.size());
  const Real h2 = h * h;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const ForceJacobian::Pair& pair = pairs[k];
    i_[k] = pair.i;
    j_[k] = pair.j;
    direction_[k] = pair.direction;
    along_[k] = h2 * (pair.axial - pair.transverse) + h * pair.damping;
    across_[k] = h2 * pair.transverse;
  }
  const std::size_t n = jacobian.particle_count();
  particle_.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    const Real mass = inv_mass[p] == 0 ? 0 : 1 / inv_mass[p];
    particle_[p] =
        mass + h * jacobian.velocity_diagonal()[p] + h2 * jacobian.position_diagonal()[p];
  }
}

void ImplicitSystemMatrix::multiply(std::span<const Vec3> y, std::span<Vec3> out) const {
  for (std::size_t p = 0; p < particle_.size(); ++p) out[p] = particle_[p] * y[p];
  for (std::size_t k = 0; k < i_.size(); ++k) {
    const Vec3 relative = y[i_[k]] - y[j_[k]];
    const Vec3 push =
        along_[k] * direction_[k].dot(relative) * direction_[k] + across_[k] * relative;
    out[i_[k]] += push;
    out[j_[k]] -= push;
  }
}

void ImplicitSystemMatrix::diagonal(std::span<Vec3> out) const {
  for (std::size_t p = 0; p < particle_.size(); ++p) out[p] = Vec3::Constant(particle_[p]);
  for (std::size_t k = 0; k < i_.size(); ++k) {
    const Vec3 block = along_[k] * direction_[k].cwiseAbs2() + Vec3::Constant(across_[k]);
    out[i_[k]] += block;
    out[j_[k]] += block;
  }
}

}  // namespace felt
