// The options both programs put their haptic-path threads on the scheduler with: apply() gives
// its caller the slice and says so in the program's words, schedule_this_thread() gives another
// thread the same, refusals name the program's flag, and spinners run only when asked.

#include <thread>

#include <gtest/gtest.h>

#include "scheduling/latency_options.hpp"

namespace felt {
namespace {

const LatencyNames kNames{"network threads", "--network-slice-us", "--realtime",
                          "--cpu-wakeup-latency-us", "--spin-idle-cores-ms"};

TEST(LatencyOptions, ApplyGivesTheCallerItsSliceAndSaysSoInTheProgramsWords) {
  std::chrono::microseconds mine{}, other{};
  std::vector<std::string> notes, errors;
  std::thread([&] {
    LatencyOptions options;
    options.slice = std::chrono::microseconds{400};
    const AppliedLatency applied = apply(options, kNames);
    notes = applied.notes();
    errors = applied.errors();
    mine = time_slice();
    std::thread([&] {
      applied.schedule_this_thread();
      other = time_slice();
    }).join();
  }).join();
  EXPECT_TRUE(errors.empty()) << errors.front();
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0], "network threads: 400 us time slice");
  if (mine.count() == 0) GTEST_SKIP() << "this kernel (before 6.12) reports no time slice";
  EXPECT_EQ(mine.count(), 400);
  EXPECT_EQ(other.count(), 400);
}

TEST(LatencyOptions, ARefusalNamesTheProgramsFlagAndNothingElseIsHeld) {
  std::vector<std::string> notes, errors;
  bool spinners = true;
  std::thread([&] {
    LatencyOptions options;
    options.slice = kMinTimeSlice - std::chrono::microseconds{1};
    const AppliedLatency applied = apply(options, kNames);
    notes = applied.notes();
    errors = applied.errors();
    spinners = applied.spinners() != nullptr;
  }).join();
  EXPECT_TRUE(notes.empty());
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].rfind("--network-slice-us: ", 0), 0u) << errors[0];
  EXPECT_FALSE(spinners);
}

TEST(LatencyOptions, SpinnersRunOnlyWhenAskedAndAreReported) {
  LatencyOptions options;
  options.slice = std::chrono::microseconds{0};
  options.spin_idle_cores = std::chrono::milliseconds{5};
  const AppliedLatency applied = apply(options, kNames);
  if (!applied.errors().empty()) GTEST_SKIP() << applied.errors().front();
  ASSERT_NE(applied.spinners(), nullptr);
  EXPECT_GE(applied.spinners()->cores(), 1u);
  ASSERT_EQ(applied.notes().size(), 1u);
  EXPECT_NE(applied.notes()[0].find("kept awake for 5 ms after each haptic update"),
            std::string::npos)
      << applied.notes()[0];
}

}  // namespace
}  // namespace felt
