// Plane and line constraints (thesis 1 §5) against the analytic motion of a bead.

#include "core/cloth/particle_constraint.hpp"

#include <gtest/gtest.h>

#include "core/cloth/cloth_grid.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

ClothBody bead(std::string_view integrator) {
  auto model = std::make_shared<ClothModel>();
  model->rest_positions = {Vec3(0, 1, 0)};
  model->uv = {Vec2::Zero()};
  model->mass = {0.1};
  return ClothBody("bead", model, ClothParams{}, make_integrator(integrator));
}

TEST(ParticleConstraint, BeadOnAnInclinedWireFallsWithTheProjectedGravity) {
  // on a line of direction d the bead accelerates at (g·d) d: x = x0 + ½ (g·d) d t²
  const Vec3 g(0, -9.81, 0);
  const Vec3 d = Vec3(1, -1, 0).normalized();
  World world(WorldSettings{g, 1e-3, 100, 6});
  world.add_body(bead("velocity_verlet"));
  world.cloths()[0].constrain(ParticleConstraint::Kind::kLine, 0, d);
  for (int n = 1; n <= 500; ++n) {
    world.step();
    const Real t = n * 1e-3;
    const Vec3 expected = Vec3(0, 1, 0) + 0.5 * g.dot(d) * d * t * t;
    ASSERT_LT((world.cloths()[0].state().x[0] - expected).norm(), 1e-12) << n;
    ASSERT_LT((world.cloths()[0].state().v[0] - g.dot(d) * d * t).norm(), 1e-12) << n;
  }
}

TEST(ParticleConstraint, BeadOnATiltedPlaneSlidesDownItsSlope) {
  const Vec3 g(0, -9.81, 0);
  const Vec3 n = Vec3(0, 1, 1).normalized();  // a 45° slope facing +y +z
  World world(WorldSettings{g, 1e-3, 100, 6});
  world.add_body(bead("velocity_verlet"));
  world.cloths()[0].constrain(ParticleConstraint::Kind::kPlane, 0, n);
  for (int k = 0; k < 300; ++k) world.step();
  const Real t = 0.3;
  const Vec3 along = g - g.dot(n) * n;
  EXPECT_LT((world.cloths()[0].state().x[0] - (Vec3(0, 1, 0) + 0.5 * along * t * t)).norm(), 1e-12);
}

TEST(ParticleConstraint, CurtainRingsStayOnTheirRailUnderStretchLimiting) {
  // the top row slides on a rail along x; one end ring is pinned
  GridClothSpec spec;
  spec.nx = spec.ny = 10;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 200, 0.05};
  params.spring(SpringKind::kShear) = {true, 50, 0.02};
  params.spring(SpringKind::kBend) = {true, 5, 0.005};
  params.drag = 0.02;
  params.stretch.enabled = true;
  params.stretch.max_strain = 0.1;
  World world;
  world.add_body(ClothBody("curtain", std::make_shared<const ClothModel>(make_grid_cloth(spec)),
                           params, make_integrator("symplectic_euler")));
  ClothBody& curtain = world.cloths()[0];
  curtain.pin(0);
  for (std::uint32_t ring = 1; ring < spec.nx; ++ring) {
    curtain.constrain(ParticleConstraint::Kind::kLine, ring, Vec3::UnitX());
  }
  const Real rail_y = curtain.state().x[1].y();
  for (int n = 0; n < 3000; ++n) {
    world.step();
    for (std::uint32_t ring = 1; ring < spec.nx; ++ring) {
      ASSERT_NEAR(world.cloths()[0].state().x[ring].y(), rail_y, 1e-12);
      ASSERT_NEAR(world.cloths()[0].state().x[ring].z(), 0, 1e-12);
    }
  }
  // the free end ring is not stuck: the sagging cloth pulled it along the rail, inward
  EXPECT_LT(world.cloths()[0].state().x[spec.nx - 1].x(), 0.5 - 1e-3);
}

}  // namespace
}  // namespace felt
