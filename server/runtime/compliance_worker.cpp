#include "runtime/compliance_worker.hpp"

#include <algorithm>
#include <utility>

namespace felt {

FoundCompliance ComplianceWorker::factor(const Request& request) {
  return {PointCompliance::factor(request.problem),
          PointCompliance::factor(request.problem, kComplianceHorizon), request.time,
          request.problem.held.size()};
}

void ComplianceWorker::request(BodyId id, Real time, ComplianceProblem problem) {
  Request asked{id, time, std::move(problem)};
  if (mode_ == Mode::kInline) {
    keep(id, factor(asked));
    return;
  }
  std::lock_guard lock(mutex_);
  if (std::ranges::find(busy_, id) != busy_.end()) return;  // one at a time per body
  busy_.push_back(id);
  waiting_.push_back(std::move(asked));
  if (!thread_.joinable()) {
    thread_ = std::jthread([this](std::stop_token stop) { serve(stop); });
  }
  wake_.notify_one();
}

bool ComplianceWorker::busy(BodyId id) const {
  std::lock_guard lock(mutex_);
  return std::ranges::find(busy_, id) != busy_.end();
}

std::optional<FoundCompliance> ComplianceWorker::latest(BodyId id) const {
  std::lock_guard lock(mutex_);
  for (const auto& [body, found] : found_) {
    if (body == id) return found;
  }
  return std::nullopt;
}

void ComplianceWorker::keep(BodyId id, FoundCompliance found) {
  std::lock_guard lock(mutex_);
  std::erase(busy_, id);
  for (auto& [body, kept] : found_) {
    if (body == id) {
      kept = std::move(found);
      return;
    }
  }
  found_.emplace_back(id, std::move(found));
}

void ComplianceWorker::serve(std::stop_token stop) {
  while (true) {
    std::optional<Request> next;
    {
      std::unique_lock lock(mutex_);
      if (!wake_.wait(lock, stop, [this] { return !waiting_.empty(); })) return;
      next = std::move(waiting_.front());
      waiting_.pop_front();
    }
    FoundCompliance found = factor(*next);
    keep(next->id, std::move(found));
  }
}

}  // namespace felt
