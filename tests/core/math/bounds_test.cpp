// The bound on every vector that enters from outside.

#include <cmath>

#include <gtest/gtest.h>

#include "core/math/bounds.hpp"

namespace felt {
namespace {

TEST(Bounds, TheBoundIsWithinNaNAndInfinityAreNot) {
  EXPECT_TRUE(within_bounds(Vec3(kMaxVectorComponent, -kMaxVectorComponent, 0)));
  EXPECT_FALSE(within_bounds(Vec3(0, std::nextafter(kMaxVectorComponent, 2e6), 0)));
  EXPECT_FALSE(within_bounds(Vec3(0, 0, std::nan(""))));
  EXPECT_FALSE(within_bounds(Vec3(-INFINITY, 0, 0)));
}

}  // namespace
}  // namespace felt
