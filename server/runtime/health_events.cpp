#include "runtime/health_events.hpp"

#include <algorithm>
#include <utility>

namespace felt {

namespace {

/// Adds `ids` to the sorted `bodies`, each once.
void add_once(std::vector<BodyId>& bodies, const std::vector<BodyId>& ids) {
  for (BodyId id : ids) {
    const auto at = std::lower_bound(bodies.begin(), bodies.end(), id);
    if (at == bodies.end() || *at != id) bodies.insert(at, id);
  }
}

}  // namespace

void HealthEvents::count(const StepReport& report) {
  if (report.flags.has(StepFlag::kRescued)) {
    ++rescued_.total;
    add_once(rescued_.bodies, report.rescued_bodies);  // every body since the last event
  }
  if (report.flags.has(StepFlag::kOverBudget)) {
    ++over_budget_.total;
    add_once(over_budget_.bodies, report.over_budget_bodies);
  }
  if (report.flags.has(StepFlag::kUnrecoverable)) {
    ++unrecoverable_.total;
    unrecoverable_.bodies = report.unrecoverable_bodies;
  }
}

void HealthEvents::report(Clock::time_point now, bool at_once, const SceneEvent& stamp) {
  for (auto [kind, troubled] : {std::pair{SceneEvent::Kind::kUnrecoverableStep, &unrecoverable_},
                                std::pair{SceneEvent::Kind::kRescuedStep, &rescued_},
                                std::pair{SceneEvent::Kind::kOverBudgetStep, &over_budget_}}) {
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
