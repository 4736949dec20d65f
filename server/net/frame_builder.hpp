#pragma once
// Snapshot -> felt.v1.Frame.

#include <cstdint>
#include <vector>

#include "felt/v1/frames.pb.h"
#include "runtime/scene_registry.hpp"
#include "runtime/snapshot.hpp"

namespace felt::net {

/// Fills `frame` with every body's positions (float32) and, when asked, normals. Triangles go
/// to the bodies whose `topology_sent` flag is false; those flags are set and the bodies
/// returned.
std::vector<std::uint32_t> build_frame(const SceneSnapshot& snapshot, SceneId scene_id,
                                       bool normals, std::vector<bool>& topology_sent,
                                       std::uint64_t skipped, felt::v1::Frame& frame);

}  // namespace felt::net
