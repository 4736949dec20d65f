#pragma once
// How feltd loads the scene files it is given (serve --scene, run): as a client's, with mesh
// files resolved inside one directory.

#include <filesystem>

#include "scene/scene_loader.hpp"

namespace felt::feltd {

/// Mesh files of a scene resolve inside `scene_dir`, as they do for clients.
inline SceneLoadOptions scene_options(const std::filesystem::path& scene_dir) {
  SceneLoadOptions options;
  options.asset_root = scene_dir;
  return options;
}

}  // namespace felt::feltd
