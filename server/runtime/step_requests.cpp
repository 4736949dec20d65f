#include "runtime/step_requests.hpp"

namespace felt {

void StepRequests::add(std::uint64_t step, std::uint32_t steps, Completion<SceneStatus> done) {
  const std::uint64_t from = pending_.empty() ? step : pending_.back().target;
  pending_.push_back({from + steps, std::move(done)});
}

void StepRequests::answer_reached(const SceneStatus& status) {
  while (!pending_.empty() && pending_.front().target <= status.step) {
    pending_.front().done(status);
    pending_.pop_front();
  }
}

void StepRequests::cancel_all(const std::string& why) {
  std::deque<Request> cancelled;
  cancelled.swap(pending_);
  for (Request& request : cancelled) {
    request.done(std::unexpected(RunnerError{RunnerError::Code::kCancelled, why}));
  }
}

}  // namespace felt
