// Clamping a vector's length against the plain formula where it holds, and against the exact
// direction and length where its squares overflow.

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/math/clamp_length.hpp"

namespace felt {
namespace {

TEST(ClampLength, WithinRangeItIsThePlainFormulaBitForBit) {
  const Vec3 v(3, -4, 12);  // length 13
  EXPECT_EQ(clamp_length(v, 13), v);
  EXPECT_EQ(clamp_length(v, 20), v);
  EXPECT_EQ(clamp_length(v, 6.5), Vec3(v * (6.5 / v.norm())));
  EXPECT_EQ(clamp_length(Vec3::Zero(), 0), Vec3::Zero());
}

TEST(ClampLength, AVectorWhoseSquaresOverflowIsClampedAlongItsDirection) {
  const Real huge = std::numeric_limits<Real>::max();
  for (const Real scale : {1e155, 1e200, 1e308, huge}) {
    const Vec3 v = Vec3(3, -4, 12) / 13 * scale;
    ASSERT_FALSE(std::isfinite(v.squaredNorm())) << scale;
    const Vec3 clamped = clamp_length(v, 10);
    EXPECT_NEAR(clamped.norm(), 10, 1e-14) << scale;
    EXPECT_NEAR((clamped / 10 - Vec3(3, -4, 12) / 13).norm(), 0, 1e-15) << scale;
  }
  const Vec3 corner(huge, -huge, huge);
  EXPECT_NEAR((clamp_length(corner, 1) - Vec3(1, -1, 1) / std::sqrt(3.0)).norm(), 0, 1e-15);
}

TEST(ClampLength, ANonFiniteVectorComesBackAsItIs) {
  const Vec3 nan(std::nan(""), 0, 0);
  EXPECT_TRUE(std::isnan(clamp_length(nan, 1).x()));
  EXPECT_TRUE(std::isinf(clamp_length(Vec3(INFINITY, 0, 0), 1).x()));
}

// Issue 31: the grab spring to a device 1e200 m away gave 0 N instead of its clamp.
TEST(ClampedSpringForce, AnyFiniteOffsetGivesTheClampAlongIt) {
  const Real huge = std::numeric_limits<Real>::max();
  for (const Real far : {1.0, 1e200, 1e308, huge}) {
    const Vec3 force = clamped_spring_force(400, Vec3(0, -far, 0), 10);
    EXPECT_EQ(force, Vec3(0, -10, 0)) << far;
  }
  // within the clamp: stiffness times the offset
  EXPECT_EQ(clamped_spring_force(400, Vec3(0.01, 0, 0), 10), Vec3(4, 0, 0));
}

}  // namespace
}  // namespace felt
