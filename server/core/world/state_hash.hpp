#pragma once

#include <cstdint>

#include "core/world/world.hpp"

namespace felt {

/// FNV-1a over the exact bits of every body's positions and velocities and the world clock:
/// two runs agree on it only if they are bit-identical.
std::uint64_t state_hash(const World& world);

}  // namespace felt
