// The idle-core spinners: one per core, under SCHED_IDLE; asleep until touched, spinning for
// the linger after a touch, asleep again after it, or spinning until destroyed when asked; a
// linger of zero is refused.

#include <gtest/gtest.h>
#include <sched.h>

#include <thread>

#include "scheduling/idle_core_spinners.hpp"
#include "support/process_threads.hpp"

namespace felt {
namespace {

using namespace std::chrono_literals;

std::unique_ptr<IdleCoreSpinners> started(std::chrono::milliseconds linger) {
  auto spinners = IdleCoreSpinners::start(linger);
  EXPECT_TRUE(spinners.has_value()) << spinners.error();
  return spinners ? std::move(*spinners) : nullptr;
}

TEST(IdleCoreSpinners, ALingerOfZeroIsRefused) {
  const auto spinners = IdleCoreSpinners::start(0ms);
  ASSERT_FALSE(spinners.has_value());
  EXPECT_NE(spinners.error().find("more than 0"), std::string::npos) << spinners.error();
}

TEST(IdleCoreSpinners, OneSpinnerPerCoreRunsUnderSchedIdle) {
  cpu_set_t allowed;
  ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
  const int before = test::sched_idle_threads("self").count;
  const auto spinners = started(100ms);
  ASSERT_TRUE(spinners);
  EXPECT_EQ(spinners->cores(), static_cast<std::size_t>(CPU_COUNT(&allowed)));
  EXPECT_EQ(test::sched_idle_threads("self").count - before, CPU_COUNT(&allowed));
}

TEST(IdleCoreSpinners, TheySleepUntilTouched) {
  const auto spinners = started(100ms);
  ASSERT_TRUE(spinners);
  std::this_thread::sleep_for(200ms);
  // waking up and going to sleep once takes microseconds; spinning would take most of 200 ms
  EXPECT_LT(spinners->cpu_time(), 5ms);
}

TEST(IdleCoreSpinners, ATouchMakesThemSpinAndAfterTheLingerTheySleepAgain) {
  const auto spinners = started(20ms);
  ASSERT_TRUE(spinners);
  // they run only on idle cores: on a machine busy with other tests that may take a while
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (spinners->cpu_time() < 2ms && std::chrono::steady_clock::now() < deadline) {
    spinners->touch(std::chrono::steady_clock::now());
    std::this_thread::sleep_for(2ms);
  }
  ASSERT_GE(spinners->cpu_time(), 2ms) << "the spinners never ran in 20 s";
  std::this_thread::sleep_for(100ms);  // the linger has passed
  const auto asleep = spinners->cpu_time();
  std::this_thread::sleep_for(200ms);
  EXPECT_LT(spinners->cpu_time() - asleep, 5ms);
}

TEST(IdleCoreSpinners, ATouchOlderThanTheLingerDoesNotWakeThem) {
  const auto spinners = started(50ms);
  ASSERT_TRUE(spinners);
  spinners->touch(std::chrono::steady_clock::now() - 1s);
  std::this_thread::sleep_for(200ms);
  EXPECT_LT(spinners->cpu_time(), 5ms);
}

TEST(IdleCoreSpinners, SpinningUntilDestroyedOutlastsTheLinger) {
  const auto spinners = started(10ms);
  ASSERT_TRUE(spinners);
  spinners->spin_until_destroyed();
  std::this_thread::sleep_for(50ms);  // well past the linger
  const auto before = spinners->cpu_time();
  // they run only on idle cores: on a machine busy with other tests that may take a while
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (spinners->cpu_time() - before < 2ms && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(2ms);
  }
  EXPECT_GE(spinners->cpu_time() - before, 2ms) << "they stopped spinning after the linger";
}

}  // namespace
}  // namespace felt
