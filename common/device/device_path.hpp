#pragma once
// Scripted haptic devices: where a device that lives in the server is at each instant and
// which buttons it holds. They drive the servo thread's proxies in demos and tests, and replay
// recorded device paths.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace felt {

/// A point of a sampled path: the device at `position` holding `buttons` at `time`.
struct DeviceSample {
  double time = 0;  ///< s from the path's start
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::uint32_t buttons = 0;
};

struct DevicePath {
  enum class Shape : std::uint8_t {
    kLine,     ///< from `a` to `b` and back, one round trip per `period`
    kCircle,   ///< around centre `a` in the plane normal to `axis`, one turn per `period`
    kPress,    ///< from `a` to `b` in `period`, then held at `b`
    kSamples,  ///< through `samples`, linearly between them, held at the last
  };
  Shape shape = Shape::kPress;
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();
  double radius = 0;
  double period = 1;                  ///< s, > 0
  std::uint32_t buttons = 0;          ///< held throughout (all shapes but kSamples)
  std::vector<DeviceSample> samples;  ///< kSamples: increasing times, at least one

  /// The device at `t` seconds after the path started (t < 0: where it starts).
  DeviceSample at(double t) const;
};

}  // namespace felt
