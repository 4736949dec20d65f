#pragma once
// How the runtime names a connected client.

#include <cstdint>

#include "ids/strong_id.hpp"

namespace felt {

/// Names a connected client (a session); 0 is the server itself.
using ClientId = StrongId<struct ClientIdTag, std::uint32_t>;

}  // namespace felt
