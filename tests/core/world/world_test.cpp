// The world step on whole cloths: statics, pins, numerical health and determinism.

#include <gtest/gtest.h>

#include <functional>

#include "core/cloth/cloth_grid.hpp"
#include "core/world/state_hash.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

GridClothSpec small_grid() {
  GridClothSpec spec;
  spec.width = 0.5;
  spec.height = 0.5;
  spec.nx = 8;
  spec.ny = 8;
  spec.total_mass = 0.2;
  spec.center = Vec3(0, 1, 0);
  return spec;
}

ClothParams params(Real structural = 100, Real drag = 0.02) {
  ClothParams p;
  p.spring(SpringKind::kStructural) = {true, structural, 0.05};
  p.spring(SpringKind::kShear) = {true, structural / 4, 0.02};
  p.spring(SpringKind::kBend) = {true, structural / 40, 0.005};
  p.drag = drag;
  return p;
}

ClothBody make_cloth(const GridClothSpec& spec, const ClothParams& p, std::string_view integrator,
                     GridPinPreset pins) {
  ClothBody body("cloth", std::make_shared<const ClothModel>(make_grid_cloth(spec)), p,
                 make_integrator(integrator));
  for (std::uint32_t i : grid_pin_indices(spec, pins)) body.pin(i);
  return body;
}

TEST(World, HangingClothPinsCarryItsWholeWeight) {
  // at rest the spring forces on the pinned particles balance the weight of all free ones
  const GridClothSpec spec = small_grid();
  World world(WorldSettings{Vec3(0, -9.81, 0), 1e-3, 100, 6});
  world.add_body(make_cloth(spec, params(100, 0.05), "symplectic_euler", GridPinPreset::kTopRow));
  for (int n = 0; n < 20000; ++n) world.step();
  const ClothBody& body = world.cloths()[0];
  ASSERT_LT(body.kinetic_energy(), 1e-12);

  std::vector<Vec3> f(body.model().particle_count());
  body.compute_forces(body.state().x, body.state().v, world.time(), f);
  Vec3 on_pins = Vec3::Zero();
  Real free_mass = 0;
  for (std::uint32_t p = 0; p < f.size(); ++p) {
    if (body.is_pinned(p)) {
      on_pins += f[p] - body.model().mass[p] * world.settings().gravity;  // springs only
    } else {
      free_mass += body.model().mass[p];
    }
  }
  const Vec3 free_weight = free_mass * world.settings().gravity;
  EXPECT_NEAR((on_pins - free_weight).norm() / free_weight.norm(), 0, 1e-6);
}

TEST(World, PinnedParticlesNeverMove) {
  const GridClothSpec spec = small_grid();
  World world;
  world.add_body(make_cloth(spec, params(), "explicit_euler", GridPinPreset::kFourCorners));
  const ClothBody& body = world.cloths()[0];
  const auto pins = grid_pin_indices(spec, GridPinPreset::kFourCorners);
  std::vector<Vec3> start;
  for (std::uint32_t p : pins) start.push_back(body.state().x[p]);
  for (int n = 0; n < 2000; ++n) {
    world.step();
    for (std::size_t k = 0; k < pins.size(); ++k) {
      ASSERT_EQ(body.state().x[pins[k]], start[k]) << "step " << n;
    }
  }
}

TEST(World, ExplodingClothIsRolledBackAndNeverNonFinite) {
  // explicit Euler with springs this stiff is unstable at any of the substeps tried
  World world(WorldSettings{Vec3(0, -9.81, 0), 2e-3, 50, 3});
  world.add_body(make_cloth(small_grid(), params(10, 0), "symplectic_euler",
                            GridPinPreset::kTopCorners));  // a calm body beside it
  world.add_body(
      make_cloth(small_grid(), params(1e7, 0), "explicit_euler", GridPinPreset::kTopCorners));
  StepFlags flags;
  for (int n = 0; n < 300; ++n) {
    const StepReport report = world.step();
    flags |= report.flags;
    if (report.flags.has(StepFlag::kUnrecoverable)) {
      // the report names the body that failed, not its calm neighbour
      ASSERT_EQ(report.unrecoverable_bodies, std::vector<BodyId>{1}) << "step " << n;
    }
    for (const Vec3& x : world.cloths()[1].state().x) ASSERT_TRUE(x.allFinite()) << "step " << n;
    for (const Vec3& v : world.cloths()[1].state().v) ASSERT_LE(v.norm(), 50.0) << "step " << n;
  }
  EXPECT_TRUE(flags.has(StepFlag::kUnrecoverable));
}

