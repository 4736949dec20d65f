#include "runtime/pacer.hpp"

#include <gtest/gtest.h>

#include "manual_clock.hpp"

namespace felt {
namespace {

using namespace std::chrono_literals;

/// Nanoseconds from `from` to `to`.
long long ns(Clock::time_point from, Clock::time_point to) {
  return std::chrono::nanoseconds(to - from).count();
}

TEST(Pacer, SimulatedTimeFollowsTheClockTimesTheScale) {
  ManualClock clock;
  Pacer pacer(clock, 1e-3);
  const Clock::time_point start = clock.now();
  EXPECT_EQ(pacer.lag(0), 0);  // the origin is now
  EXPECT_NEAR(ns(start, pacer.next_due(0)), 1'000'000, 1);
  clock.advance(10ms);
  EXPECT_NEAR(pacer.lag(0), 0.010, 1e-12);
  EXPECT_NEAR(pacer.lag(0.004), 0.006, 1e-12);
  // twice as fast from where the scene is: the next step is due in half a step of the clock
  pacer.set_scale(2);
  EXPECT_EQ(pacer.lag(0.004), 0);
  EXPECT_NEAR(ns(clock.now(), pacer.next_due(0.004)), 500'000, 1);
  clock.advance(5ms);
  EXPECT_NEAR(pacer.lag(0.004), 0.010, 1e-12);
}

TEST(Pacer, AFarLagResynchronisesToOneStepBehind) {
  ManualClock clock;
  Pacer pacer(clock, 1e-3);
  EXPECT_EQ(pacer.lag(0), 0);
  clock.advance(1s);
  EXPECT_EQ(pacer.lag(0), 1e-3);  // not a second of steps in a burst
  // and from there on the clock again
  clock.advance(2ms);
  EXPECT_NEAR(pacer.lag(0.001), 0.002, 1e-12);
}

// Issue 31, found 5: a scale of 1e-300 overflowed a signed duration (undefined behaviour), made
// the next step due in the past, and the physics thread spun while the scene stood still.
TEST(Pacer, ATinyScaleHoldsTheSceneStillWithNoStepDueForLong) {
  ManualClock clock;
  Pacer pacer(clock, 1e-3);
  clock.advance(1h);
  EXPECT_EQ(pacer.lag(5.0), 0);
  pacer.set_scale(1e-300);
  EXPECT_EQ(pacer.lag(5.0), 0);
  EXPECT_GE(pacer.next_due(5.0), clock.now() + 24h);
  clock.advance(100h);
  const double lag = pacer.lag(5.0);
  EXPECT_GE(lag, 0);
  EXPECT_LT(lag, 1e-3);
  EXPECT_GE(pacer.next_due(5.0), clock.now() + 24h);
  // and back to real time from where it stands
  pacer.set_scale(1);
  EXPECT_EQ(pacer.lag(5.0), 0);
  EXPECT_NEAR(ns(clock.now(), pacer.next_due(5.0)), 1'000'000, 1);
}

TEST(Pacer, ALateSceneOfAnyClockNeverOverflows) {
  ManualClock clock;
  Pacer pacer(clock, 0.1);
  pacer.set_scale(100);
  EXPECT_EQ(pacer.lag(9e8), 0);  // a restored clock may be near 1e9 s
  clock.advance(1ms);
  EXPECT_NEAR(pacer.lag(9e8), 0.1, 1e-6);
  EXPECT_NEAR(ns(clock.now(), pacer.next_due(9e8)), 0, 1);
}

}  // namespace
}  // namespace felt
