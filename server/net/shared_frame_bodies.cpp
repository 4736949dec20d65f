#include "net/shared_frame_bodies.hpp"

#include <utility>

namespace felt::net {

std::shared_ptr<const EncodedBody> SharedFrameBodies::get(
    const std::shared_ptr<const SceneSnapshot>& snapshot, std::size_t index,
    const BodyEncoding& encoding, const std::function<EncodedBody()>& encode) {
  const auto find = [&]() -> std::shared_ptr<const EncodedBody> {
    for (const Entry& entry : entries_) {
      // an expired snapshot locks to null: a new one at its address never matches
      if (entry.index == index && entry.encoding == encoding && entry.snapshot.lock() == snapshot) {
        return entry.body;
      }
    }
    return nullptr;
  };
  {
    const std::lock_guard lock(mutex_);
    if (auto body = find()) {
      ++shared_;
      return body;
    }
  }
  // encoded outside the lock: another encoder thread may do the same body meanwhile, and the
  // first to finish is kept
  auto body = std::make_shared<const EncodedBody>(encode());
  const std::lock_guard lock(mutex_);
  ++encoded_;
  std::erase_if(entries_, [](const Entry& entry) { return entry.snapshot.expired(); });
  if (auto kept = find()) return kept;
  entries_.push_back({snapshot, index, encoding, body});
  return body;
}

std::uint64_t SharedFrameBodies::encoded() const {
  const std::lock_guard lock(mutex_);
  return encoded_;
}

std::uint64_t SharedFrameBodies::shared() const {
  const std::lock_guard lock(mutex_);
  return shared_;
}

}  // namespace felt::net
