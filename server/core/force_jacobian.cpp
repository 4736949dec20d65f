#include "core/force_jacobian.hpp"

#include <algorithm>

namespace felt {

void ForceJacobian::reset(std::size_t particles) {
  pairs_.clear();
  velocity_diagonal_.assign(particles, 0);
}

void ForceJacobian::multiply(std::span<const Vec3> y, std::span<Vec3> dfdx_y,
                             std::span<Vec3> dfdv_y) const {
  for (std::size_t p = 0; p < y.size(); ++p) {
    dfdx_y[p].setZero();
    dfdv_y[p] = -velocity_diagonal_[p] * y[p];
  }
  for (const Pair& pair : pairs_) {
    const Vec3 relative = y[pair.i] - y[pair.j];
    const Vec3 by_x = pair.dx * relative;
    const Vec3 by_v = pair.dv * relative;
    dfdx_y[pair.i] += by_x;
    dfdx_y[pair.j] -= by_x;
    dfdv_y[pair.i] += by_v;
    dfdv_y[pair.j] -= by_v;
  }
}

void ForceJacobian::diagonal_blocks(std::span<Mat3> dx, std::span<Mat3> dv) const {
  for (std::size_t p = 0; p < velocity_diagonal_.size(); ++p) {
    dx[p].setZero();
    dv[p] = -velocity_diagonal_[p] * Mat3::Identity();
  }
  for (const Pair& pair : pairs_) {
    dx[pair.i] += pair.dx;
    dx[pair.j] += pair.dx;
    dv[pair.i] += pair.dv;
    dv[pair.j] += pair.dv;
  }
}

}  // namespace felt
