// health.enabled off (issue 27, item 6): a step costs its integrator alone. Where the check would
// have found nothing it steps exactly as with the check; where it would have rescued, the body
// is left to grow, and only a state gone non-finite is caught: the body starts over from its
// rest shape, at rest, reported unrecoverable, so nothing non-finite ever leaves a step.

#include <gtest/gtest.h>

#include <limits>
#include <utility>
#include <vector>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/solids/solid_fixtures.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

WorldSettings settings(bool health, Real time_step) {
  WorldSettings s{.gravity = Vec3(0, -9.81, 0), .time_step = time_step};
  s.health.enabled = health;
  return s;
}

/// A 10 × 10 cloth of kang's hanging by its top row, after `steps` steps of 5 ms.
std::vector<Vec3> hung_cloth(bool health, int steps) {
  World world(settings(health, 0.005));
  ClothBody body = test::small_grid_body(10, 10, 500, 0.1, "kang");
  const std::vector<Vec3>& rest = body.model().rest_positions;
  for (std::uint32_t p = 0; p < rest.size(); ++p) {
    if (rest[p].y() == rest.front().y()) body.pin(p);
  }
  world.add_body(std::move(body));
  for (int n = 0; n < steps; ++n) EXPECT_EQ(world.step().flags, StepFlags{}) << "step " << n;
  return std::as_const(world).cloths()[0].state().x;
}

TEST(HealthSwitch, OffAHealthyClothStepsExactlyAsWithTheCheck) {
  const std::vector<Vec3> checked = hung_cloth(true, 300);
  EXPECT_EQ(hung_cloth(false, 300), checked);
  EXPECT_NE(checked, hung_cloth(true, 0));  // it moved
}

TEST(HealthSwitch, OffAGrowingClothIsLeftToGrowAndStartsOverFromRestWhenNonFinite) {
  // explicit Euler on an undamped spring at ωh = 5 multiplies the amplitude by √(1 + (ωh)²)
  // = 5.1 a step: after about 220 steps (10¹⁵⁵ m) the spring's squared length overflows
  for (const bool health : {true, false}) {
    WorldSettings s = settings(health, 0.05);
    s.gravity = Vec3::Zero();
    s.health.auto_substeps = false;
    World world(s);
    world.add_body(test::spring_pair(1, 1e4, 1, 0, "explicit_euler"));
    world.cloths()[0].state().x[1].x() = 1.1;
    StepFlags flags;
    int first_stop = -1;
    Real largest = 0;
    for (int n = 0; n < 1000; ++n) {
      const StepFlags step = world.step().flags;
      flags |= step;
      const ClothBody& body = std::as_const(world).cloths()[0];
      ASSERT_TRUE(test::all_finite(body.state())) << "step " << n;
      largest = std::max(largest, body.state().x[1].norm());
      if (!health && step.has(StepFlag::kUnrecoverable) && first_stop < 0) {
        first_stop = n;
        EXPECT_EQ(body.state().x, body.model().rest_positions);
        EXPECT_EQ(body.state().v[1], Vec3::Zero());
      }
    }
    if (health) {
      EXPECT_TRUE(flags.has(StepFlag::kRescued));
      EXPECT_LT(largest, 100);
    } else {
      EXPECT_FALSE(flags.has(StepFlag::kRescued));
      EXPECT_GT(largest, 1e150);  // nobody stopped the growth
      EXPECT_GT(first_stop, 200);
    }
  }
}

World falling_cube(bool health) {
  World world(settings(health, 0.01));
  world.add_body(SolidBody("cube", test::box({2, 2, 2}, 0.5), test::mass_spring(1, 1e3, 1e3, 1)));
  return world;
}

TEST(HealthSwitch, OffASolidStepsExactlyAsWithTheCheckAndANanStartsItOverFromRest) {
  World checked = falling_cube(true);
  World unchecked = falling_cube(false);
  for (int n = 0; n < 100; ++n) {
    ASSERT_EQ(checked.step().flags, StepFlags{});
    ASSERT_EQ(unchecked.step().flags, StepFlags{});
  }
  const SolidBody& body = std::as_const(unchecked).solids().bodies()[0];
  EXPECT_EQ(body.positions(), std::as_const(checked).solids().bodies()[0].positions());

  unchecked.solids().bodies()[0].add_external_force(
      3, Vec3::Constant(std::numeric_limits<Real>::quiet_NaN()));
  EXPECT_TRUE(unchecked.step().flags.has(StepFlag::kUnrecoverable));
  EXPECT_TRUE(test::all_finite(body));
  EXPECT_EQ(body.positions(), body.rest().nodes);
  EXPECT_FALSE(unchecked.step().flags.has(StepFlag::kUnrecoverable));
}

}  // namespace
}  // namespace felt
