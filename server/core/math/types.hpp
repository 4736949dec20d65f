#pragma once
// Scalar and vector types of the simulation. Units are SI: metres, kilograms, seconds, newtons.

#include <array>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace felt {

using Real = double;
using Vec2 = Eigen::Matrix<Real, 2, 1>;
using Vec3 = Eigen::Matrix<Real, 3, 1>;
using Mat3 = Eigen::Matrix<Real, 3, 3>;

/// A surface triangle: three particle indices, counter-clockwise seen from the front.
using Triangle = std::array<std::uint32_t, 3>;

}  // namespace felt
