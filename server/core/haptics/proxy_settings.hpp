#pragma once

#include "core/math/types.hpp"

namespace felt {

/// How a haptic proxy touches a scene: a god-object sphere tied to the device by a spring.
struct ProxySettings {
  Real radius = 0.02;         ///< m; the sphere that touches the surface (0: a point)
  Real stiffness = 400;       ///< N/m; force = stiffness · (proxy − device)
  Real damping = 0;           ///< N·s/m on the device's velocity relative to the proxy, in contact
  Real max_force = 10;        ///< N; the device's safety clamp
  Real max_force_change = 0;  ///< N per update; a jump in force is spread over updates (0: none)
  Real static_friction = 0;   ///< μ_s: the proxy sticks while the device stays inside this cone
  Real dynamic_friction = 0;  ///< μ_d ≤ μ_s: the cone a slipping proxy is dragged to
  bool force_shading = true;  ///< force along the interpolated vertex normal (Ruspini sub-proxy)
};

}  // namespace felt
