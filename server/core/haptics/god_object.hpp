#pragma once
// The god-object haptic proxy (Zilles & Salisbury 1995; Ruspini et al. 1997 for a finite
// radius): a massless sphere that follows the device but never passes through a surface, held
// by up to three constraint planes (a face, a crease, a corner). The device feels a spring
// pulling it to the proxy. Surfaces may move and deform between updates; the proxy moves with
// the surface it touches and its path is tested against the triangles' motion, so a moving
// cloth never slips past it (thesis 1 §11: "the SCP sometimes falls through the cloth").
//
// Every surface is two-sided: the side the proxy's centre is on is the outside. Each update
// the proxy is anchored to the nearest triangle within its radius plus that body's
// max_displacement (proxy_anchor.hpp), and starts the next update from that placement on the
// triangle as it is rendered then.
//
// What never happens: the proxy's centre passing through the interior of a triangle (one with
// finite corners, reported by its body's TriangleQuery). Between two updates the centre takes a
// path in two legs, and each is checked:
//  1. carried with the surface, from where it was against the previous rendered state to its
//     placement on its anchor triangle against the current state, while every triangle moves
//     linearly between the two states: tested exactly (surface_carry.hpp);
//  2. slid toward the device against the current state, frozen: a swept sphere that stops
//     before it touches, and rests a skin of 1 µm outside its radius (constrained_move.hpp,
//     proxy_skin.hpp).
// Leg 2 is not tested against the motion of leg 1's interval: sliding while the surface turns
// would cross it in a linear model that the real motion does not follow.
//
// An update is a list of stages, each in its own file: the candidate triangles
// (candidate_triangles.hpp), the carry (surface_carry.hpp), the constrained move
// (constrained_move.hpp), friction (proxy_friction.hpp), the touch and anchor
// (proxy_anchor.hpp), the force (proxy_force.hpp). The force is computed from the proxy moved
// back onto its radius (the skin is not felt).

#include <optional>

#include "core/haptics/candidate_triangles.hpp"
#include "core/haptics/haptic_contact.hpp"
#include "core/haptics/haptic_surface.hpp"
#include "core/haptics/proxy_anchor.hpp"
#include "core/haptics/proxy_force.hpp"
#include "core/haptics/proxy_settings.hpp"
#include "core/haptics/surface_carry.hpp"

namespace felt {

class GodObject {
 public:
  GodObject(const ProxySettings& settings, const Vec3& device);

  /// Moves the proxy toward `device` against `surface` as rendered now, `dt` seconds after the
  /// previous update (dt ≤ 0: unknown, no damping). Never returns a non-finite value: a device
  /// position that is not finite or lies beyond ±kMaxVectorComponent (1e6 m,
  /// core/math/bounds.hpp) is no reading, and neither is an update whose result is not
  /// finite: the proxy stays where it is, free, with zero force. Triangles with a non-finite
  /// corner are not there.
  ///
  /// Force: stiffness · (proxy − device), or with force shading (one constraint plane) the
  /// spring to Ruspini's sub-proxy on the plane through the proxy whose normal is the vertex
  /// normals interpolated at the contact point; plus damping on the rate of change of
  /// (proxy − device) while in contact, never pulling the device into the surface; friction
  /// as CHAI3D's finger proxy (the proxy sticks while the device stays in the static cone and
  /// is dragged to the dynamic cone once it leaves it); then clamped to max_force and to
  /// max_force_change from the previous update's force.
  HapticContact update(const HapticSurface& surface, const Vec3& device, Real dt);

  const ProxySettings& settings() const { return settings_; }
  void set_settings(const ProxySettings& settings) { settings_ = settings; }
  /// The god-object's centre as last reported (touching the surface at exactly the radius).
  const Vec3& proxy() const { return proxy_; }
  /// Lets go of the surface kept from the previous update, and of the snapshots under it (a
  /// proxy left idle must not hold a large scene's memory): the next update is not tested
  /// against the motion since, and starts where the proxy was.
  void forget_previous_surface() { carry_.forget(); }

 private:
  /// The reply to an update that is no reading: zero force, the proxy where it was, free.
  HapticContact hold();

  ProxySettings settings_;
  Vec3 proxy_;  ///< reported centre
  Vec3 rest_;   ///< where the sphere rests: a tiny skin farther out than `proxy_`
  std::optional<ProxyAnchor> anchor_;
  bool slipping_ = false;
  ForceHistory history_;
  SurfaceCarry carry_;
  CandidateTriangles candidates_;
};

}  // namespace felt
