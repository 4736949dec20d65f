// Bounded cost (issue 27): an absurd adaptive step, and implicit Euler's and projective
// dynamics' iterations, end within the world's step budget, counted as work (internal steps),
// and are reported; stretch limiting is held to each substep's share of it; a step whose retries
// the budget cannot afford ends as unrecoverable instead of trying them.

#include <gtest/gtest.h>

#include <memory>
#include <utility>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/integrate/counting_integrator.hpp"
#include "core/integrate/implicit_euler.hpp"
#include "core/integrate/projective_dynamics.hpp"
#include "core/integrate/runge_kutta_integrators.hpp"
#include "core/integrate/xpbd_integrator.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

/// A stiff, light 6 × 6 cloth (k = 1e5 N/m, 1 g) under `inner`, its work counted.
ClothBody stiff_light_cloth(std::unique_ptr<Integrator> inner) {
  GridClothSpec spec;
  spec.nx = spec.ny = 6;
  spec.total_mass = 1e-3;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 1e5, 0.01};
  params.spring(SpringKind::kShear) = {true, 2e4, 0};
  ClothBody body("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                 std::make_unique<test::CountingIntegrator>(std::move(inner)));
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) body.pin(p);
  return body;
}

/// The same under adaptive_rk at the smallest tolerance a scene may set, 1e-9 m: its error
/// control asks for thousands of internal steps a step.
ClothBody stiff_light_cloth() {
  return stiff_light_cloth(std::make_unique<AdaptiveRungeKutta>(1e-9));
}

TEST(StepBudget, AnAbsurdAdaptiveStepEndsWithinItsBudgetAndIsReported) {
  constexpr int kBudget = 200;
  World world(WorldSettings{
      .gravity = Vec3(0, -9.81, 0), .time_step = 1e-2, .health = {.step_budget = kBudget}});
  const BodyId id = world.add_body(stiff_light_cloth());
  auto& counter = static_cast<test::CountingIntegrator&>(world.cloths()[0].integrator());
  std::uint64_t over_budget = 0;
  long most = 0;
  for (int n = 0; n < 20; ++n) {
    const StepReport report = world.step();
    const long work = counter.take_work();
    most = std::max(most, work);
    // every attempt of the step, every retry and every internal step together
    EXPECT_LE(work, kBudget) << "step " << n;
    if (report.flags.has(StepFlag::kOverBudget)) {
      ++over_budget;
      EXPECT_EQ(report.over_budget_bodies, std::vector<BodyId>{id});
    }
    for (const Vec3& x : world.cloths()[0].state().x) ASSERT_TRUE(x.allFinite());
  }
  // the error control wanted more than the budget: it got most of it (the last internal steps
  // of a capped call are longer, and a retry gets only what is left)
  EXPECT_GT(most, kBudget / 2);
  EXPECT_GT(over_budget, 0u);
  EXPECT_EQ(world.step_counts(id).over_budget_steps, over_budget);
}

TEST(StepBudget, WithoutTheBudgetTheSameStepTakesFarMore) {
  // the same cloth with the largest budget a scene may set: the work the budget saves
  World world(WorldSettings{
      .gravity = Vec3(0, -9.81, 0), .time_step = 1e-2, .health = {.step_budget = 100000}});
  world.add_body(stiff_light_cloth());
  auto& counter = static_cast<test::CountingIntegrator&>(world.cloths()[0].integrator());
  world.step();
  EXPECT_GT(counter.take_work(), 2000);
}

TEST(StepBudget, RetriesTheBudgetCannotAffordAreNotTried) {
  // explicit Euler on an undamped spring: no step is stable, so its automatic substeps ask for
  // more than any budget; the step takes the budget's worth and reports it
  World world(
      WorldSettings{.gravity = Vec3::Zero(), .time_step = 1e-2, .health = {.step_budget = 64}});
  const BodyId id = world.add_body(test::spring_pair(1, 1e4, 1, 0, "explicit_euler"));
  world.cloths()[0].state().x[1].x() = 1.1;
  for (int n = 0; n < 10; ++n) {
    const StepReport report = world.step();
    EXPECT_TRUE(report.flags.has(StepFlag::kOverBudget)) << "step " << n;
    EXPECT_LE(world.step_counts(id).substeps, 64);
  }
}

