#pragma once
// A value one thread publishes and any thread reads: an immutable object behind a shared_ptr,
// swapped under a mutex. Not std::atomic<std::shared_ptr>: libstdc++'s spins on a lock bit,
// and a real-time network thread (feltd serve --realtime) spinning on it while the
// normal-priority physics thread that holds it waits for the same core never lets it go; a
// mutex puts the reader to sleep instead, and the holder runs.

#include <memory>
#include <mutex>
#include <utility>

namespace felt {

template <class T>
class Published {
 public:
  std::shared_ptr<const T> load() const {
    std::lock_guard lock(mutex_);
    return value_;
  }

  void store(std::shared_ptr<const T> value) {
    {
      std::lock_guard lock(mutex_);
      value.swap(value_);
    }
    // the old value may be the last reference to a large snapshot: freed outside the lock
  }

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const T> value_;
};

}  // namespace felt
