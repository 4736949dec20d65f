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
// max_displacement (its placement: the barycentric coordinates of the nearest point and the
// offset from it in the triangle's frame), and starts the next update from that placement on
// the triangle as it is rendered then.
//
// What never happens: the proxy's centre passing through the interior of a triangle (one with
// finite corners, reported by its body's TriangleQuery). Between two updates the centre takes a
// path in two legs, and each is checked:
//  1. carried with the surface, from where it was against the previous rendered state to its
//     placement on its anchor triangle against the current state, while every triangle moves
//     linearly between the two states: tested exactly (when the point and the moving triangle
//     are coplanar, the roots of a cubic);
//  2. slid toward the device against the current state, frozen: a swept sphere that stops
//     before it touches, and rests a skin of 1 µm outside its radius.
// Leg 2 is not tested against the motion of leg 1's interval: sliding while the surface turns
// would cross it in a linear model that the real motion does not follow. The previous rendered
// state is the surface the previous update rendered (kept, with its storage, until the next),
// however many snapshots came between: a proxy updated rarely (a remote client at 20 Hz) is
// carried through all the motion since, taken as linear. If leg 1 would pass a triangle the
// proxy keeps instead the placement it had relative to that triangle; only when that fails
// too, twice (surfaces closing on the proxy from both sides, where no place keeps every side),
// is the carried leg taken regardless.
//
// The force is computed from the proxy moved back onto its radius (the skin is not felt).

#include <cstdint>
#include <optional>
#include <vector>

#include "core/collision/sphere_sweep.hpp"
#include "core/haptics/haptic_surface.hpp"
#include "core/haptics/proxy_settings.hpp"
#include "core/math/aabb.hpp"

namespace felt {

struct HapticContact {
  bool in_contact = false;
  Vec3 force = Vec3::Zero();          ///< N, to render on the device
  Vec3 proxy = Vec3::Zero();          ///< the god-object's centre
  Vec3 contact_point = Vec3::Zero();  ///< the touched surface point (the device when free)
  Vec3 normal = Vec3::Zero();         ///< the surface normal the force is shaded along
  std::uint32_t body_id = 0;          ///< the touched body and triangle, when in contact
  std::int32_t triangle = -1;
  Vec3 barycentric = Vec3::Zero();  ///< of contact_point in the touched triangle
  int constraints = 0;    ///< active constraint planes: 0 free, 1 face, 2 crease, 3 corner
  bool slipping = false;  ///< friction state: false = sticking (or free)

  /// Whether every vector is finite: what an update returns always is.
  bool finite() const {
    return force.allFinite() && proxy.allFinite() && contact_point.allFinite() &&
           normal.allFinite() && barycentric.allFinite();
  }
};

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
  void forget_previous_surface() { previous_.reset(); }

 private:
  /// Where the proxy sits relative to a triangle: the barycentric coordinates of the
  /// triangle's point nearest to it and the offset from that point in the triangle's frame
  /// (first edge, its perpendicular in the plane, the unit normal).
  struct Anchor {
    std::uint32_t body_id = 0;
    std::uint32_t body = 0;  ///< index into HapticSurface::bodies when it was made
    std::uint32_t triangle = 0;
    Vec3 barycentric = Vec3::Zero();
    Vec3 offset = Vec3::Zero();
  };

  /// Adds the triangles in `region` to the candidates, unless a region gathered before in
  /// this update holds it.
  void gather(const HapticSurface& surface, const Aabb& region);
  /// Starts an update with no candidates.
  void forget_candidates();
  /// Matches the bodies of `surface` with those of the previous update's surface and bounds
  /// how far each vertex moved since (then_, travel_, margin_).
  void follow_bodies(const HapticSurface& surface);
  /// The reply to an update that is no reading: zero force, the proxy where it was, free.
  HapticContact hold();
  /// A triangle of body `b` of `surface` as the previous update rendered it, if it had the body.
  std::optional<TriangleCorners> previous_corners(std::uint32_t b, std::uint32_t triangle) const;
  /// Leg 1 (see above): where the proxy is carried to against the current state; `before` is
  /// set to where it was against the previous state.
  Vec3 carry(const HapticSurface& surface, Vec3& before);
  /// The anchor's body index in `surface`, or none when its body or triangle is gone.
  std::optional<std::uint32_t> find_body(const HapticSurface& surface, const Anchor& anchor) const;

  ProxySettings settings_;
  Vec3 proxy_;  ///< reported centre
  Vec3 rest_;   ///< where the sphere rests: a tiny skin farther out than `proxy_`
  std::optional<Anchor> anchor_;
  std::optional<HapticSurface> previous_;  ///< what the previous update rendered against
  /// Per body of the current surface, where the previous update rendered it: a body of
  /// previous_ at its alpha, or of the current surface when that shows the same state (fewer
  /// snapshots to read); null when the body is new.
  struct Then {
    const HapticBody* body = nullptr;
    Real alpha = 0;
  };
  std::vector<Then> then_;
  std::vector<Real> travel_;  ///< per body: a bound on any vertex's move since previous_
  bool in_contact_ = false;
  bool slipping_ = false;
  Vec3 force_ = Vec3::Zero();            ///< the last force returned
  Vec3 previous_offset_ = Vec3::Zero();  ///< proxy − device at the last update, for damping
  // the triangles the update looks at, gathered box by box as it needs them, at the current
  // state, as structure of arrays; kept so that an update allocates nothing once warm
  static constexpr std::size_t kGatheredBoxes = 16;
  std::vector<Aabb> gathered_;
  std::vector<std::vector<std::uint32_t>> stamps_;  ///< per body and triangle: epoch gathered
  std::uint32_t epoch_ = 0;                         ///< of the current update
  Real margin_ = 0;                                 ///< the largest travel_
  std::vector<std::uint32_t> candidate_body_;       ///< index into HapticSurface::bodies
  std::vector<std::uint32_t> candidate_triangle_;
  std::vector<TriangleCorners> candidate_now_;
  std::vector<Vec3> candidate_normal_;  ///< unit; zero for a triangle without area
  std::vector<Vec3> candidate_centre_;  ///< centroid
  std::vector<Real> candidate_extent_;  ///< largest distance of a corner from the centroid
  std::vector<Aabb> candidate_bounds_;
  std::vector<std::uint32_t> collected_;
};

}  // namespace felt
