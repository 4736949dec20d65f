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

}  // namespace
}  // namespace felt
