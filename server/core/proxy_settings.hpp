#pragma once

#include "core/types.hpp"

namespace felt {

/// How a haptic proxy touches a scene: a sphere tied to the device by a spring.
struct ProxySettings {
  Real radius = 0.02;    ///< m; the sphere that touches the surface
  Real stiffness = 400;  ///< N/m; force = stiffness · penetration
  Real max_force = 10;   ///< N; the device's safety clamp
};

}  // namespace felt
