#pragma once
// The "haptics" object of a scene (docs/scenes.md): proxy settings, the broad phase, and the
// scripted devices the server's servo thread drives.

#include "scene/object_reader.hpp"
#include "scene/scene.hpp"

namespace felt::scene_json {

void read_haptics(const ObjectReader& haptics, Scene& scene);

}  // namespace felt::scene_json
