#pragma once
// Where a scene's point compliance is factored (issue 26: the local models' surface stiffness).
// Two sparse factorizations per body take 33 ms for the default curtain's 400 particles; on the
// physics thread, every kComplianceRefresh of the scene's time, they held its publication back
// by that long, and a remote device went as long without a model (its extrapolated surface
// centimetres off). Threaded, the physics thread copies the problem out of the body
// (ComplianceProblem) and a thread of the worker's own factors it, while the snapshots keep the
// last compliance found; the simulated runs of the remote-haptics study factor inline instead,
// on the caller's thread, so that a run repeats bit for bit.

#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <stop_token>
#include <thread>
#include <vector>

#include "core/math/point_compliance.hpp"
#include "core/world/world.hpp"

namespace felt {

/// s: how long a push is held for FoundCompliance::prompt: the shortest round trip at which a
/// local model's surface gives under the device's push before the server shows it
/// (runtime/local_model_stiffness); a point whose give over it is far from its static give is
/// answering by its inertia.
inline constexpr Real kComplianceHorizon = 0.05;

/// A body's point compliance as found from its state at simulated time `time`.
struct FoundCompliance {
  PointCompliance at_rest;
  PointCompliance prompt;  ///< over kComplianceHorizon
  Real time = 0;
  std::size_t nodes = 0;  ///< of the body then
};

class ComplianceWorker {
 public:
  enum class Mode {
    kInline,  ///< request() factors before it returns
    kThread,  ///< a thread of the worker's own factors, one request at a time
  };

  explicit ComplianceWorker(Mode mode) : mode_(mode) {}
  ComplianceWorker(const ComplianceWorker&) = delete;
  ComplianceWorker& operator=(const ComplianceWorker&) = delete;

  /// Asks for body `id`'s compliance from `problem`, its state at simulated time `time`. The
  /// thread starts at the first request and takes the nice of the thread that makes it.
  void request(BodyId id, Real time, ComplianceProblem problem);
  /// Whether a request for body `id` waits or is being factored.
  bool busy(BodyId id) const;
  /// The compliance last found for body `id`, if any.
  std::optional<FoundCompliance> latest(BodyId id) const;

 private:
  struct Request {
    BodyId id;
    Real time;
    ComplianceProblem problem;
  };

  void serve(std::stop_token stop);
  static FoundCompliance factor(const Request& request);
  void keep(BodyId id, FoundCompliance found);

  Mode mode_;
  mutable std::mutex mutex_;
  std::condition_variable_any wake_;
  std::deque<Request> waiting_;
  std::vector<BodyId> busy_;  ///< waiting or being factored
  std::vector<std::pair<BodyId, FoundCompliance>> found_;
  /// last: stopped (waking its wait) and joined before the rest goes
  std::jthread thread_;
};

}  // namespace felt
