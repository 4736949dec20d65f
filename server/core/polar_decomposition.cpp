#include "core/polar_decomposition.hpp"

#include <Eigen/SVD>

namespace felt {

PolarDecomposition polar_decomposition(const Mat3& f) {
  const Eigen::JacobiSVD<Mat3> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 u = svd.matrixU();
  Vec3 sigma = svd.singularValues();
  const Mat3& v = svd.matrixV();
  if (u.determinant() * v.determinant() < 0) {
    // the smallest singular value takes the reflection, which disturbs the fit the least
    u.col(2) = -u.col(2);
    sigma(2) = -sigma(2);
  }
  return {u * v.transpose(), v * sigma.asDiagonal() * v.transpose()};
}

}  // namespace felt
