#include "core/collision/collider.hpp"

#include <algorithm>
#include <cmath>

namespace felt {
namespace {

SignedDistance from_center(const Vec3& p, const Vec3& center, Real radius) {
  const Vec3 offset = p - center;
  const Real length = offset.norm();
  // at the exact centre any direction is as good: push up
  return {length - radius, length > 0 ? Vec3(offset / length) : Vec3::UnitY()};
}

SignedDistance box_distance(const Vec3& p, const Vec3& center, const Vec3& half) {
  const Vec3 local = p - center;
  const Vec3 q = local.cwiseAbs() - half;
  if ((q.array() > 0).any()) {
    // outside: distance to the nearest point of the box
    const Vec3 outside = q.cwiseMax(0);
    const Real distance = outside.norm();
    Vec3 normal = outside.cwiseProduct(local.cwiseSign()) / distance;
    return {distance, normal};
  }
  // inside: the nearest face decides
  int axis = 0;
  q.maxCoeff(&axis);
  Vec3 normal = Vec3::Zero();
  normal[axis] = local[axis] >= 0 ? 1 : -1;
  return {q[axis], normal};
}

/// Calls `resolve` with a test of whether a point may be closer than `reach` to a collider's
/// surface, without a root or a division: nearly every particle of a cloth is far from a small
/// ball (a haptic proxy), and a full signed distance for each cost a fifth of a step with eight
/// proxies in the scene. What the test needs of the collider is worked out once, and its shape
/// chosen once, not per particle.
template <class Resolve>
std::size_t with_near_test(const Collider& c, Real reach, Resolve resolve) {
  switch (c.shape) {
    case Collider::Shape::kPlane:
      return resolve([center = c.center, normal = c.normal, reach](const Vec3& p) {
        return normal.dot(p - center) < reach;
      });
    case Collider::Shape::kBox:
      // the distance to a box is at least its largest per-axis distance outside it
      return resolve([center = c.center, half = c.half_extents, reach](const Vec3& p) {
        return ((p - center).cwiseAbs() - half).maxCoeff() < reach;
      });
    case Collider::Shape::kSphere: {
      const Real r = c.radius + reach;
      return resolve([center = c.center, r_sq = r * r](const Vec3& p) {
        return (p - center).squaredNorm() < r_sq;
      });
    }
    case Collider::Shape::kCapsule: {
      // the ball around the capsule
      const Vec3 center = 0.5 * (c.center + c.end);
      const Real r = c.radius + reach + 0.5 * (c.end - c.center).norm();
      return resolve(
          [center, r_sq = r * r](const Vec3& p) { return (p - center).squaredNorm() < r_sq; });
    }
  }
  return resolve([](const Vec3&) { return true; });
}

}  // namespace

SignedDistance signed_distance(const Collider& c, const Vec3& p) {
  switch (c.shape) {
    case Collider::Shape::kPlane:
      return {c.normal.dot(p - c.center), c.normal};
    case Collider::Shape::kSphere:
      return from_center(p, c.center, c.radius);
    case Collider::Shape::kBox:
      return box_distance(p, c.center, c.half_extents);
    case Collider::Shape::kCapsule: {
      const Vec3 axis = c.end - c.center;
      const Real length_sq = axis.squaredNorm();
      const Real t =
          length_sq > 0 ? std::clamp((p - c.center).dot(axis) / length_sq, Real{0}, Real{1}) : 0;
      return from_center(p, c.center + t * axis, c.radius);
    }
  }
  return {};
}

std::size_t resolve_collisions(std::span<const Collider> colliders, std::span<const Real> inv_mass,
                               Real thickness, ParticleState& state) {
  std::size_t contacts = 0;
  for (const Collider& collider : colliders) {
    contacts += with_near_test(collider, thickness, [&](const auto& may_be_near) {
      std::size_t found = 0;
      for (std::size_t p = 0; p < state.size(); ++p) {
        if (inv_mass[p] == 0 || !may_be_near(state.x[p])) continue;
        const SignedDistance sd = signed_distance(collider, state.x[p]);
        if (sd.distance >= thickness) continue;
        ++found;
        state.x[p] += (thickness - sd.distance) * sd.normal;
        const Real normal_speed = state.v[p].dot(sd.normal);
        if (normal_speed >= 0) continue;  // already leaving
        const Vec3 tangential = state.v[p] - normal_speed * sd.normal;
        const Real tangential_speed = tangential.norm();
        // the normal impulse −v_n bounds the friction impulse by μ |v_n|; it may stop the slide
        const Real slowed = std::max(Real{0}, tangential_speed + collider.friction * normal_speed);
        state.v[p] =
            tangential_speed > 0 ? Vec3(tangential * (slowed / tangential_speed)) : Vec3::Zero();
      }
      return found;
    });
  }
  return contacts;
}

}  // namespace felt
