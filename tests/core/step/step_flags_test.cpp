// StepFlags: a set of what happened in a step, and how a failing test prints it.

#include "core/step/step_flags.hpp"

#include <sstream>

#include <gtest/gtest.h>

namespace felt {
namespace {

std::string text(StepFlags flags) {
  std::ostringstream out;
  out << flags;
  return out.str();
}

TEST(StepFlags, HoldsEachFlagApartAndJoinsSets) {
  StepFlags flags;
  EXPECT_TRUE(flags.ok());
  flags.set(StepFlag::kOverBudget);
  EXPECT_FALSE(flags.ok());
  EXPECT_TRUE(flags.has(StepFlag::kOverBudget));
  EXPECT_FALSE(flags.has(StepFlag::kRescued));
  EXPECT_FALSE(flags.has(StepFlag::kUnrecoverable));
  EXPECT_FALSE(flags.any_of({StepFlag::kRescued, StepFlag::kUnrecoverable}));
  flags |= StepFlags{StepFlag::kRescued};
  EXPECT_TRUE(flags.any_of({StepFlag::kRescued, StepFlag::kUnrecoverable}));
  EXPECT_EQ(flags, (StepFlags{StepFlag::kOverBudget, StepFlag::kRescued}));
  EXPECT_NE(flags, StepFlags{StepFlag::kRescued});
}

TEST(StepFlags, PrintAsTheirNames) {
  EXPECT_EQ(text({}), "ok");
  EXPECT_EQ(text({StepFlag::kUnrecoverable}), "unrecoverable");
  EXPECT_EQ(text({StepFlag::kOverBudget, StepFlag::kRescued}), "rescued+over_budget");
}

}  // namespace
}  // namespace felt
