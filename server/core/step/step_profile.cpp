#include "core/step/step_profile.hpp"

namespace felt {

std::string_view stage_name(StepStage stage) {
  switch (stage) {
    case StepStage::kIntegration:
      return "integration";
    case StepStage::kStretchLimit:
      return "stretch_limit";
    case StepStage::kDetection:
      return "detection";
    case StepStage::kTriangles:
      return "triangles";
    case StepStage::kPenetration:
      return "penetration";
    case StepStage::kResolution:
      return "resolution";
    case StepStage::kSelfCollision:
      return "self_collision";
    case StepStage::kColliders:
      return "colliders";
    case StepStage::kConstraints:
      return "constraints";
    case StepStage::kFinish:
      return "finish";
    case StepStage::kHealth:
      return "health";
  }
  return "unknown";
}

}  // namespace felt
