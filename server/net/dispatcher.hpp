#pragma once
// ClientMessage -> runtime calls -> ServerMessage replies. The only code that translates
// between the wire and the runtime.

#include "felt/v1/envelope.pb.h"
#include "net/session.hpp"

namespace felt::net {

/// The protocol version this server speaks.
inline constexpr std::uint32_t kProtocolVersion = 1;

/// Handles one request of `session`; every request gets a reply or an Error.
void dispatch(Session& session, const felt::v1::ClientMessage& message);

}  // namespace felt::net
