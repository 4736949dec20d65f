#pragma once
// A reply that comes later, from another thread (the loader, a scene's physics thread).

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "felt/v1/envelope.pb.h"

namespace felt::net {

class Session;

/// Safe to use from any thread; the reply is sent on the session's strand, once. Holding one
/// takes one of the session's requests in flight until it is sent; one dropped unsent answers
/// INTERNAL (a server bug, reported as such).
class PendingReply {
 public:
  PendingReply(std::shared_ptr<Session> session, std::uint64_t request_id);
  ~PendingReply();
  PendingReply(const PendingReply&) = delete;
  PendingReply& operator=(const PendingReply&) = delete;

  std::uint64_t request_id() const { return request_id_; }
  void send(felt::v1::ServerMessage message);
  void fail(felt::v1::ErrorCode code, std::string message);

 private:
  std::weak_ptr<Session> session_;
  std::uint64_t request_id_;
  std::atomic<bool> sent_{false};
};

}  // namespace felt::net
