#pragma once
// The force stage of a god-object update: the spring from the device to the proxy
// (Zilles & Salisbury 1995), or with force shading (one constraint plane) to Ruspini's
// sub-proxy on the plane through the proxy whose normal is the vertex normals interpolated at
// the contact point (Ruspini et al. 1997, after Morgenbesser & Srinivasan 1996); damping on
// the rate of change of (proxy − device) while in contact, never pulling the device into the
// surface; then the device's limits: max_force, and max_force_change from the previous force.

#include <optional>

#include "core/haptics/candidate_triangles.hpp"
#include "core/haptics/haptic_contact.hpp"
#include "core/haptics/haptic_surface.hpp"
#include "core/haptics/proxy_anchor.hpp"
#include "core/haptics/proxy_settings.hpp"

namespace felt {

/// What the force stage keeps from one update to the next.
struct ForceHistory {
  bool in_contact = false;
  Vec3 offset = Vec3::Zero();  ///< proxy − device, for damping
  Vec3 force = Vec3::Zero();   ///< the last force returned
};

/// Where the proxy ended its move.
struct ProxyRest {
  Vec3 position;        ///< where it rests: a skin outside what holds it
  Vec3 frictionless;    ///< where it would rest without friction
  int constraints = 0;  ///< planes holding it, without friction
  bool slipping = false;
};

struct RenderedContact {
  HapticContact contact;
  ForceHistory next;  ///< to keep, if the contact is finite
};

/// The reply to an update whose proxy of `radius` rests at `rest`, touching `nearest` (from
/// find_touch against `candidates`), for the device at `device`, `dt` seconds after the
/// previous update (≤ 0: unknown, no damping).
RenderedContact render_contact(const HapticSurface& surface, const CandidateTriangles& candidates,
                               const ProxySettings& settings,
                               const std::optional<NearestTriangle>& nearest, const ProxyRest& rest,
                               const Vec3& device, Real radius, Real dt,
                               const ForceHistory& history);

}  // namespace felt
