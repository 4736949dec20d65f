#pragma once
// Things that happen in a scene that the clients in it must hear about, beside the frames.

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/body_catalog.hpp"

namespace felt {

struct SceneEvent {
  enum class Kind : std::uint8_t {
    /// steps in which some body could not be rescued: it was rolled back to where it was before
    /// the step and brought to rest (core/world/world.hpp). Coalesced, so an exploding scene
    /// reports
    /// at most twice a second rather than every step.
    kUnrecoverableStep,
    /// steps some body took only with substeps after its step failed; coalesced the same way
    kRescuedStep,
    /// steps in which some body reached its step budget or an integrator's cap; coalesced the
    /// same way
    kOverBudgetStep,
    kBodyAdded,
    kBodyRemoved,
    kBodyChanged,
    kPaused,
    kResumed,
    kReset,
    kStateRestored,
    kTimeScale,
    kDestroyed,
    kClientJoined,
    kClientLeft,
  };
  Kind kind = Kind::kUnrecoverableStep;
  std::uint64_t sequence = 0;  ///< 1, 2, ... per scene
  std::uint64_t step = 0;      ///< the scene's step count when it was reported
  double sim_time = 0;
  /// kUnrecoverableStep, kRescuedStep, kOverBudgetStep: such steps since the last one
  std::uint64_t count = 0;
  std::vector<BodyId> body_ids;  ///< the bodies concerned
  std::vector<BodyInfo> bodies;  ///< kBodyAdded: the new body; kReset: every body now
  ClientId client = 0;           ///< whose request caused it (0: the server)
  std::string client_name;
  double time_scale = 1;
};

}  // namespace felt
