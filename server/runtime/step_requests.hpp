#pragma once
// The steps a paused scene was asked to take (StepScene), in the order asked: each request
// starts where the one before it ends and is answered once the scene has reached its step.
// Owned by the physics thread.

#include <cstdint>
#include <deque>
#include <functional>
#include <string>

#include "runtime/runner_error.hpp"
#include "runtime/scene_status.hpp"

namespace felt {

class StepRequests {
 public:
  bool empty() const { return pending_.empty(); }
  /// `steps` more after the requests before it, from `step` when there are none.
  void add(std::uint64_t step, std::uint32_t steps, Completion<SceneStatus> done);
  /// Answers, with `status`, the requests whose step the scene at `status.step` has reached.
  void answer_reached(const SceneStatus& status);
  /// Answers every request with kCancelled and `why`.
  void cancel_all(const std::string& why);

 private:
  struct Request {
    std::uint64_t target = 0;
    Completion<SceneStatus> done;
  };
  std::deque<Request> pending_;
};

}  // namespace felt
