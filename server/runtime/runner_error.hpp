#pragma once
// Why a scene could not do what a request asked.

#include <expected>
#include <functional>
#include <string>

#include "scene/scene_error.hpp"

namespace felt {

struct RunnerError {
  enum class Code : std::uint8_t {
    kBadRequest,     ///< a value out of range, or state that does not fit the scene
    kUnknownId,      ///< no such body or saved state
    kWrongState,     ///< not now (stepping a running scene, resetting one that cannot be)
    kLimitExceeded,  ///< the scene's body or particle limit
    kCancelled,      ///< the scene stopped before the request ran
    kBadScene,       ///< the scene's source no longer loads (reset)
  };
  Code code = Code::kBadRequest;
  std::string message;
  SceneLimit exceeded = SceneLimit::kNone;  ///< with kLimitExceeded: which of the scene's limits
};

/// Called once, from the physics thread (or the thread that stopped the scene), with the
/// outcome of a request. Must not block.
template <class T>
using Completion = std::function<void(std::expected<T, RunnerError>)>;

}  // namespace felt
