#include "runtime/stats_window.hpp"

#include <gtest/gtest.h>

namespace felt {
namespace {

using namespace std::chrono_literals;

TEST(StatsWindow, ReportsTheRatesOfAFullWindowAndThenStartsAnother) {
  const Clock::time_point start{};
  StatsWindow window(start, 2.0);
  // 400 steps of 1 ms, each taking 0.25 ms, in the first 400 ms
  for (int i = 0; i < 400; ++i) window.add_step(250us);
  EXPECT_FALSE(window.close_if_full(start + 499ms, 2.4));
  const auto rates = window.close_if_full(start + 500ms, 2.4);
  ASSERT_TRUE(rates);
  EXPECT_DOUBLE_EQ(rates->real_time_factor, 0.4 / 0.5);
  EXPECT_DOUBLE_EQ(rates->ms_per_step, 0.25);
  // the next window counts from there: a second of a paused scene, no steps
  EXPECT_FALSE(window.close_if_full(start + 999ms, 2.4));
  const auto paused = window.close_if_full(start + 1500ms, 2.4);
  ASSERT_TRUE(paused);
  EXPECT_EQ(paused->real_time_factor, 0);
  EXPECT_EQ(paused->ms_per_step, 0);
}

TEST(StatsWindow, AveragesTheStagesPerStep) {
  const Clock::time_point start{};
  StatsWindow window(start, 0.0);
  StepProfile cloth, solid;
  cloth[StepStage::kIntegration] = 3e-4;
  solid[StepStage::kDetection] = 1e-4;
  window.add_step(1ms, cloth, solid);
  cloth[StepStage::kIntegration] = 1e-4;
  cloth[StepStage::kStretchLimit] = 2e-4;
  window.add_step(1ms, cloth, StepProfile{});
  const auto rates = window.close_if_full(start + 500ms, 0.002);
  ASSERT_TRUE(rates);
  EXPECT_DOUBLE_EQ(rates->cloth_profile[StepStage::kIntegration], 2e-4);
  EXPECT_DOUBLE_EQ(rates->cloth_profile[StepStage::kStretchLimit], 1e-4);
  EXPECT_DOUBLE_EQ(rates->solid_profile[StepStage::kDetection], 0.5e-4);
  EXPECT_EQ(rates->solid_profile[StepStage::kHealth], 0);
  // the next window starts from nothing
  const auto next = window.close_if_full(start + 1000ms, 0.002);
  ASSERT_TRUE(next);
  EXPECT_EQ(next->cloth_profile[StepStage::kIntegration], 0);
}

}  // namespace
}  // namespace felt
