// The rollback-and-substep rule the cloth and the solid systems share.

#include "core/step/substep_rescue.hpp"

#include <vector>

#include <gtest/gtest.h>

namespace felt {
namespace {

/// Attempts that succeed from `needed` substeps on, recording what was tried.
struct Trial {
  explicit Trial(int needed_substeps) : needed(needed_substeps) {}

  int needed;
  std::vector<int> tried;
  int restores = 0;

  RescueOutcome run(int first, const RescuePolicy& policy) {
    return step_with_rescue(
        first, policy,
        [&](int substeps) {
          tried.push_back(substeps);
          return substeps >= needed;
        },
        [&] { ++restores; });
  }
};

TEST(SubstepRescue, AHealthyFirstAttemptIsNotARescue) {
  Trial trial{1};
  const RescueOutcome outcome = trial.run(1, {});
  EXPECT_TRUE(outcome.ok);
  EXPECT_FALSE(outcome.rescued);
  EXPECT_EQ(outcome.substeps, 1);
  EXPECT_EQ(trial.restores, 0);
}

TEST(SubstepRescue, AFailedAttemptIsUndoneAndRetriedWithTwiceTheSubsteps) {
  Trial trial{5};
  const RescueOutcome outcome = trial.run(3, {});
  EXPECT_EQ(trial.tried, (std::vector<int>{3, 6}));
  EXPECT_TRUE(outcome.ok);
  EXPECT_TRUE(outcome.rescued);
  EXPECT_EQ(outcome.substeps, 6);
  EXPECT_EQ(trial.restores, 1);
}

TEST(SubstepRescue, RetriesStopAfterTheDoublingsAllowed) {
  Trial trial{1000};
  const RescueOutcome outcome = trial.run(1, RescuePolicy{.max_doublings = 3});
  EXPECT_EQ(trial.tried, (std::vector<int>{1, 2, 4, 8}));
  EXPECT_FALSE(outcome.ok);
  EXPECT_FALSE(outcome.rescued);
  EXPECT_EQ(outcome.substeps, 8);
}

TEST(SubstepRescue, NoRetryPassesTheBudget) {
  // retries of 2, 4 and 8 substeps add up to 14; a budget of 10 allows the first two
  Trial trial{1000};
  RescuePolicy policy{.max_doublings = 6, .min_budget = 10, .budget_factor = 0};
  trial.run(1, policy);
  EXPECT_EQ(trial.tried, (std::vector<int>{1, 2, 4}));
  // the budget grows with the first attempt: 4 × 5 substeps allow 10 (but not 10 + 20)
  Trial scaled{1000};
  policy.budget_factor = 4;
  scaled.run(5, policy);
  EXPECT_EQ(scaled.tried, (std::vector<int>{5, 10}));
}

}  // namespace
}  // namespace felt
