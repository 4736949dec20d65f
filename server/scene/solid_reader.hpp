#pragma once
// Scene entries of soft solids ("type": "solid", docs/scenes.md) -> SolidBody.

#include <cstddef>
#include <filesystem>

#include "core/solids/solid_body.hpp"
#include "core/solids/solid_system.hpp"
#include "core/step/health_settings.hpp"
#include "scene/object_reader.hpp"

namespace felt::scene_json {

/// The solid described by `body`, the `index`th body of the scene. Files resolve inside
/// `asset_root`; its nodes and fine vertices count against `particles_left`. `time_step` is
/// the scene's: a material so stiff for its mass that the step would need absurdly many
/// substeps is refused here rather than stalling the server, as is a "max_step" beyond
/// `health`'s step budget.
SolidBody read_solid(const ObjectReader& body, std::size_t index,
                     const std::filesystem::path& asset_root, Real time_step,
                     const HealthSettings& health, std::size_t& particles_left);

/// The scene's "solids" settings of the contact pipeline, for a scene stepping `time_step`.
SolidStepSettings read_solid_settings(const ObjectReader& solids, Real time_step);

}  // namespace felt::scene_json
