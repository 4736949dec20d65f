#pragma once

#include <limits>

#include "core/math/types.hpp"

namespace felt {

/// An axis-aligned bounding box; a default one is empty and grows to enclose what it is given.
struct Aabb {
  Vec3 lo = Vec3::Constant(std::numeric_limits<Real>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<Real>::infinity());

  void grow(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void grow(const Aabb& box) {
    lo = lo.cwiseMin(box.lo);
    hi = hi.cwiseMax(box.hi);
  }
  Aabb inflated(Real margin) const { return {lo.array() - margin, hi.array() + margin}; }
  bool empty() const { return (lo.array() > hi.array()).any(); }
  bool overlaps(const Aabb& box) const {
    return (lo.array() <= box.hi.array()).all() && (box.lo.array() <= hi.array()).all();
  }
  bool contains(const Aabb& box) const {
    return (lo.array() <= box.lo.array()).all() && (box.hi.array() <= hi.array()).all();
  }
  /// Squared distance from p to the nearest point of the box: 0 inside, infinite when empty.
  Real squared_distance(const Vec3& p) const {
    return (p - p.cwiseMax(lo).cwiseMin(hi)).squaredNorm();
  }
};

}  // namespace felt
