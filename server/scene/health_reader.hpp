#pragma once
// A scene's "health" object: how its steps are judged and rescued (docs/scenes.md "Numerical
// health").

#include <cstdint>

#include "core/world/world.hpp"
#include "scene/object_reader.hpp"

namespace felt::scene_json {

/// The largest "step_budget": 1e5 substeps of a 100 x 100 cloth take seconds.
inline constexpr std::int64_t kMaxStepBudget = 100000;

/// Reads the keys of `health` into `settings`.
void read_health(const ObjectReader& health, WorldSettings& settings);

}  // namespace felt::scene_json
