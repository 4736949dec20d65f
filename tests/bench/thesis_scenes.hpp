#pragma once
// The second thesis's scenes (scenes/thesis/) and the stages of the soft-solid step, for the
// soft-solid benchmark and the results table.

#include <array>
#include <string>
#include <string_view>

#include "bench_scene.hpp"

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
  return load_bench_scene("thesis/" + std::string(name) + ".json");
}

}  // namespace felt::bench
