#pragma once
// The named stages of a physics step, shared by the cloth and the solid systems, and the wall
// time each took: the per-step profile that `feltd run --stats-json` and GetStats report (the
// second thesis's Table 7.4 for solids).

#include <array>
#include <chrono>
#include <cstdint>
#include <string_view>

#include "core/math/types.hpp"

namespace felt {

enum class StepStage : std::uint8_t {
  kIntegration,    ///< forces and the integrator (solids: SolidBody::advance)
  kStretchLimit,   ///< cloth: stretch limiting
  kDetection,      ///< solids: nodes hashed against tetrahedra (Table 7.4 CD)
  kTriangles,      ///< solids: the colliding surface triangles
  kPenetration,    ///< solids: consistent penetration vectors
  kResolution,     ///< solids: the contact surface
  kSelfCollision,  ///< cloth: the cloth pushed off its own triangles
  kColliders,      ///< the static colliders and the haptic proxies' spheres
  kConstraints,    ///< cloth: particles held in planes and on lines
  kFinish,         ///< solids: velocities from the positions (Table 7.4 FI)
  kHealth,         ///< the check of the state after a step or substep
};
inline constexpr std::size_t kStepStageCount = 11;

/// The stage's name in statistics: "integration", "stretch_limit", ...
std::string_view stage_name(StepStage stage);

/// Seconds spent in each stage during one step, summed over its substeps and any redone
/// attempts.
struct StepProfile {
  std::array<Real, kStepStageCount> seconds{};

  Real& operator[](StepStage stage) { return seconds[static_cast<std::size_t>(stage)]; }
  Real operator[](StepStage stage) const { return seconds[static_cast<std::size_t>(stage)]; }
};

/// Runs `stage_work()` and adds the seconds it took to `profile[stage]`.
template <class Work>
decltype(auto) timed(StepProfile& profile, StepStage stage, Work&& stage_work) {
  const auto start = std::chrono::steady_clock::now();
  struct AddOnExit {
    StepProfile& profile;
    StepStage stage;
    std::chrono::steady_clock::time_point start;
    ~AddOnExit() {
      profile[stage] +=
          std::chrono::duration<Real>(std::chrono::steady_clock::now() - start).count();
    }
  } add{profile, stage, start};
  return stage_work();
}

}  // namespace felt
