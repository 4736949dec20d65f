#pragma once

#include <string>

#include "core/proxy_settings.hpp"
#include "core/world.hpp"

namespace felt {

/// A loaded scene: its world and the settings the runtime needs to serve it.
struct Scene {
  std::string name;
  World world;
  ProxySettings haptics;
};

}  // namespace felt
