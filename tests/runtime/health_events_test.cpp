#include "runtime/health_events.hpp"

#include <gtest/gtest.h>

#include "runner_fixtures.hpp"

namespace felt {
namespace {

StepReport unrecoverable(BodyId body) {
  StepReport report;
  report.flags = {StepFlag::kUnrecoverable};
  report.unrecoverable_bodies = {body};
  return report;
}

TEST(HealthEvents, StepsInTroubleAreToldAtMostOncePerIntervalAndNeverTwice) {
  SceneMembers members;
  auto log = std::make_shared<EventLog>();
  members.join({7, "observer", log});
  HealthEvents health(members);
  const Clock::time_point start{};
  SceneEvent stamp;
  stamp.step = 3;

  // the first is told at once
  for (int i = 0; i < 3; ++i) health.count(unrecoverable(2));
  health.report(start, false, stamp);
  // then the next ones wait for the interval
  for (int i = 0; i < 5; ++i) health.count(unrecoverable(4));
  StepReport rescued;
  rescued.flags = {StepFlag::kRescued};
  health.count(rescued);
  health.report(start + HealthEvents::kInterval / 2, false, stamp);
  ASSERT_EQ(log->events().size(), 2u);  // the first unrecoverable one, the first rescued one
  health.report(start + HealthEvents::kInterval, false, stamp);
  health.report(start + HealthEvents::kInterval, false, stamp);  // nothing new
  health.count(unrecoverable(4));
  health.report(start + HealthEvents::kInterval, true, stamp);  // at once: the scene stops

  const std::vector<SceneEvent> events = log->events();
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[0].kind, SceneEvent::Kind::kUnrecoverableStep);
  EXPECT_EQ(events[0].count, 3u);
  EXPECT_EQ(events[0].body_ids, std::vector<BodyId>{2});
  EXPECT_EQ(events[0].step, 3u);
  EXPECT_EQ(events[1].kind, SceneEvent::Kind::kRescuedStep);
  EXPECT_EQ(events[1].count, 1u);
  EXPECT_EQ(events[2].kind, SceneEvent::Kind::kUnrecoverableStep);
  EXPECT_EQ(events[2].count, 5u);
  EXPECT_EQ(events[2].body_ids, std::vector<BodyId>{4});
  EXPECT_EQ(events[3].count, 1u);
  EXPECT_EQ(health.unrecoverable(), 9u);
  EXPECT_EQ(health.rescued(), 1u);
}

}  // namespace
}  // namespace felt
