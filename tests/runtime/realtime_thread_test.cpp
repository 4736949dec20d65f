// Real-time network threads: the priority range is checked, and a real-time thread's own
// threads (a scene's physics started from a network thread) get the normal policy back.

#include <sched.h>

#include <thread>

#include <gtest/gtest.h>

#include "runtime/realtime_thread.hpp"

namespace felt {
namespace {

TEST(RealtimeThread, APriorityOutsideTheRangeIsRefusedWithTheRange) {
  for (const int priority : {0, -3, kMaxRealtimePriority + 1}) {
    const auto made = make_this_thread_realtime(priority);
    ASSERT_FALSE(made.has_value()) << priority;
    EXPECT_NE(made.error().find("1 to 99"), std::string::npos) << made.error();
  }
  EXPECT_EQ(sched_getscheduler(0) & ~SCHED_RESET_ON_FORK, SCHED_OTHER);
}

TEST(RealtimeThread, ThreadsStartedByARealtimeThreadRunUnderTheNormalPolicy) {
  int policy = -1, child_policy = -1;
  std::string refused;
  std::thread([&] {
    const auto made = make_this_thread_realtime(5);
    if (!made) {
      refused = made.error();
      return;
    }
    policy = sched_getscheduler(0) & ~SCHED_RESET_ON_FORK;
    std::thread([&] { child_policy = sched_getscheduler(0); }).join();
  }).join();
  if (!refused.empty()) GTEST_SKIP() << "this machine refuses real-time threads: " << refused;
  EXPECT_EQ(policy, SCHED_FIFO);
  EXPECT_EQ(child_policy, SCHED_OTHER);
}

}  // namespace
}  // namespace felt
