#include "core/geometry/triangle_mesh.hpp"

#include <cmath>

namespace felt {

Vec3 Transform::apply(const Vec3& p) const {
  const Vec3 r = rotate_degrees * (M_PI / 180);
  const Mat3 rotation =
      (Eigen::AngleAxis<Real>(r.z(), Vec3::UnitZ()) * Eigen::AngleAxis<Real>(r.y(), Vec3::UnitY()) *
       Eigen::AngleAxis<Real>(r.x(), Vec3::UnitX()))
          .toRotationMatrix();
  return (rotation * p).cwiseProduct(scale) + translate;
}

}  // namespace felt
