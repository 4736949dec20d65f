#include "runtime/health_events.hpp"

#include <algorithm>
#include <utility>

namespace felt {

void HealthEvents::count(const StepReport& report) {
  if (report.flags & kStepRescued) {
    ++rescued_.total;
    // every body rescued since the last event, once
    for (BodyId id : report.rescued_bodies) {
      const auto at = std::lower_bound(rescued_.bodies.begin(), rescued_.bodies.end(), id);
      if (at == rescued_.bodies.end() || *at != id) rescued_.bodies.insert(at, id);
    }
  }
  if (report.flags & kStepUnrecoverable) {
    ++unrecoverable_.total;
    unrecoverable_.bodies = report.unrecoverable_bodies;
  }
}

void HealthEvents::report(Clock::time_point now, bool at_once, const SceneEvent& stamp) {
  for (auto [kind, troubled] : {std::pair{SceneEvent::Kind::kUnrecoverableStep, &unrecoverable_},
                                std::pair{SceneEvent::Kind::kRescuedStep, &rescued_}}) {
    if (troubled->total == troubled->reported) continue;
    if (!at_once && troubled->last_event && now - *troubled->last_event < kInterval) continue;
    SceneEvent e = stamp;
    e.kind = kind;
    e.count = troubled->total - troubled->reported;
    e.body_ids = std::move(troubled->bodies);
    members_.broadcast(std::move(e));
    troubled->reported = troubled->total;
    troubled->bodies.clear();
    troubled->last_event = now;
  }
}

}  // namespace felt
