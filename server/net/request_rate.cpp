#include "net/request_rate.hpp"

#include <algorithm>
#include <cmath>

namespace felt::net {

RequestRate::RequestRate(double per_second, double burst, Clock::time_point now)
    : per_second_(per_second), burst_(burst), tokens_(burst), filled_(now) {}

RequestRate::Clock::duration RequestRate::wait(Clock::time_point now) {
  if (now > filled_) {
    const double elapsed = std::chrono::duration<double>(now - filled_).count();
    tokens_ = std::min(burst_, tokens_ + elapsed * per_second_);
    filled_ = now;
  }
  if (tokens_ >= 1) return Clock::duration::zero();
  // rounded up, so that the wait always brings the token
  const double seconds = (1 - tokens_) / per_second_;
  return std::chrono::ceil<Clock::duration>(std::chrono::duration<double>(seconds));
}

double request_burst(double per_second) {
  return std::max(32.0, per_second / 10);
}

}  // namespace felt::net
