#include "runtime/local_model_feed.hpp"

namespace felt {

bool LocalModelFeed::due(std::uint64_t version, Clock::time_point now) const {
  if (!any_sent_) return true;
  if (version == version_) return false;
  return request_.rate_hz <= 0 ||
         std::chrono::duration<Real>(now - sent_at_).count() * request_.rate_hz >= 1;
}

void LocalModelFeed::sent(std::uint64_t version, Clock::time_point now) {
  any_sent_ = true;
  version_ = version;
  sent_at_ = now;
}

}  // namespace felt
