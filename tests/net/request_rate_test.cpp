// RequestRate, on a clock the test sets: a burst at once, then one request per 1/rate.

#include "net/request_rate.hpp"

#include <gtest/gtest.h>

namespace felt::net {
namespace {

using namespace std::chrono_literals;
using Clock = RequestRate::Clock;

double seconds(Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

TEST(RequestRate, LetsABurstThroughThenOneRequestPerPeriod) {
  const Clock::time_point start{};
  RequestRate rate(1000, 100, start);
  for (int i = 0; i < 100; ++i) {
    ASSERT_EQ(rate.wait(start), Clock::duration::zero()) << "request " << i;
    rate.take();
  }
  // empty: the next token comes 1 ms later, and not before
  EXPECT_NEAR(seconds(rate.wait(start)), 1e-3, 1e-9);
  EXPECT_NEAR(seconds(rate.wait(start + 400us)), 600e-6, 1e-9);
  EXPECT_EQ(rate.wait(start + 1001us), Clock::duration::zero());
  rate.take();
  // 50 ms bring 50 tokens
  const Clock::time_point later = start + 51ms;
  for (int i = 0; i < 50; ++i) {
    ASSERT_EQ(rate.wait(later), Clock::duration::zero()) << "request " << i;
    rate.take();
  }
  EXPECT_GT(rate.wait(later), Clock::duration::zero());
}

TEST(RequestRate, NeverHoldsMoreThanItsBurst) {
  const Clock::time_point start{};
  RequestRate rate(1000, 10, start);
  // an hour idle fills the bucket, not more
  const Clock::time_point later = start + 1h;
  for (int i = 0; i < 10; ++i) {
    ASSERT_EQ(rate.wait(later), Clock::duration::zero());
    rate.take();
  }
  EXPECT_NEAR(seconds(rate.wait(later)), 1e-3, 1e-9);
}

TEST(RequestRate, ABurstIsATenthOfASecondsRequestsAndAtLeastATurns) {
  EXPECT_DOUBLE_EQ(request_burst(20'000), 2'000);
  EXPECT_DOUBLE_EQ(request_burst(100), 32);
}

}  // namespace
}  // namespace felt::net
