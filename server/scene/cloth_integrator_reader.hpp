#pragma once
// A cloth's "integrator" (docs/scenes.md "integrator"), and the check that the integrator can step
// the cloth at all (docs/scenes.md "Stable steps").

#include <memory>

#include "core/cloth/cloth_body.hpp"
#include "core/step/health_settings.hpp"
#include "scene/object_reader.hpp"

namespace felt::scene_json {

/// A cloth's "integrator": a name, or an object with the name and the integrator's parameters
/// (xpbd's "substeps", adaptive_rk's "tolerance").
std::unique_ptr<Integrator> read_cloth_integrator(const ObjectReader& body);

/// Refuses a cloth whose explicit integrator no step keeps stable (explicit Euler or midpoint
/// on undamped springs) or, with automatic substeps, one whose stable step needs more substeps
/// of `time_step` than the step budget allows: both would run into their limits at every step.
void check_stable_step(const ObjectReader& body, const ClothBody& cloth, Real time_step,
                       const HealthSettings& health);

}  // namespace felt::scene_json
