#pragma once
// A step that left an unhealthy state is undone and tried again with twice the substeps, then
// four times, ...: the rollback-and-substep rule the cloth and the solid systems share
// (docs/scenes.md, "Numerical health").

#include <algorithm>
#include <cstdint>
#include <limits>

namespace felt {

/// How often and at what cost a failed step is retried.
struct RescuePolicy {
  int max_doublings = 6;  ///< retries, each with twice the substeps of the one before
  /// The substeps all retries of one step may take together: the larger of `min_budget` and
  /// `budget_factor` times the substeps of the first attempt. A retry that would pass it is not
  /// tried, so a step that cannot be rescued costs a few normal steps, not seconds.
  std::int64_t min_budget = std::numeric_limits<std::int64_t>::max();
  std::int64_t budget_factor = 0;
};

struct RescueOutcome {
  int substeps = 1;      ///< of the last attempt
  bool ok = false;       ///< the last attempt was healthy
  bool rescued = false;  ///< healthy only after a retry
  /// a retry was due that the budget could not afford (the retries left untried)
  bool out_of_budget = false;
};

/// Runs `attempt(substeps)` (true when the state it leaves is healthy) and, while it fails, at
/// most `max_doublings` times and while `affordable(next)` allows a retry with `next`
/// substeps, `restore()` followed by an attempt with twice the substeps. After a failed outcome
/// the state is that of the last attempt: the caller decides what to put back.
template <class Attempt, class Restore, class Affordable>
RescueOutcome step_with_rescue(int substeps, int max_doublings, Attempt&& attempt,
                               Restore&& restore, Affordable&& affordable) {
  RescueOutcome outcome{substeps, attempt(substeps), false};
  for (int doubling = 0; !outcome.ok && doubling < max_doublings; ++doubling) {
    if (!affordable(2 * outcome.substeps)) {
      outcome.out_of_budget = true;
      break;
    }
    restore();
    outcome.substeps *= 2;
    outcome.ok = attempt(outcome.substeps);
    outcome.rescued = outcome.ok;
  }
  return outcome;
}

/// The same within `policy`'s budget of retry substeps and, with the first attempt's, within
/// `step_budget` substeps in all.
template <class Attempt, class Restore>
RescueOutcome step_with_rescue(
    int substeps, const RescuePolicy& policy, Attempt&& attempt, Restore&& restore,
    std::int64_t step_budget = std::numeric_limits<std::int64_t>::max()) {
  const std::int64_t budget =
      std::max(policy.min_budget, policy.budget_factor * std::int64_t{substeps});
  std::int64_t retried = 0;
  return step_with_rescue(substeps, policy.max_doublings, attempt, restore, [&](int next) {
    if (retried + next > budget || substeps + retried + next > step_budget) return false;
    retried += next;
    return true;
  });
}

}  // namespace felt
