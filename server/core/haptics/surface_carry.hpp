#pragma once
// Leg 1 of a god-object update (god_object.hpp): the proxy carried with the surface it touches,
// from where it was against the previous rendered state to its placement on its anchor triangle
// against the current state, while every triangle moves linearly between the two states; the
// path is tested exactly against that motion (when the point and a moving triangle are
// coplanar, the roots of a cubic: point_passes_moving_triangle). The previous rendered state is
// the surface the previous update rendered (kept, with its storage, until the next), however
// many snapshots came between: a proxy updated rarely (a remote client at 20 Hz) is carried
// through all the motion since, taken as linear. If the carry would pass a triangle the proxy
// keeps instead the placement it had relative to that triangle; only when that fails too, twice
// (surfaces closing on the proxy from both sides, where no place keeps every side), is the
// carried path taken regardless.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/haptics/candidate_triangles.hpp"
#include "core/haptics/haptic_surface.hpp"
#include "core/haptics/proxy_anchor.hpp"

namespace felt {

class SurfaceCarry {
 public:
  /// Matches the bodies of `surface` with those of the surface kept from the previous update
  /// and bounds how far each vertex moved since. Call first in an update; `surface` must outlive
  /// the calls that follow until the next follow().
  void follow(const HapticSurface& surface);
  /// The largest of those bounds: how far the carry looks for triangles that moved.
  Real margin() const { return margin_; }
  /// Where the proxy resting at `rest`, anchored to `anchor`, is carried to against `surface`
  /// (the surface given to follow()). Gathers into `candidates` the triangles its path may pass.
  Vec3 carry(const HapticSurface& surface, CandidateTriangles& candidates, const Vec3& rest,
             const std::optional<ProxyAnchor>& anchor) const;
  /// Keeps `surface`, with its storage, as the previous rendered state of the next update.
  void remember(const HapticSurface& surface) { previous_ = surface; }
  /// Lets go of the previous rendered state, and of the snapshots under it: the next update is
  /// not tested against the motion since.
  void forget() { previous_.reset(); }

 private:
  /// A triangle of body `b` of the current surface as the previous update rendered it, if it
  /// had the body.
  std::optional<TriangleCorners> previous_corners(std::uint32_t b, std::uint32_t triangle) const;

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
  Real margin_ = 0;           ///< the largest travel_
};

}  // namespace felt
