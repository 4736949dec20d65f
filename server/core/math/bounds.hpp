#pragma once
// How large a number that enters from outside may be (scene files, requests, restored states):
// one bound for every coordinate, velocity and vector component, so that what comes in stays
// where doubles still tell a body's particles apart and the floats of frames still hold it.

#include "core/math/types.hpp"

namespace felt {

/// Far past any scene's extent (metres), velocity (m/s) or acceleration: a solid translated by
/// 9e15 m had nodes 0.1 m apart collapse onto each other and failed an invariant of the server.
inline constexpr Real kMaxVectorComponent = 1e6;

/// Whether every component of `v` is within ±kMaxVectorComponent (never for NaN or infinity).
inline bool within_bounds(const Vec3& v) {
  return (v.array().abs() <= kMaxVectorComponent).all();
}

}  // namespace felt
