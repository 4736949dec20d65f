// How stiff a surface is under a haptic push (SurfaceStiffnessEstimate), against surfaces whose
// stiffness is known: a spring's u = u0 - F / k, with and without noise, one that changes, and
// pushes that say nothing of it.

#include "core/haptics/surface_stiffness_estimate.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace felt {
namespace {

TEST(SurfaceStiffnessEstimate, ASpringPressedHarderGivesItsStiffness) {
  SurfaceStiffnessEstimate estimate;
  EXPECT_EQ(estimate.stiffness(), 0);  // nothing yet
  for (int i = 0; i <= 100; ++i) {
    const Real force = 0.05 * i;  // a press from 0 to 5 N
    estimate.add(force, 0.2 - force / 1500);
  }
  EXPECT_NEAR(estimate.stiffness(), 1500, 1e-6);
}

TEST(SurfaceStiffnessEstimate, NoiseOnThePositionAveragesOut) {
  std::mt19937 random(3);
  std::normal_distribution<Real> noise(0, 1e-4);  // 0.1 mm on a 3 mm give
  SurfaceStiffnessEstimate estimate;
  for (int i = 0; i < 400; ++i) {
    const Real force = 3 + 2.5 * std::sin(0.05 * i);
    estimate.add(force, 0.1 - force / 2000 + noise(random));
  }
  EXPECT_NEAR(estimate.stiffness(), 2000, 100);
}

TEST(SurfaceStiffnessEstimate, OlderPushesAreForgotten) {
  SurfaceStiffnessEstimate estimate(0.98);
  for (int i = 0; i < 600; ++i) {  // 0.98^450: what is left of the softer spring's weight
    const Real force = 2 + std::sin(0.1 * i);
    estimate.add(force, -force / (i < 150 ? 500 : 5000));
  }
  EXPECT_NEAR(estimate.stiffness(), 5000, 50);
}

TEST(SurfaceStiffnessEstimate, ASteadyPushOrASurfaceComingCloserSaysNothing) {
  SurfaceStiffnessEstimate steady;
  for (int i = 0; i < 100; ++i) steady.add(4 + 1e-3 * (i % 2), 0.1 - 1e-6 * i);  // creeping
  EXPECT_EQ(steady.stiffness(), 0);
  SurfaceStiffnessEstimate closer;  // pushed harder as the body moves toward the finger
  for (int i = 0; i < 100; ++i) closer.add(0.05 * i, 0.1 + 1e-4 * i);
  EXPECT_EQ(closer.stiffness(), 0);
  closer.reset();
  closer.add(std::numeric_limits<Real>::quiet_NaN(), 0);
  EXPECT_EQ(closer.stiffness(), 0);
}

}  // namespace
}  // namespace felt
