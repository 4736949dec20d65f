// A served scene's step never exceeds its budget (issue 27, "bounded cost"): the project's cloth
// scenes with their cloth under adaptive_rk at the smallest tolerance a scene may set and a
// small step budget. The work of every step, counted as the integrator's internal steps over all
// its calls (not timed), stays within the budget, and the steps that reach it are reported.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "core/integrate/counting_integrator.hpp"
#include "core/integrate/runge_kutta_integrators.hpp"
#include "scene/scene_loader.hpp"
#include "scene/scene_overrides.hpp"

namespace felt {
namespace {

TEST(ServedStepBudget, NoStepOfAServedClothSceneExceedsItsBudget) {
  constexpr int kBudget = 50;
  for (const std::string file : {"default.json", "flag.json", "cloth_on_ball.json",
                                 "finger_on_hammock.json", "swinging_cloth.json"}) {
    SCOPED_TRACE(file);
    auto document = read_scene_json(std::string(FELT_SCENE_DIR) + "/" + file);
    ASSERT_TRUE(document) << document.error().message;
    ASSERT_TRUE(apply_override(
        *document, R"(bodies.0.integrator={"name": "adaptive_rk", "tolerance": 1e-9})"));
    ASSERT_TRUE(apply_override(*document, "health.step_budget=" + std::to_string(kBudget)));
    auto scene = load_scene(*document);
    ASSERT_TRUE(scene) << scene.error().what();
    World& world = scene->world;
    ClothBody& cloth = world.cloths()[0];
    // the same integrator, counted
    ASSERT_EQ(static_cast<const AdaptiveRungeKutta&>(cloth.integrator()).tolerance(), 1e-9);
    cloth.set_integrator(
        std::make_unique<test::CountingIntegrator>(std::make_unique<AdaptiveRungeKutta>(1e-9)));
    auto& counter = static_cast<test::CountingIntegrator&>(cloth.integrator());
    std::uint64_t over_budget = 0;
    for (int n = 0; n < 20; ++n) {
      const StepReport report = world.step();
      EXPECT_LE(counter.take_work(), kBudget) << "step " << n;
      if (report.flags.has(StepFlag::kOverBudget)) ++over_budget;
    }
    EXPECT_EQ(world.step_counts(0).over_budget_steps, over_budget);
  }
}

}  // namespace
}  // namespace felt
