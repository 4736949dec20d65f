#pragma once
// A scene's "health" object: how its steps are judged and rescued (docs/scenes.md "Numerical
// health").

#include "core/world/world.hpp"
#include "scene/object_reader.hpp"

namespace felt::scene_json {

/// Reads the keys of `health` into `settings`.
void read_health(const ObjectReader& health, WorldSettings& settings);

}  // namespace felt::scene_json
