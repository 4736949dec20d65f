#pragma once
// The second thesis's scenes (scenes/thesis/) and the stages of the soft-solid step, for the
// soft-solid benchmark and the results table.

#include <array>
#include <string>
#include <string_view>

#include "bench_scene.hpp"

namespace felt::bench {

/// The stages of the soft-solid step in the order of thesis 2 Table 7.4 (NF and UI are one
/// stage here; the health check, which the thesis does not have, is left out).
inline constexpr std::array<StepStage, 7> kStages = {
    StepStage::kIntegration, StepStage::kDetection, StepStage::kTriangles, StepStage::kPenetration,
    StepStage::kResolution,  StepStage::kColliders, StepStage::kFinish};

/// The scenes of thesis 2 Table 7.2 and Appendix C that issue 4 measures.
inline constexpr std::array<std::string_view, 4> kThesisScenes = {"three_cubes", "four_bunnies",
                                                                  "cube_on_rings", "two_rings"};

inline Scene load_thesis_scene(std::string_view name) {
  return load_bench_scene("thesis/" + std::string(name) + ".json");
}

}  // namespace felt::bench
