#pragma once
// Clamping a vector's length, as the haptic force limits do, without overflow: the squared
// norm of a finite vector overflows once a component passes ~1e154, and `v * (max / inf)` is
// zero, so a naive clamp turned a device 1e200 m away into no force at all (issue 31).

#include <cmath>

#include "core/math/types.hpp"

namespace felt {

/// `v` scaled down to `max_length` (≥ 0) when it is longer, for any finite `v`: when its
/// squared norm overflows it is measured in units of its largest component. Equal to
/// `v * (max_length / v.norm())` wherever that does not overflow. A non-finite `v` comes back
/// as it is: what leaves the caller is checked there.
inline Vec3 clamp_length(const Vec3& v, Real max_length) {
  const Real length = v.norm();
  if (length <= max_length) return v;
  if (std::isfinite(length)) return v * (max_length / length);
  const Real largest = v.cwiseAbs().maxCoeff();
  if (!std::isfinite(largest)) return v;
  const Vec3 direction = v / largest;  // its largest component ±1: the norm is in [1, √3]
  return direction * (max_length / direction.norm());
}

/// A spring's force `stiffness · offset` clamped to `max_force`, scaled rather than multiplied
/// out, so that no finite offset overflows it.
inline Vec3 clamped_spring_force(Real stiffness, const Vec3& offset, Real max_force) {
  return stiffness * clamp_length(offset, max_force / stiffness);
}

}  // namespace felt