TEST(StepBudget, IterationsOfTheImplicitSchemesCountAndStopAtTheBudget) {
  // implicit Euler's conjugate gradients to 1e-12 on the stiff cloth, and 100 iterations of
  // projective dynamics: each iteration counts as an internal step, and a step stops at 4
  constexpr int kBudget = 4;
  const auto implicit = [] {
    auto euler = std::make_unique<ImplicitEuler>();
    euler->solver().tolerance = 1e-12;
    return euler;
  };
  for (int scheme = 0; scheme < 2; ++scheme) {
    const auto body = [&] {
      return stiff_light_cloth(scheme == 0 ? std::unique_ptr<Integrator>(implicit())
                                           : std::make_unique<ProjectiveDynamics>(100));
    };
    // what a step takes unbudgeted
    World free(WorldSettings{
        .gravity = Vec3(0, -9.81, 0), .time_step = 1e-2, .health = {.step_budget = 100000}});
    free.add_body(body());
    free.step();
    EXPECT_GT(static_cast<test::CountingIntegrator&>(free.cloths()[0].integrator()).take_work(),
              3 * kBudget)
        << "scheme " << scheme;

    World world(WorldSettings{
        .gravity = Vec3(0, -9.81, 0), .time_step = 1e-2, .health = {.step_budget = kBudget}});
    const BodyId id = world.add_body(body());
    auto& counter = static_cast<test::CountingIntegrator&>(world.cloths()[0].integrator());
    for (int n = 0; n < 10; ++n) {
      const StepReport report = world.step();
      EXPECT_LE(counter.take_work(), kBudget) << "scheme " << scheme << " step " << n;
      EXPECT_TRUE(report.flags.has(StepFlag::kOverBudget)) << "scheme " << scheme << " step " << n;
      for (const Vec3& x : world.cloths()[0].state().x) ASSERT_TRUE(x.allFinite());
    }
    EXPECT_EQ(world.step_counts(id).over_budget_steps, 10u);
  }
}

TEST(StepBudget, XpbdsSubstepsAreAffordedWhole) {
  // 50 xpbd substeps a call, which no limit cuts, and a body's own max_step set after loading
  // (SetBodyParameters) asking for 10 calls a step: the budget of 100 affords two
  World world(WorldSettings{
      .gravity = Vec3(0, -9.81, 0), .time_step = 1e-2, .health = {.step_budget = 100}});
  const BodyId id = world.add_body(stiff_light_cloth(std::make_unique<XpbdIntegrator>(50)));
  world.cloths()[0].set_max_step(1e-3);
  auto& counter = static_cast<test::CountingIntegrator&>(world.cloths()[0].integrator());
  for (int n = 0; n < 10; ++n) {
    EXPECT_TRUE(world.step().flags.has(StepFlag::kOverBudget)) << "step " << n;
    EXPECT_LE(counter.take_work(), 100) << "step " << n;
    EXPECT_EQ(world.step_counts(id).substeps, 2);
  }
}

TEST(StepBudget, StretchLimitingIsHeldToTheSubstepsShareAndReportedWhenCut) {
  // a cloth limited to 1 % strain with 100 sweeps and 20 projection steps a pass, set 20 %
  // stretched, in 10 substeps a step (its own max_step): a budget of 20 leaves each substep's
  // limiting 2 of each, too few to bring it back, and the step is reported; with a
  // budget that affords them all, the same step is not
  const auto reported = [](int budget) {
    World world(WorldSettings{.gravity = Vec3(0, -9.81, 0),
                              .time_step = 1e-2,
                              .health = {.auto_substeps = false, .step_budget = budget}});
    GridClothSpec spec;
    spec.nx = spec.ny = 8;
    spec.total_mass = 10;
    ClothParams params;
    params.spring(SpringKind::kStructural) = {true, 100, 0.1};
    params.stretch = {
        .enabled = true, .max_strain = 0.01, .iterations = 100, .projection_iterations = 20};
    ClothBody body("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                   make_integrator("symplectic_euler"));
    for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) body.pin(p);
    body.set_max_step(1e-3);
    for (Vec3& x : body.state().x) x *= 1.2;
    world.add_body(std::move(body));
    return world.step().flags.has(StepFlag::kOverBudget);
  };
  EXPECT_TRUE(reported(20));
  EXPECT_FALSE(reported(1'000'000));
}

}  // namespace
}  // namespace felt
