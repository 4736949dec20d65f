#pragma once
// ClientMessage -> the request's handler (requests.hpp). The only code that translates between
// the wire and the runtime is in the handlers it calls.

#include "felt/v1/envelope.pb.h"
#include "net/session.hpp"

namespace felt::net {

/// Handles one request of `session`; every request gets a reply or an Error.
void dispatch(Session& session, const felt::v1::ClientMessage& message);

}  // namespace felt::net
