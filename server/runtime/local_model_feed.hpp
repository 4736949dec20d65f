#pragma once
// When a local-model proxy gets its next model of the surface near it (issue 26; the protocol's
// LocalModel): with the reply to an update from its device, when the physics thread has
// published a snapshot since the last model, and no more often than the rate it asked for.

#include <chrono>
#include <cstdint>

#include "core/math/types.hpp"

namespace felt {

struct LocalModelRequest {
  Real radius = 0.1;  ///< m: triangles this near the proxy go into the model
  Real rate_hz = 0;   ///< models per second at most; 0: one per snapshot
};

class LocalModelFeed {
 public:
  using Clock = std::chrono::steady_clock;

  explicit LocalModelFeed(const LocalModelRequest& request) : request_(request) {}

  const LocalModelRequest& request() const { return request_; }
  /// Whether a model of the snapshot with `version` is due at `now`.
  bool due(std::uint64_t version, Clock::time_point now) const;
  /// A model of the snapshot with `version` was sent at `now`.
  void sent(std::uint64_t version, Clock::time_point now);

 private:
  LocalModelRequest request_;
  bool any_sent_ = false;
  std::uint64_t version_ = 0;
  Clock::time_point sent_at_{};
};

}  // namespace felt
