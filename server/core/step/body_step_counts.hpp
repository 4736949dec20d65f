#pragma once
// What a body's steps cost, for its stats (issue 27, "bounded cost").

#include <cstdint>

namespace felt {

struct BodyStepCounts {
  int substeps = 1;  ///< in its last step: its stable step's, or a rescue's
  /// steps that reached their budget (HealthSettings::step_budget) or an integrator's cap
  std::uint64_t over_budget_steps = 0;
};

}  // namespace felt
