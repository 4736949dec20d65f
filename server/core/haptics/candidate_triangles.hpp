#pragma once
// The triangles a god-object update looks at: gathered box by box from the bodies' broad
// phases (their TriangleQuery) as the stages need them, at the state the update renders, with
// what the stages' cheap rejections read (unit normals, bounding circles in their planes,
// boxes). Structure of arrays, kept from update to update so that an update allocates nothing
// once warm.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/collision/sphere_sweep.hpp"
#include "core/haptics/haptic_surface.hpp"
#include "core/math/aabb.hpp"

namespace felt {

/// The box around the segment p0 → p1, grown by `margin`.
Aabb segment_box(const Vec3& p0, const Vec3& p1, Real margin);

class CandidateTriangles {
 public:
  /// Starts an update with no candidates.
  void forget();
  /// Adds the triangles of `surface` in `region`, unless a region gathered before in this
  /// update holds it. In index order whatever the broad phase, so that every structure feeds the
  /// same triangles in the same order and a replay against another is bit for bit the same.
  void gather(const HapticSurface& surface, const Aabb& region);

  std::size_t size() const { return now_.size(); }
  /// Candidate i's body: an index into HapticSurface::bodies.
  std::uint32_t body(std::size_t i) const { return body_[i]; }
  /// Candidate i's triangle in its body. Equal hits and distances go to the lower index, so a
  /// result does not depend on the order a broad phase lists candidates in.
  std::uint32_t triangle(std::size_t i) const { return triangle_[i]; }
  const TriangleCorners& corners(std::size_t i) const { return now_[i]; }
  /// Unit; zero for a triangle without area.
  const Vec3& normal(std::size_t i) const { return normal_[i]; }
  const Aabb& bounds(std::size_t i) const { return bounds_[i]; }

  /// A lower bound on the distance from p to candidate i, far cheaper than the distance: the
  /// height over its plane, with how far p's foot on the plane lies outside its circle.
  Real distance_bound(std::size_t i, const Vec3& p) const;
  /// Whether the whole segment p0 → p1 (of `length`) stays farther than `reach` from
  /// candidate i, by two cheap tests: beyond its plane on one side at both ends (the height is
  /// affine along the segment), or far from it at both ends (the distance changes no faster
  /// than the point moves, so it stays above the mean of the ends less half the length).
  bool out_of_reach(std::size_t i, const Vec3& p0, const Vec3& p1, Real length, Real reach) const;

 private:
  static constexpr std::size_t kGatheredBoxes = 16;
  std::vector<Aabb> gathered_;
  std::vector<std::vector<std::uint32_t>> stamps_;  ///< per body and triangle: epoch gathered
  std::uint32_t epoch_ = 0;                         ///< of the current update
  std::vector<std::uint32_t> body_;
  std::vector<std::uint32_t> triangle_;
  std::vector<TriangleCorners> now_;
  std::vector<Vec3> normal_;
  std::vector<Vec3> centre_;  ///< centroid
  std::vector<Real> extent_;  ///< largest distance of a corner from the centroid
  std::vector<Aabb> bounds_;
  std::vector<std::uint32_t> collected_;  ///< a broad phase's answer, reused
};

// inline: the stages call these in their innermost loops
inline Real CandidateTriangles::distance_bound(std::size_t i, const Vec3& p) const {
  const Vec3 d = p - centre_[i];
  const Real height = normal_[i].dot(d);
  const Real across = std::sqrt(std::max(d.squaredNorm() - height * height, Real{0})) - extent_[i];
  return across > 0 ? std::sqrt(height * height + across * across) : std::abs(height);
}

inline bool CandidateTriangles::out_of_reach(std::size_t i, const Vec3& p0, const Vec3& p1,
                                             Real length, Real reach) const {
  const Real h0 = normal_[i].dot(p0 - centre_[i]);
  const Real h1 = normal_[i].dot(p1 - centre_[i]);
  if ((h0 > reach && h1 > reach) || (h0 < -reach && h1 < -reach)) return true;
  return distance_bound(i, p0) + distance_bound(i, p1) - length > 2 * reach;
}

}  // namespace felt
