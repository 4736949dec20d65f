#pragma once
// Scripted haptic devices: where a device that lives in the server is at each instant and
// which buttons it holds. They drive the servo thread's proxies in demos and tests, and replay
// recorded device paths.

#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace felt {

/// A point of a sampled path: the device at `position` holding `buttons` at `time`.
struct DeviceSample {
  Real time = 0;  ///< s from the path's start
  Vec3 position = Vec3::Zero();
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
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::Zero();
  Vec3 axis = Vec3::UnitY();
  Real radius = 0;
  Real period = 1;                    ///< s, > 0
  std::uint32_t buttons = 0;          ///< held throughout (all shapes but kSamples)
  std::vector<DeviceSample> samples;  ///< kSamples: increasing times, at least one

  /// The device at `t` seconds after the path started (t < 0: where it starts).
  DeviceSample at(Real t) const;
};

}  // namespace felt
