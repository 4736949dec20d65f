#pragma once
// Friction on the god-object as CHAI3D's finger proxy (cAlgorithmFingerProxy): the proxy sticks
// where it first met the surface, or where it stuck the update before, while the device stays
// inside the static cone around the frictionless proxy (of radius μs · depth); once it leaves, the
// proxy slips and is dragged until the device lies on the dynamic cone (μd · depth).

#include "core/haptics/candidate_triangles.hpp"
#include "core/haptics/constrained_move.hpp"
#include "core/haptics/haptic_surface.hpp"
#include "core/haptics/proxy_settings.hpp"

namespace felt {

struct FrictionStop {
  Vec3 rest;              ///< where the proxy rests: a skin outside what holds it
  bool slipping = false;  ///< false: sticking (or free, or no friction)
};

/// Where friction holds the proxy of `radius` in contact whose frictionless move from `start`
/// toward `device` is `frictionless`. `was_in_contact`, `was_slipping`: the previous update's
/// state. A drag back toward where it stuck sweeps against `candidates`, gathered from
/// `surface`.
FrictionStop hold_by_friction(const HapticSurface& surface, CandidateTriangles& candidates,
                              const ProxySettings& settings, const ConstrainedMove& frictionless,
                              const Vec3& start, const Vec3& device, Real radius,
                              bool was_in_contact, bool was_slipping);

}  // namespace felt
