// The wake-up latency request: limits outside the kernel's range are refused, a held limit is
// the one in force until it is released, and a moved hold stays held.

#include <gtest/gtest.h>

#include "scheduling/cpu_wakeup_latency.hpp"

namespace felt {
namespace {

using std::chrono::microseconds;

TEST(CpuWakeupLatency, ALimitOutsideTheKernelsRangeIsRefusedWithTheRange) {
  for (const auto limit : {microseconds{-1}, kMaxCpuWakeupLatency + microseconds{1}}) {
    const auto held = CpuWakeupLatencyLimit::hold(limit);
    ASSERT_FALSE(held.has_value()) << limit.count();
    EXPECT_NE(held.error().find("not in 0 to 2000000000"), std::string::npos) << held.error();
  }
}

TEST(CpuWakeupLatency, AHeldLimitIsInForceUntilItIsReleased) {
  const auto before = cpu_wakeup_latency_limit();
  {
    auto held = CpuWakeupLatencyLimit::hold(microseconds{123});
    if (!held || !before) GTEST_SKIP() << (held ? "the limit cannot be read" : held.error());
    // the strictest request wins: another process may hold a stricter one
    EXPECT_LE(cpu_wakeup_latency_limit()->count(), 123);
    auto strict = CpuWakeupLatencyLimit::hold(microseconds{0});
    ASSERT_TRUE(strict.has_value()) << strict.error();
    EXPECT_EQ(cpu_wakeup_latency_limit()->count(), 0);
  }
  EXPECT_EQ(cpu_wakeup_latency_limit(), before);
}

TEST(CpuWakeupLatency, AMovedHoldStaysHeld) {
  const auto before = cpu_wakeup_latency_limit();
  auto held = CpuWakeupLatencyLimit::hold(microseconds{0});
  if (!held || !before) GTEST_SKIP() << (held ? "the limit cannot be read" : held.error());
  {
    CpuWakeupLatencyLimit moved = std::move(*held);
    held = std::unexpected("moved");  // destroys the moved-from hold, which releases nothing
    EXPECT_EQ(cpu_wakeup_latency_limit()->count(), 0);
  }
  EXPECT_EQ(cpu_wakeup_latency_limit(), before);
}

}  // namespace
}  // namespace felt
