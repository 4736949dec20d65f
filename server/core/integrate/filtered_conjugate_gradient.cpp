#include "core/integrate/filtered_conjugate_gradient.hpp"

#include <cmath>

namespace felt {
namespace {

Real dot(std::span<const Vec3> a, std::span<const Vec3> b) {
  Real sum = 0;
  for (std::size_t p = 0; p < a.size(); ++p) sum += a[p].dot(b[p]);
  return sum;
}

}  // namespace

FilteredConjugateGradient::Result FilteredConjugateGradient::solve(
    const Operator& apply, std::span<const Vec3> b, std::span<const Vec3> inv_diagonal,
    std::span<const Mat3> filter, std::span<Vec3> x) {
  const std::size_t n = b.size();
  r_.resize(n);
  c_.resize(n);
  q_.resize(n);
  s_.resize(n);

  // δ0 = (S b)ᵀ P⁻¹ (S b): the scale the residual is measured against
  Real delta0 = 0;
  for (std::size_t p = 0; p < n; ++p) {
    const Vec3 fb = filter[p] * b[p];
    delta0 += fb.dot(inv_diagonal[p].cwiseProduct(fb));
  }
  apply(x, q_);
  for (std::size_t p = 0; p < n; ++p) {
    r_[p] = filter[p] * (b[p] - q_[p]);
    c_[p] = filter[p] * inv_diagonal[p].cwiseProduct(r_[p]);
  }
  Real delta = dot(r_, c_);

  Result result;
  const Real target = tolerance * tolerance * delta0;
  while (delta > target && result.iterations < max_iterations) {
    apply(c_, q_);
    for (std::size_t p = 0; p < n; ++p) q_[p] = filter[p] * q_[p];
    const Real curvature = dot(c_, q_);
    if (!(curvature > 0)) break;  // not positive definite along c: stop with what we have
    const Real alpha = delta / curvature;
    for (std::size_t p = 0; p < n; ++p) {
      x[p] += alpha * c_[p];
      r_[p] -= alpha * q_[p];
      s_[p] = inv_diagonal[p].cwiseProduct(r_[p]);
    }
    const Real delta_old = delta;
    delta = dot(r_, s_);
    const Real beta = delta / delta_old;
    for (std::size_t p = 0; p < n; ++p) c_[p] = filter[p] * (s_[p] + beta * c_[p]);
    ++result.iterations;
  }
  result.converged = delta <= target;
  result.residual_ratio = delta0 > 0 ? std::sqrt(delta / delta0) : 0;
  return result;
}

}  // namespace felt
