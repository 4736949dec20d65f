// The haptic path's threads: the slice and priority ranges are checked, a thread gets the slice
// it asked for, and the threads it starts (a scene's physics started from a network thread) get
// the default slice and the normal policy back; a thread's nice is its own.

#include <sched.h>

#include <algorithm>
#include <thread>

#include <gtest/gtest.h>

#include "scheduling/thread_latency.hpp"

namespace felt {
namespace {

TEST(TimeSlice, ASliceOutsideTheRangeIsRefusedWithTheRange) {
  for (const auto slice :
       {std::chrono::microseconds{-1}, kMinTimeSlice - std::chrono::microseconds{1},
        kMaxTimeSlice + std::chrono::microseconds{1}}) {
    const auto requested = request_time_slice(slice);
    ASSERT_FALSE(requested.has_value()) << slice.count();
    EXPECT_NE(requested.error().find("0 or in 100 to 100000"), std::string::npos)
        << requested.error();
  }
}

TEST(TimeSlice, AThreadGetsItsSliceAndTheThreadsItStartsTheDefault) {
  std::chrono::microseconds before{}, mine{}, child{};
  std::string refused;
  std::thread([&] {
    before = time_slice();
    const auto requested = request_time_slice(std::chrono::microseconds{200});
    if (!requested) {
      refused = requested.error();
      return;
    }
    mine = time_slice();
    std::thread([&] { child = time_slice(); }).join();
  }).join();
  ASSERT_TRUE(refused.empty()) << refused;
  if (before.count() == 0) GTEST_SKIP() << "this kernel (before 6.12) reports no time slice";
  EXPECT_EQ(mine.count(), 200);
  EXPECT_EQ(child, before);
}

TEST(TimeSlice, ZeroGivesTheDefaultBack) {
  std::chrono::microseconds before{}, after{};
  std::string refused;
  std::thread([&] {
    before = time_slice();
    const auto requested = request_time_slice(std::chrono::microseconds{250});
    const auto restored = request_time_slice(std::chrono::microseconds{0});
    if (!requested || !restored) {
      refused = requested ? restored.error() : requested.error();
      return;
    }
    after = time_slice();
  }).join();
  ASSERT_TRUE(refused.empty()) << refused;
  if (before.count() == 0) GTEST_SKIP() << "this kernel (before 6.12) reports no time slice";
  EXPECT_EQ(after, before);
}

TEST(TimeSlice, AnInheritedSliceGoesToTheThreadsItStarts) {
  std::chrono::microseconds child{};
  std::string refused;
  std::thread([&] {
    const auto requested =
        request_time_slice(std::chrono::microseconds{300}, SliceInheritance::kAlsoThreadsItStarts);
    if (!requested) {
      refused = requested.error();
      return;
    }
    std::thread([&] { child = time_slice(); }).join();
  }).join();
  ASSERT_TRUE(refused.empty()) << refused;
  if (child.count() == 0) GTEST_SKIP() << "this kernel (before 6.12) reports no time slice";
  EXPECT_EQ(child.count(), 300);
}

TEST(ThreadNice, IsTheCallingThreadsAloneAndGoesToTheThreadsItStarts) {
  const int mine = this_thread_nice();
  const int nicer = std::min(mine + 7, kMaxNice);
  if (nicer == mine) GTEST_SKIP() << "the test runs at the highest nice already";
  int set = -1, child = -1;
  std::string refused;
  std::thread([&] {
    const auto lowered = set_this_thread_nice(nicer);
    if (!lowered) {
      refused = lowered.error();
      return;
    }
    set = this_thread_nice();
    std::thread([&] { child = this_thread_nice(); }).join();
  }).join();
  ASSERT_TRUE(refused.empty()) << refused;
  EXPECT_EQ(set, nicer);
  EXPECT_EQ(child, nicer);
  EXPECT_EQ(this_thread_nice(), mine);
}

// Found by running the suite under nice 15 as root: feltd's background threads went to nice 10,
// above the network threads they step aside for.
TEST(ThreadNice, SteppingAsideRaisesTheNiceAndNeverLowersIt) {
  const int mine = this_thread_nice();
  if (mine + 4 > kMaxNice) GTEST_SKIP() << "the test runs too near the highest nice";
  int kept = -1, raised = -1;
  std::string refused;
  std::thread([&] {
    if (const auto set = step_this_thread_aside(mine + 2); !set) refused = set.error();
    if (const auto lower = step_this_thread_aside(mine + 1); !lower) refused = lower.error();
    kept = this_thread_nice();
    if (const auto higher = step_this_thread_aside(mine + 4); !higher) refused = higher.error();
    raised = this_thread_nice();
  }).join();
  ASSERT_TRUE(refused.empty()) << refused;
  EXPECT_EQ(kept, mine + 2);
  EXPECT_EQ(raised, mine + 4);
}

TEST(ThreadNice, ANiceOutsideTheRangeIsRefusedWithTheRange) {
  const int mine = this_thread_nice();
  for (const int nice : {-1, kMaxNice + 1}) {
    const auto set = set_this_thread_nice(nice);
    ASSERT_FALSE(set.has_value()) << nice;
    EXPECT_NE(set.error().find("0 to 19"), std::string::npos) << set.error();
  }
  EXPECT_EQ(this_thread_nice(), mine);
}

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
