#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/collision/triangle_query.hpp"
#include "core/haptics/proxy_settings.hpp"
#include "core/world/world.hpp"
#include "device/device_path.hpp"

namespace felt {

/// A haptic device that lives in the server and follows a script (demos, tests).
struct ScriptedDevice {
  std::string name;
  DevicePath path;
};

/// A loaded scene: its world and the settings the runtime needs to serve it.
struct Scene {
  Scene(std::string scene_name, World scene_world)
      : name(std::move(scene_name)), world(std::move(scene_world)) {}

  std::string name;
  World world;
  ProxySettings haptics;  ///< every proxy's settings
  /// the broad phase of the haptic query (docs/results/haptics.md says why this default)
  TriangleQueryKind haptic_structure = TriangleQueryKind::kBvhAabb4;
  Real servo_rate = 1000;  ///< Hz, of the servo thread that drives `devices`
  std::vector<ScriptedDevice> devices;
};

}  // namespace felt
