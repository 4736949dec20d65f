#pragma once
// The force on a haptic proxy touching a scene snapshot. A penalty sphere against the surface:
// the stand-in until the god-object renderer (issue 5) replaces it.

#include <cstdint>

#include "core/proxy_settings.hpp"
#include "runtime/snapshot.hpp"

namespace felt {

struct ProxyContact {
  bool in_contact = false;
  Vec3 force = Vec3::Zero();  ///< on the device, N
  Vec3 contact_point = Vec3::Zero();
  std::uint32_t body_id = 0;
  std::int32_t triangle = -1;
  Vec3 barycentric = Vec3::Zero();
};

/// Finds the deepest contact of the proxy sphere at `position` with any body and returns the
/// force k·depth along the contact normal, clamped to the maximum force. Free: zero force and
/// the contact point at the position.
ProxyContact solve_proxy_contact(const SceneSnapshot& snapshot, const ProxySettings& settings,
                                 const Vec3& position);

}  // namespace felt
