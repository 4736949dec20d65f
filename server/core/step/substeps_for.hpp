#pragma once
// How many equal substeps of a step h keep each one within a longest step: the one count the
// cloths' stable step, the solids' stable step and a body's own max_step all go through.

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/math/types.hpp"

namespace felt {

/// ⌈h / longest⌉, at least 1. The tolerance keeps a step of exactly k·longest from rounding up
/// to k + 1 substeps; a longest step of 0, below 0 or NaN (no step is short enough) and counts
/// beyond 10^18 give the largest count, which any budget refuses.
inline std::int64_t substeps_for(Real h, Real longest) {
  constexpr std::int64_t kBeyondAnyBudget = std::numeric_limits<std::int64_t>::max();
  if (!(longest > 0)) return kBeyondAnyBudget;
  const Real substeps = std::ceil(h / longest - 1e-9);
  if (substeps >= Real{1e18}) return kBeyondAnyBudget;
  return substeps < 1 ? 1 : static_cast<std::int64_t>(substeps);
}

}  // namespace felt
