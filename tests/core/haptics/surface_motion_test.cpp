// How far a surface moved, per snapshot pair and along a chain of them.

#include <vector>

#include <gtest/gtest.h>

#include "core/haptics/surface_motion.hpp"

namespace felt {
namespace {

TEST(SurfaceMotion, APairMovesByItsFarthestVertexAndAChainSumsItsPairs) {
  const std::vector<Vec3> a = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const std::vector<Vec3> b = {Vec3(0, 0, 0.01), Vec3(1, 0.03, 0.04), Vec3(0, 1, 0)};  // 5 cm
  const std::vector<Vec3> c = {Vec3(0, 0, 0.03), Vec3(1, 0.03, 0.04), Vec3(0, 1, 0)};  // 2 cm
  const SurfaceMotion first = SurfaceMotion{0, 0, 42}.then(a, a);
  EXPECT_EQ(first.max_displacement, 0);
  EXPECT_EQ(first.travelled, 0);
  const SurfaceMotion second = first.then(a, b);
  EXPECT_DOUBLE_EQ(second.max_displacement, 0.05);
  EXPECT_DOUBLE_EQ(second.travelled, 0.05);
  const SurfaceMotion third = second.then(b, c);
  EXPECT_DOUBLE_EQ(third.max_displacement, 0.02);
  EXPECT_DOUBLE_EQ(third.travelled, 0.07);
  EXPECT_EQ(third.chain, 42u);
}

}  // namespace
}  // namespace felt
