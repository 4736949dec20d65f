#include "core/cloth/cloth_self_collision.hpp"

#include <cmath>

#include "core/geometry/triangle_geometry.hpp"
#include "core/math/check.hpp"

namespace felt {
namespace {

// A particle nearer to its triangle than this fraction of the thickness (squared) has no
// reliable direction from the nearest point; the face normal is used instead.
constexpr Real kOnSurfaceSq = 1e-24;

/// Mean edge length of the triangles at x, counting shared edges once per triangle (Teschner et
/// al.'s best cell size). Falls back to 0 when the cloth has no usable length (no triangles, or
/// a non-finite state that is about to be rolled back).
Real mean_edge_length(std::span<const Triangle> triangles, std::span<const Vec3> x) {
  Real sum = 0;
  for (const Triangle& tri : triangles) {
    sum += (x[tri[1]] - x[tri[0]]).norm() + (x[tri[2]] - x[tri[1]]).norm() +
           (x[tri[0]] - x[tri[2]]).norm();
  }
  const Real mean = sum / static_cast<Real>(3 * triangles.size());
  return std::isfinite(mean) ? mean : 0;
}

bool is_corner(const Triangle& tri, std::uint32_t p) {
  return tri[0] == p || tri[1] == p || tri[2] == p;
}

}  // namespace

std::span<const SelfProximity> ClothSelfCollision::find_proximities(
    std::span<const Triangle> triangles, std::span<const Vec3> x, Real thickness) {
  FELT_CHECK(thickness > 0 && std::isfinite(thickness));
  // a typical triangle's box grown by the thickness is about this wide, so it overlaps at most
  // two cells along each axis (Teschner et al. look up unpadded boxes in cells of the mean edge)
  hash_.begin(mean_edge_length(triangles, x) + 2 * thickness, x.size());
  for (std::uint32_t p = 0; p < x.size(); ++p) hash_.insert(0, p, x[p]);

  proximities_.clear();
  const Real thickness_sq = thickness * thickness;
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    const Vec3& a = x[tri[0]];
    const Vec3& b = x[tri[1]];
    const Vec3& c = x[tri[2]];
    const Vec3 lo = a.cwiseMin(b).cwiseMin(c).array() - thickness;
    const Vec3 hi = a.cwiseMax(b).cwiseMax(c).array() + thickness;
    hash_.for_each_in_box(lo, hi, [&](std::uint32_t /*body*/, std::uint32_t p) {
      // the hash returns whole cells; the box test is much cheaper than the nearest point
      if (is_corner(tri, p) || (x[p].array() < lo.array()).any() ||
          (x[p].array() > hi.array()).any()) {
        return;
      }
      const ClosestPoint closest = closest_point_on_triangle(x[p], a, b, c);
      // written so that a NaN distance (a corrupt state) is never a contact
      if ((x[p] - closest.point).squaredNorm() < thickness_sq) proximities_.push_back({p, t});
    });
  }
  return proximities_;
}

std::size_t ClothSelfCollision::resolve(std::span<const Triangle> triangles,
                                        std::span<const Real> inv_mass, Real thickness,
                                        ParticleState& state) {
  FELT_CHECK(inv_mass.size() == state.size() && state.v.size() == state.size());
  find_proximities(triangles, state.x, thickness);
  std::vector<Vec3>& x = state.x;
  std::vector<Vec3>& v = state.v;
  std::size_t moved = 0;
  for (const SelfProximity& pair : proximities_) {
    const Triangle& tri = triangles[pair.triangle];
    const std::uint32_t p = pair.particle;
    // again from the current positions: pairs resolved before may have separated this one
    const ClosestPoint closest = closest_point_on_triangle(x[p], x[tri[0]], x[tri[1]], x[tri[2]]);
    const Vec3 offset = x[p] - closest.point;
    const Real distance = offset.norm();
    if (!(distance < thickness)) continue;
    const Vec3& b = closest.barycentric;  // the weights of the corners
    const Vec3 triangle_velocity = b[0] * v[tri[0]] + b[1] * v[tri[1]] + b[2] * v[tri[2]];
    Vec3 normal;
    if (distance * distance > kOnSurfaceSq * thickness * thickness) {
      normal = offset / distance;
    } else {
      const Vec3 face = (x[tri[1]] - x[tri[0]]).cross(x[tri[2]] - x[tri[0]]);
      const Real area2 = face.norm();
      if (area2 == 0) continue;  // a degenerate triangle gives no direction to push
      normal = face / area2;
      // a particle moving along +n came from the back side: push it back there
      if ((v[p] - triangle_velocity).dot(normal) > 0) normal = -normal;
    }
    // a unit impulse along n changes the particle's velocity relative to the triangle's
    // nearest point by w_p + Σ b_i² w_i; the same factor relates a shared displacement to the
    // change in distance
    const Real mobility = inv_mass[p] + b[0] * b[0] * inv_mass[tri[0]] +
                          b[1] * b[1] * inv_mass[tri[1]] + b[2] * b[2] * inv_mass[tri[2]];
    if (mobility == 0) continue;  // the particle and the whole triangle are pinned
    ++moved;
    const Real push = (thickness - distance) / mobility;
    const Real approach = (v[p] - triangle_velocity).dot(normal);
    const Real impulse = approach < 0 ? -approach / mobility : 0;
    x[p] += inv_mass[p] * push * normal;
    v[p] += inv_mass[p] * impulse * normal;
    for (int k = 0; k < 3; ++k) {
      const Real share = b[k] * inv_mass[tri[k]];
      x[tri[k]] -= share * push * normal;
      v[tri[k]] -= share * impulse * normal;
    }
  }
  return moved;
}

}  // namespace felt
