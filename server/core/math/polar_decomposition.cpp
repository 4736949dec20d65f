#include "core/math/polar_decomposition.hpp"

#include <cmath>

#include <Eigen/SVD>

namespace felt {
namespace {

/// det F / ‖F‖³ (Frobenius) at or below which F counts as inverted or flat: 1/√27 for a
/// rotation, about σ_min / (2.8 σ_max) for a flattened element.
constexpr Real kNearlyFlat = 1e-5;
/// Newton's error after a step is about half the square of the step (σ → (σ + 1/σ)/2 near 1),
/// so once a step moves X by less than 10⁻⁸ the new X is a rotation to rounding.
constexpr Real kConverged = 1e-8;
/// Higham's scaling brings the singular values of a far F (a cluster moment in m², a nearly flat
/// element) to about 1 in one step; once X moves by less than this, the unscaled steps converge
/// as fast, without the two square roots (Higham scales while the step exceeds 10⁻²: on strains
/// of 10–30 % that made the decomposition 20–40 % slower for the same number of steps).
constexpr Real kScaleWhileChange = 0.5;
/// From the flattest F allowed (σ_min = 3·10⁻⁵ σ_max) the iteration needs 5 steps; the rest is
/// room for rounding before the SVD takes over.
constexpr int kMaxIterations = 16;

PolarDecomposition with_rotation(const Mat3& f, const Mat3& rotation) {
  const Mat3 stretch = rotation.transpose() * f;  // symmetric but for rounding
  return {rotation, 0.5 * (stretch + stretch.transpose())};
}

}  // namespace

PolarDecomposition polar_decomposition(const Mat3& f) {
  const Real norm = f.norm();
  if (!(f.determinant() > kNearlyFlat * norm * norm * norm)) return polar_decomposition_svd(f);
  Mat3 x = f;
  Real change_squared = kScaleWhileChange * kScaleWhileChange;
  for (int i = 0; i < kMaxIterations; ++i) {
    // X⁻ᵀ = cof(X) / det X, the cofactor columns being cross products of X's columns
    Mat3 cofactor;
    cofactor << x.col(1).cross(x.col(2)), x.col(2).cross(x.col(0)), x.col(0).cross(x.col(1));
    const Real det = x.col(0).dot(cofactor.col(0));
    // ζ = (‖X⁻¹‖ / ‖X‖)^½, which makes the scaled X and X⁻ᵀ equally large
    const Real zeta = change_squared >= kScaleWhileChange * kScaleWhileChange
                          ? std::sqrt(std::sqrt(cofactor.squaredNorm() / x.squaredNorm()) / det)
                          : 1;
    const Mat3 next = 0.5 * (zeta * x + cofactor / (zeta * det));
    change_squared = (next - x).squaredNorm();
    x = next;
    if (change_squared < kConverged * kConverged) return with_rotation(f, x);
  }
  return polar_decomposition_svd(f);
}

PolarDecomposition polar_decomposition_svd(const Mat3& f) {
  const Eigen::JacobiSVD<Mat3> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 u = svd.matrixU();
  const Mat3& v = svd.matrixV();
  if (u.determinant() * v.determinant() < 0) {
    // the smallest singular value takes the reflection, which disturbs the fit the least
    u.col(2) = -u.col(2);
  }
  return with_rotation(f, u * v.transpose());  // Rᵀ F = V Σ Vᵀ
}

}  // namespace felt
