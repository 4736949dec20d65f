// The scene every latency figure is measured on (scenes/service_bench.json: a 100 x 100 cloth
// hung from its top row, symplectic Euler at 2 ms, stretch limit 0.1) held to what a hanging,
// damped cloth must do: come to rest, within its stretch limit after every step.

#include <gtest/gtest.h>

#include "core/cloth/stretch_limiter.hpp"
#include "scene/scene_loader.hpp"

namespace felt {
namespace {

TEST(ServedBenchScene, ComesToRestWithinItsStretchLimit) {
  auto scene = load_scene_file(std::string(FELT_SCENE_DIR) + "/service_bench.json");
  ASSERT_TRUE(scene) << scene.error().message;
  World& world = scene->world;
  ASSERT_EQ(world.cloths().size(), 1u);
  const ClothBody& sheet = world.cloths()[0];
  const Real limit = sheet.params().stretch.max_strain;
  ASSERT_TRUE(sheet.params().stretch.enabled);
  Real worst = 0;
  while (world.time() < 5 - 1e-9) {
    ASSERT_EQ(world.step().flags, StepFlags{}) << "t = " << world.time();
    worst = std::max(worst, sheet.max_strain());
  }
  EXPECT_LE(worst, limit * (1 + kStretchTolerance));
  EXPECT_LT(sheet.kinetic_energy(), 1e-6);
}

}  // namespace
}  // namespace felt
