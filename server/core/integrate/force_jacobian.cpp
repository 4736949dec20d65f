#include "core/integrate/force_jacobian.hpp"

#include <algorithm>
#include <vector>

#include "core/math/largest_eigenvalue.hpp"

namespace felt {

Mat3 ForceJacobian::Pair::dx() const {
  const Mat3 outer = direction * direction.transpose();
  return -(axial * outer + transverse * (Mat3::Identity() - outer));
}

Mat3 ForceJacobian::Pair::dv() const {
  return -damping * direction * direction.transpose();
}

void ForceJacobian::reset(std::size_t particles) {
  pairs_.clear();
  velocity_diagonal_.assign(particles, 0);
  position_diagonal_.assign(particles, 0);
}

void ForceJacobian::multiply(std::span<const Vec3> y, std::span<Vec3> dfdx_y,
                             std::span<Vec3> dfdv_y) const {
  for (std::size_t p = 0; p < y.size(); ++p) {
    dfdx_y[p] = -position_diagonal_[p] * y[p];
    dfdv_y[p] = -velocity_diagonal_[p] * y[p];
  }
  for (const Pair& pair : pairs_) {
    const Vec3 relative = y[pair.i] - y[pair.j];
    const Real along = pair.direction.dot(relative);
    const Vec3 by_x =
        -(pair.axial - pair.transverse) * along * pair.direction - pair.transverse * relative;
    const Vec3 by_v = -pair.damping * along * pair.direction;
    dfdx_y[pair.i] += by_x;
    dfdx_y[pair.j] -= by_x;
    dfdv_y[pair.i] += by_v;
    dfdv_y[pair.j] -= by_v;
  }
}

void ForceJacobian::diagonal_blocks(std::span<Mat3> dx, std::span<Mat3> dv) const {
  for (std::size_t p = 0; p < velocity_diagonal_.size(); ++p) {
    dx[p] = -position_diagonal_[p] * Mat3::Identity();
    dv[p] = -velocity_diagonal_[p] * Mat3::Identity();
  }
  for (const Pair& pair : pairs_) {
    const Mat3 pair_dx = pair.dx();
    const Mat3 pair_dv = pair.dv();
    dx[pair.i] += pair_dx;
    dx[pair.j] += pair_dx;
    dv[pair.i] += pair_dv;
    dv[pair.j] += pair_dv;
  }
}

void ForceJacobian::scaled_matrices(std::span<const Real> scale,
                                    Eigen::SparseMatrix<Real>& stiffness,
                                    Eigen::SparseMatrix<Real>& damping) const {
  const std::size_t n = particle_count();
  std::vector<Mat3> dx(n), dv(n);
  diagonal_blocks(dx, dv);
  std::vector<Eigen::Triplet<Real>> k, d;
  for (std::uint32_t p = 0; p < n; ++p) {
    const Real s = scale[p] * scale[p];
    add_block(k, p, p, -s * dx[p]);
    add_block(d, p, p, -s * dv[p]);
  }
  // ∂f_i/∂x_j = −∂f_i/∂x_i for a pair, so K's off-diagonal block is the pair's dx()
  for (const Pair& pair : pairs_) {
    const Real s = scale[pair.i] * scale[pair.j];
    const Mat3 k_ij = s * pair.dx(), d_ij = s * pair.dv();
    add_block(k, pair.i, pair.j, k_ij);
    add_block(k, pair.j, pair.i, k_ij);
    add_block(d, pair.i, pair.j, d_ij);
    add_block(d, pair.j, pair.i, d_ij);
  }
  stiffness = block_matrix(n, k);
  damping = block_matrix(n, d);
}

}  // namespace felt
