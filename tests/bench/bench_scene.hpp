#pragma once
// A scene of the project's scenes/ directory, loaded as feltd loads it, for the benchmarks that
// measure what a served scene costs.

#include <filesystem>
#include <stdexcept>
#include <string_view>

#include "scene/scene_loader.hpp"

namespace felt::bench {

/// scenes/`relative` (meshes resolve inside scenes/); throws with the loader's message.
inline Scene load_bench_scene(std::string_view relative) {
  SceneLoadOptions options;
  options.asset_root = FELT_SCENE_DIR;
  const std::filesystem::path file = std::filesystem::path(FELT_SCENE_DIR) / relative;
  auto scene = load_scene_file(file, options);
  if (!scene) throw std::runtime_error(file.string() + ": " + scene.error().what());
  return std::move(*scene);
}

}  // namespace felt::bench