TEST(World, SubstepsRescueAStepThatIsTooLongForTheSprings) {
  // symplectic Euler is stable below h = 2/ω; one step of 8 ms is far beyond it for this cloth,
  // 64 substeps of 0.125 ms are not. The speed limit catches the blow-up within a step. (With
  // automatic substeps the step would start with enough of them: stable_substeps_test.cpp.)
  WorldSettings settings{Vec3(0, -9.81, 0), 8e-3, 5, 6};
  settings.health.auto_substeps = false;
  World world(settings);
  world.add_body(
      make_cloth(small_grid(), params(3e4, 0.05), "symplectic_euler", GridPinPreset::kTopRow));
  StepFlags flags;
  int most_substeps = 1;
  for (int n = 0; n < 100; ++n) {
    const StepReport report = world.step();
    flags |= report.flags;
    most_substeps = std::max(most_substeps, report.max_substeps);
  }
  EXPECT_TRUE(flags.has(StepFlag::kRescued));
  EXPECT_FALSE(flags.has(StepFlag::kUnrecoverable));
  EXPECT_GT(most_substeps, 1);
}

TEST(World, ExplicitEulerStartsFromRestWithoutARescue) {
  // its first step from rest moves no particle yet gains ½ m (g h)² each: the health check must
  // count that as work done by gravity, not as an explosion
  World world(WorldSettings{Vec3(0, -9.81, 0), 1e-4, 100, 6});
  world.add_body(make_cloth(small_grid(), params(), "explicit_euler", GridPinPreset::kTopCorners));
  for (int n = 0; n < 100; ++n) ASSERT_EQ(world.step().flags, StepFlags{}) << "step " << n;
  EXPECT_LT(world.cloths()[0].state().x[63].y(), 1 - 0.25 - 1e-4);  // the free corner fell
}

TEST(World, SameInputsGiveBitIdenticalStates) {
  auto run = [](Real stiffness) {
    World world;
    world.add_body(make_cloth(small_grid(), params(stiffness), "symplectic_euler",
                              GridPinPreset::kTopCorners));
    for (int n = 0; n < 500; ++n) world.step();
    return state_hash(world);
  };
  EXPECT_EQ(run(100), run(100));
  EXPECT_NE(run(100), run(101));  // the hash does see the state
}

TEST(World, AStepYieldsBetweenItsPhasesAndYieldingChangesNothing) {
  auto run = [](bool yielding, int& yields) {
    World world;
    for (Real x : {-1.0, 1.0}) {
      GridClothSpec spec = small_grid();
      spec.center = Vec3(x, 1, 0);
      world.add_body(make_cloth(spec, params(), "symplectic_euler", GridPinPreset::kTopCorners));
    }
    const std::function<void()> count = [&yields] { ++yields; };
    for (int n = 0; n < 200; ++n) world.step(yielding ? count : std::function<void()>{});
    return state_hash(world);
  };
  int yields = 0;
  const auto yielded = run(true, yields);
  EXPECT_EQ(yields, 200 * 2 * 2);  // after each cloth's integration and after its constraints
  int none = 0;
  EXPECT_EQ(yielded, run(false, none));
  EXPECT_EQ(none, 0);
}

TEST(World, ARescuedStepYieldsInEverySubstep) {
  // the longest steps are the rescued ones: each of their substeps is a phase of its own
  WorldSettings settings{Vec3(0, -9.81, 0), 8e-3, 5, 6};
  settings.health.auto_substeps = false;  // a rescue from one substep
  World world(settings);
  world.add_body(
      make_cloth(small_grid(), params(3e4, 0.05), "symplectic_euler", GridPinPreset::kTopRow));
  for (int n = 0; n < 100; ++n) {
    int yields = 0;
    const StepReport report = world.step([&yields] { ++yields; });
    if (report.max_substeps == 1) continue;
    // tries of 1, 2, 4 ... m substeps, each substep yielding twice
    EXPECT_EQ(yields, 2 * (2 * report.max_substeps - 1)) << "step " << n;
    return;
  }
  FAIL() << "no step needed substeps";
}

TEST(World, AStepReportsTheTimeOfEachStageOfEachSystem) {
  World world;
  world.add_body(
      make_cloth(small_grid(), params(), "symplectic_euler", GridPinPreset::kTopCorners));
  const StepReport report = world.step();
  for (StepStage stage : {StepStage::kIntegration, StepStage::kStretchLimit, StepStage::kColliders,
                          StepStage::kConstraints, StepStage::kHealth}) {
    EXPECT_GT(report.cloth_profile[stage], 0) << stage_name(stage);
  }
  EXPECT_EQ(report.cloth_profile[StepStage::kSelfCollision], 0);            // off for this cloth
  EXPECT_EQ(report.cloth_profile[StepStage::kDetection], 0);                // a solid's stage
  for (Real seconds : report.solid_profile.seconds) EXPECT_EQ(seconds, 0);  // no solids
}

TEST(World, ClockIsStepCountTimesStep) {
  World world(WorldSettings{Vec3::Zero(), 1e-3, 100, 6});
  for (int n = 0; n < 12345; ++n) world.step();
  EXPECT_EQ(world.step_count(), 12345u);
  EXPECT_DOUBLE_EQ(world.time(), 12.345);
}

}  // namespace
}  // namespace felt
