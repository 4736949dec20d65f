#pragma once
// A body's own "max_step" (docs/scenes.md "Bodies"): the longest step it takes, as substeps of
// the scene's. SetBodyParameters.max_step takes the same range.

#include "core/step/health_settings.hpp"
#include "scene/object_reader.hpp"

namespace felt::scene_json {

/// s: shorter steps make a body's error rounding, longer ones are longer than any time step.
inline constexpr Real kMinBodyStep = 1e-6;
inline constexpr Real kMaxBodyStep = 1;

/// The body's "max_step" within [kMinBodyStep, kMaxBodyStep], infinite when absent. Refused
/// when the time step would need more substeps, each of `internal_steps` internal steps of its
/// integrator (xpbd's substeps), than the step budget lets a step take.
Real read_max_step(const ObjectReader& body, Real time_step, const HealthSettings& health,
                   int internal_steps = 1);

}  // namespace felt::scene_json
