// Stretch limiting of a cloth that colliders press (issue 30): the haptic proxies of the served
// scene's clients push its taut cloth past the limit again after every pass, so the limiter stops
// its sweeps once they stall and does not try its global solve. Checked against the bound, the
// colliders' surfaces and the energy.

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/cloth/hanging_cloth.hpp"
#include "core/cloth/stretch_limiter.hpp"
#include "core/collision/collider.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

/// Four 5 cm balls in a row, pressed 2.5 cm into the middle of the hanging cloth (its particles
/// 5 cm apart), as the service benchmark's clients hold their 2 cm proxies 1 cm into its 2 cm
/// mesh.
std::vector<Collider> pressing_balls() {
  return test::balls_in_a_row(4, Vec3(0, 1.0, 0.025), 0.05, 0.05);
}

/// The served scene's cloth at 40 x 40 under kang, hung for a second, then pressed.
struct PressedCloth {
  World world = test::hanging_cloth(40, "kang", 2e-3, true);
  /// after any step from half a second into the pressing: the first steps meet balls that
  /// appeared inside the cloth
  Real largest_strain = 0;
  Real closest = 1e300;  ///< the least distance of a particle from a ball's centre

  explicit PressedCloth(Real seconds) {
    while (world.time() < 1) world.step();
    const std::vector<Collider> balls = pressing_balls();
    const ClothBody& cloth = world.cloths()[0];
    while (world.time() < 1 + seconds) {
      world.set_moving_colliders(balls);
      EXPECT_EQ(world.step().flags, StepFlags{}) << world.time();
      if (world.time() > 1.5) largest_strain = std::max(largest_strain, cloth.max_strain());
      for (const Vec3& x : cloth.state().x) {
        for (const Collider& ball : balls) closest = std::min(closest, (x - ball.center).norm());
      }
    }
  }
};

TEST(PressedCloth, HoldsItsLimitOutsideTheBallsAndComesToRest) {
  const PressedCloth pressed(2);
  // the stalled sweeps still hold the limit once the cloth has given way to the balls (0.1008)
  EXPECT_LE(pressed.largest_strain, 0.1 * (1 + kStretchTolerance));
  EXPECT_GT(pressed.closest, 0.05);  // the colliders have the last word
  EXPECT_LT(pressed.world.cloths()[0].kinetic_energy(), 1e-5);
}

TEST(StretchLimiter, PushedByCollidersItStopsStalledSweepsAndLeavesOutTheGlobalSolve) {
  // a cloth pinned at two corners and stretched 40 % at random, where each sweep takes little
  // off the excess: without colliders ten sweeps run and the global solve follows them
  const test::StretchedGrid stretched = test::badly_stretched_grid();
  StretchLimit limit;
  limit.enabled = true;
  const auto pass = [&](bool pushed) {
    ParticleState state = stretched.state;
    StretchLimiter limiter;
    limiter.set_pushed_by_colliders(pushed);
    return limiter.apply(stretched.model, stretched.inv_mass, limit, 1e-3, state);
  };
  const StretchLimitStats free = pass(false);
  const StretchLimitStats pushed = pass(true);
  EXPECT_EQ(free.position_sweeps, limit.iterations);
  EXPECT_GT(free.position_projections, 0);
  EXPECT_LT(pushed.position_sweeps, limit.iterations);
  EXPECT_EQ(pushed.position_projections, 0);
}

}  // namespace
}  // namespace felt
