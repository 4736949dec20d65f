#include "core/collider.hpp"

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

/// Tells whether a point may be closer than `reach` to a collider's surface, without a root or
/// a division: nearly every particle of a cloth is far from a small ball (a haptic proxy), and
/// a full signed distance for each cost a fifth of a step with eight proxies in the scene. What
/// it needs of the collider is worked out once, not per particle.
class NearTest {
 public:
  NearTest(const Collider& c, Real reach) : shape_(c.shape), reach_(reach) {
    switch (c.shape) {
      case Collider::Shape::kPlane:
        center_ = c.center;
        axis_ = c.normal;
        break;
      case Collider::Shape::kBox:
        center_ = c.center;
        axis_ = c.half_extents;
        break;
      case Collider::Shape::kSphere:
        center_ = c.center;
        radius_sq_ = (c.radius + reach) * (c.radius + reach);
        break;
      case Collider::Shape::kCapsule: {
        // the ball around the capsule
        center_ = 0.5 * (c.center + c.end);
        const Real r = c.radius + reach + 0.5 * (c.end - c.center).norm();
        radius_sq_ = r * r;
        break;
      }
    }
  }

  bool operator()(const Vec3& p) const {
    switch (shape_) {
      case Collider::Shape::kPlane:
        return axis_.dot(p - center_) < reach_;
      case Collider::Shape::kBox:
        // the distance to a box is at least its largest per-axis distance outside it
        return ((p - center_).cwiseAbs() - axis_).maxCoeff() < reach_;
      case Collider::Shape::kSphere:
      case Collider::Shape::kCapsule:
        return (p - center_).squaredNorm() < radius_sq_;
    }
    return true;
  }

 private:
  Collider::Shape shape_;
  Real reach_;
  Vec3 center_ = Vec3::Zero();
  Vec3 axis_ = Vec3::Zero();  ///< plane: its normal; box: its half extents
  Real radius_sq_ = 0;        ///< sphere, capsule: of the ball around it, grown by the reach
};

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
    const NearTest may_be_near(collider, thickness);
    for (std::size_t p = 0; p < state.size(); ++p) {
      if (inv_mass[p] == 0 || !may_be_near(state.x[p])) continue;
      const SignedDistance sd = signed_distance(collider, state.x[p]);
      if (sd.distance >= thickness) continue;
      ++contacts;
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
  }
  return contacts;
}

}  // namespace felt
