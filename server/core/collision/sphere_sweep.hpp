#pragma once
// Continuous collision tests for a haptic proxy's path: a sphere (or a point) swept along a
// segment against a static triangle, and a point moving against a triangle whose corners move
// linearly over the same interval. Both look at the whole path, so a fast device or a fast
// cloth cannot step over a triangle between two updates (thesis 1 §11: the SCP fell through).

#include <optional>

#include "core/math/types.hpp"

namespace felt {

/// Where a swept sphere first touches a triangle.
struct SweepHit {
  Real t = 0;                       ///< fraction of the path at first contact, in [0, 1]
  Vec3 normal = Vec3::Zero();       ///< unit, from the touched point toward the sphere's centre
  Vec3 barycentric = Vec3::Zero();  ///< of the touched point in the triangle
};

/// Time of first contact of a sphere of `radius` (0: a point) whose centre moves from p0 to p1
/// with the static triangle (a, b, c): its face offset by `radius` on the side p0 is on, its
/// edges as capsules, its corners as spheres. A sphere that starts closer than `radius`
/// (rounding, or a surface that moved onto it) is blocked at t = 0 if it moves toward the
/// triangle and not at all if it moves away or along it. A triangle without area is its edges;
/// a point never hits one. Non-finite input gives no hit.
std::optional<SweepHit> sweep_sphere_triangle(const Vec3& p0, const Vec3& p1, Real radius,
                                              const Vec3& a, const Vec3& b, const Vec3& c);

/// The corners of a triangle at one instant.
struct TriangleCorners {
  Vec3 a;
  Vec3 b;
  Vec3 c;
};

/// The first time s ∈ [0, 1] at which a point moving linearly from p0 to p1 passes through the
/// triangle whose corners move linearly from `from` to `to` over the same interval: a root of
/// the cubic that says when the four points are coplanar (Provot 1997) at which the point lies
/// inside the triangle. Conservative: a path that grazes an edge, or ends on the triangle,
/// counts as passing through; a path that starts on the triangle's plane has no side to keep
/// and does not. A triangle that has no area at that instant cannot be passed through.
std::optional<Real> point_passes_moving_triangle(const Vec3& p0, const Vec3& p1,
                                                 const TriangleCorners& from,
                                                 const TriangleCorners& to);

}  // namespace felt
