#pragma once
// Things that happen in a scene that its clients must hear about, beside the frames.

#include <cstdint>
#include <vector>

namespace felt {

/// Steps in which some body could not be rescued: it was rolled back to where it was before the
/// step and brought to rest (core/world.hpp). Coalesced, so an exploding scene reports at most
/// twice a second rather than every step.
struct SceneEvent {
  std::uint64_t sequence = 0;  ///< 1, 2, ... per scene
  std::uint64_t step = 0;      ///< the scene's step count when it was reported
  double sim_time = 0;
  std::uint64_t unrecoverable_steps = 0;  ///< since the previous event
  std::vector<std::uint32_t> bodies;      ///< the bodies that failed in the last of those steps
};

}  // namespace felt
