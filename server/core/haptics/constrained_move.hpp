#pragma once
// The constrained move of the god-object (Zilles & Salisbury 1995; Ruspini et al. 1997 for a
// finite radius): leg 2 of an update (god_object.hpp), the proxy slid from where the surface
// carried it toward the device against the surface as rendered now, held by up to three
// constraint planes (a face, a crease, a corner).

#include <optional>

#include "core/haptics/candidate_triangles.hpp"
#include "core/haptics/haptic_surface.hpp"

namespace felt {

struct ConstrainedMove {
  Vec3 position = Vec3::Zero();    ///< where the proxy rests: a skin outside what holds it
  int constraints = 0;             ///< planes holding the proxy where it stopped
  std::optional<Vec3> first_stop;  ///< where it first met the surface
};

/// Sweeps the sphere of `radius` from `start` toward `goal`; each triangle met becomes a
/// plane, the goal is projected onto the free side of the planes and swept to again; planes
/// the goal is on the free side of are dropped; a fourth plane stops it. Gathers into
/// `candidates` the triangles of `surface` each sweep looks at.
ConstrainedMove move_proxy(const HapticSurface& surface, CandidateTriangles& candidates,
                           const Vec3& start, const Vec3& goal, Real radius);

}  // namespace felt
