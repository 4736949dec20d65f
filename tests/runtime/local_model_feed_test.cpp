// When a local-model proxy gets its next model: once per new snapshot, at most at its rate.

#include <gtest/gtest.h>

#include "runtime/local_model_feed.hpp"

namespace felt {
namespace {

using namespace std::chrono_literals;

TEST(LocalModelFeed, SendsEachSnapshotOnceAndNoFasterThanItsRate) {
  const auto t0 = LocalModelFeed::Clock::time_point{} + 1h;
  LocalModelFeed every_step({0.1, 0});
  EXPECT_TRUE(every_step.due(1, t0));
  every_step.sent(1, t0);
  EXPECT_FALSE(every_step.due(1, t0 + 1s));  // nothing new
  EXPECT_TRUE(every_step.due(2, t0 + 1us));

  LocalModelFeed hundred({0.1, 100});
  hundred.sent(1, t0);
  EXPECT_FALSE(hundred.due(2, t0 + 9ms));
  EXPECT_TRUE(hundred.due(2, t0 + 10ms));
  EXPECT_FALSE(hundred.due(1, t0 + 20ms));
}

}  // namespace
}  // namespace felt
