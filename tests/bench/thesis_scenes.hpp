#pragma once
// The second thesis's scenes (scenes/thesis/) and the stages of the soft-solid step, for the
// soft-solid benchmark and the results table.

#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scene/scene_loader.hpp"

namespace felt::bench {

/// A stage of the soft-solid step: its name and where SolidStageTimes keeps its seconds.
struct StageColumn {
  std::string_view name;
  Real SolidStageTimes::*seconds;
};

/// The stages in the order of thesis 2 Table 7.4 (NF and UI are one stage here).
inline constexpr std::array<StageColumn, 7> kStages = {{
    {"integration", &SolidStageTimes::integration},
    {"detection", &SolidStageTimes::detection},
    {"triangles", &SolidStageTimes::triangles},
    {"penetration", &SolidStageTimes::penetration},
    {"resolution", &SolidStageTimes::resolution},
    {"colliders", &SolidStageTimes::colliders},
    {"finish", &SolidStageTimes::finish},
}};

/// The scenes of thesis 2 Table 7.2 and Appendix C that issue 4 measures.
inline constexpr std::array<std::string_view, 4> kThesisScenes = {"three_cubes", "four_bunnies",
                                                                  "cube_on_rings", "two_rings"};

inline Scene load_thesis_scene(std::string_view name) {
  SceneLoadOptions options;
  options.asset_root = FELT_SCENE_DIR;
  const std::filesystem::path file =
      std::filesystem::path(FELT_SCENE_DIR) / "thesis" / (std::string(name) + ".json");
  auto scene = load_scene_file(file, options);
  if (!scene) throw std::runtime_error(file.string() + ": " + scene.error().what());
  return std::move(*scene);
}

}  // namespace felt::bench
