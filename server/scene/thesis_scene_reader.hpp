#pragma once
// The second thesis's own scene files (its Appendix B.3), read as the equivalent JSON scene:
//
//   # comment
//   DeformableModels
//   DeformableModel {
//     Name Cube  Path lattice:5x5x5  Immersed box:20  Mass 0.050
//     Scale 1 1 1  Translate 0 2 0  Rotate 0 0.3 0
//     Damping 2  DistancePreservation 60  VolumePreservation 20
//   }
//
// Parameters and defaults are Table B.1's; rotations are in radians and apply before the
// scale and the translation; the floor is the plane y = 0. The thesis's own mesh formats are
// replaced by what Felt reads: Path is a TetGen .node file, a closed .obj surface (voxelized;
// the surface is embedded in the lattice) or lattice:NXxNYxNZ (a unit box of that many cells),
// and Immersed, for a lattice, is box:N (a fine box surface of N×N squares per side).

#include <expected>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "scene/scene_error.hpp"

namespace felt {

/// The JSON scene (docs/scenes.md) that `text` describes; errors name `source` and the
/// line.
std::expected<nlohmann::json, SceneError> thesis_scene_to_json(std::string_view text,
                                                               const std::string& source);

}  // namespace felt
