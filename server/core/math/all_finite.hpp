#pragma once
// Whether a set of vectors holds only finite numbers: what the health checks and a run's
// statistics ask of a body's state before anyone sees it.

#include <algorithm>
#include <span>

#include "core/math/types.hpp"

namespace felt {

inline bool all_finite(std::span<const Vec3> values) {
  return std::ranges::all_of(values, [](const Vec3& v) { return v.allFinite(); });
}

}  // namespace felt
