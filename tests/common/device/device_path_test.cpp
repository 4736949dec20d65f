#include "device/device_path.hpp"

#include <numbers>

#include <gtest/gtest.h>

namespace felt {
namespace {

TEST(DevicePath, LineGoesThereAndBackOncePerPeriod) {
  DevicePath path;
  path.shape = DevicePath::Shape::kLine;
  path.a = Eigen::Vector3d(0, 1, 0);
  path.b = Eigen::Vector3d(2, 1, 0);
  path.period = 4;
  EXPECT_EQ(path.at(0).position, path.a);
  EXPECT_EQ(path.at(1).position, Eigen::Vector3d(1, 1, 0));
  EXPECT_EQ(path.at(2).position, path.b);
  EXPECT_EQ(path.at(3).position, Eigen::Vector3d(1, 1, 0));
  EXPECT_NEAR((path.at(4).position - path.a).norm(), 0, 1e-12);
  EXPECT_EQ(path.at(-1).position, path.a);  // before the start: where it starts
}

TEST(DevicePath, CircleStaysOnItsCircleInThePlaneNormalToTheAxis) {
  DevicePath path;
  path.shape = DevicePath::Shape::kCircle;
  path.a = Eigen::Vector3d(1, 2, 3);
  path.axis = Eigen::Vector3d(1, 1, 0);
  path.radius = 0.25;
  path.period = 0.5;
  const Eigen::Vector3d n = path.axis.normalized();
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d r = path.at(0.031 * i).position - path.a;
    EXPECT_NEAR(r.norm(), 0.25, 1e-12);
    EXPECT_NEAR(r.dot(n), 0, 1e-12);
  }
  // a quarter period turns a quarter turn
  const Eigen::Vector3d r0 = path.at(0).position - path.a;
  const Eigen::Vector3d r1 = path.at(0.125).position - path.a;
  EXPECT_NEAR(r0.dot(r1), 0, 1e-12);
  EXPECT_NEAR((path.at(0.5).position - path.at(0).position).norm(), 0, 1e-12);
}

TEST(DevicePath, PressMovesThenHoldsWithItsButtons) {
  DevicePath path;
  path.shape = DevicePath::Shape::kPress;
  path.a = Eigen::Vector3d(0, 1, 0);
  path.b = Eigen::Vector3d(0, 0, 0);
  path.period = 2;
  path.buttons = 1;
  EXPECT_EQ(path.at(1).position, Eigen::Vector3d(0, 0.5, 0));
  EXPECT_EQ(path.at(2).position, path.b);
  EXPECT_EQ(path.at(50).position, path.b);
  EXPECT_EQ(path.at(50).buttons, 1u);
}

TEST(DevicePath, SamplesAreInterpolatedAndButtonsChangeAtSamples) {
  DevicePath path;
  path.shape = DevicePath::Shape::kSamples;
  path.samples = {{0, Eigen::Vector3d(0, 0, 0), 0},
                  {1, Eigen::Vector3d(1, 0, 0), 1},
                  {3, Eigen::Vector3d(1, 2, 0), 0}};
  EXPECT_EQ(path.at(0.5).position, Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(path.at(0.5).buttons, 0u);
  EXPECT_EQ(path.at(1).buttons, 1u);
  EXPECT_EQ(path.at(2).position, Eigen::Vector3d(1, 1, 0));
  EXPECT_EQ(path.at(2).buttons, 1u);
  EXPECT_EQ(path.at(9).position, Eigen::Vector3d(1, 2, 0));
  // exactly at a sample: that sample, bit for bit (replays depend on it)
  EXPECT_EQ(path.at(1).position, Eigen::Vector3d(1, 0, 0));
}

}  // namespace
}  // namespace felt
