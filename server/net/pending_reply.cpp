#include "net/pending_reply.hpp"

#include "net/session.hpp"
#include "net/wire_convert.hpp"

namespace felt::net {

namespace v1 = felt::v1;

PendingReply::PendingReply(std::shared_ptr<Session> session, std::uint64_t request_id)
    : session_(session), request_id_(request_id) {
  session->begin_deferred();
}

PendingReply::~PendingReply() {
  if (!sent_) fail(v1::ERROR_CODE_INTERNAL, "the request was dropped");
}

void PendingReply::send(v1::ServerMessage message) {
  if (sent_.exchange(true)) return;
  auto session = session_.lock();
  if (!session) return;
  message.set_request_id(request_id_);
  // the reference moves into the handler: this thread must never hold the last one, or the
  // session would be destroyed here
  Session& target = *session;
  target.post([session = std::move(session), message = std::move(message)] {
    session->end_deferred(message);
  });
}

void PendingReply::fail(v1::ErrorCode code, std::string message) {
  v1::ServerMessage reply;
  fill_error(request_id_, code, message, reply);
  send(std::move(reply));
}

}  // namespace felt::net
