#pragma once
// The first Error an asynchronous client reports through on_error (a refused update, the
// server's last word, the end of the connection): where a device loop stops, and what the
// command then ends with.

#include <atomic>
#include <mutex>
#include <optional>

#include "felt_client.hpp"

namespace felt::cli {

class FirstError {
 public:
  /// Keeps `error` unless one came before; safe from any thread.
  void keep(const felt::v1::Error& error) {
    std::lock_guard lock(mutex_);
    if (!error_) error_ = error;
    any_ = true;
  }
  bool any() const { return any_; }
  /// Throws the kept Error as a ClientError, if one came.
  void throw_if_any() const {
    std::lock_guard lock(mutex_);
    if (error_) throw client::ClientError(*error_);
  }

 private:
  mutable std::mutex mutex_;
  std::optional<felt::v1::Error> error_;
  std::atomic<bool> any_{false};
};

}  // namespace felt::cli
