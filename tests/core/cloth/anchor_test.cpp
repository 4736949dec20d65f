// Following a point: the soft anchor spring and the kinematic move (thesis 1 §5).

#include <cmath>

#include <gtest/gtest.h>

#include "core/world/world.hpp"

namespace felt {
namespace {

ClothBody lone_particle(std::string_view integrator, Real mass) {
  auto model = std::make_shared<ClothModel>();
  model->rest_positions = {Vec3::Zero()};
  model->uv = {Vec2::Zero()};
  model->mass = {mass};
  return ClothBody("p", model, ClothParams{}, make_integrator(integrator));
}

TEST(Anchor, OscillatesWithThePeriodOfItsSpring) {
  // m = 0.2 kg on k = 80 N/m: T = 2π √(m/k) ≈ 0.3142 s; count the upward zero crossings
  const Real m = 0.2, k = 80, h = 1e-4;
  World world(WorldSettings{Vec3::Zero(), h, 100, 6});
  world.add_body(lone_particle("velocity_verlet", m));
  world.cloths()[0].set_anchor({0, Vec3(0.1, 0, 0), k, 0});
  std::vector<Real> crossings;
  Real previous = world.cloths()[0].state().x[0].x() - 0.1;
  for (int n = 1; n <= 20000; ++n) {
    world.step();
    const Real offset = world.cloths()[0].state().x[0].x() - 0.1;
    if (previous < 0 && offset >= 0) {
      crossings.push_back((n - 1 + -previous / (offset - previous)) * h);  // interpolated
    }
    previous = offset;
  }
  ASSERT_GE(crossings.size(), 5u);
  const Real period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  EXPECT_NEAR(period, 2 * M_PI * std::sqrt(m / k), 1e-4);
}

TEST(Anchor, ImplicitEulerSettlesAtTheStaticEquilibriumAtAnyStep) {
  // hanging from its anchor: at rest k (target − x) = −m g, so x = target + m g / k
  const Real m = 0.5, k = 20;
  const Vec3 g(0, -9.81, 0), target(0, 1, 0);
  for (const Real h : {1e-3, 0.05, 1.0}) {
    World world(WorldSettings{g, h, 100, 6});
    world.add_body(lone_particle("implicit_euler", m));
    world.cloths()[0].set_anchor({0, target, k, 2});
    for (int n = 0; n < 20000 && n * h < 60; ++n) world.step();
    EXPECT_LT((world.cloths()[0].state().x[0] - (target + m * g / k)).norm(), 1e-6) << h;
  }
}

TEST(Anchor, ABouncingParticleKeepsItsKineticElasticAndGravitationalEnergy) {
  // undamped, a particle on its anchor spring under gravity is a conservative system: the sum of
  // ½ m v², ½ k |target − x|² and −m g·x stays what it was at the start (RK4 at ωh = 0.002)
  const Real m = 0.2, k = 80, h = 1e-4;
  const Vec3 g(0, -9.81, 0);
  World world(WorldSettings{g, h, 100, 6});
  world.add_body(lone_particle("rk4", m));
  ClothBody& body = world.cloths()[0];
  body.set_anchor({0, Vec3(0.1, 0.3, 0), k, 0});
  const auto total = [&] {
    return body.kinetic_energy() + body.elastic_energy() + body.gravitational_energy();
  };
  // starting 0.3 m below the anchor: m g·Δy = 0.2 · 9.81 · 0.3 ≈ 0.589 J of gravity to trade
  EXPECT_NEAR(body.gravitational_energy(), 0, 1e-15);
  const Real start = total();
  Real lowest = body.state().x[0].y(), highest = lowest;
  for (int n = 0; n < 10000; ++n) {
    world.step();
    lowest = std::min(lowest, body.state().x[0].y());
    highest = std::max(highest, body.state().x[0].y());
    ASSERT_NEAR(total(), start, 1e-9 * std::abs(start)) << n;
  }
  // and the energy really moved between the three: it bounced from y = 0 to the mirror point of
  // the equilibrium 0.3 − m g / k, with −m g·x following y
  EXPECT_NEAR(highest, 0.6 - 2 * m * 9.81 / k, 1e-6);
  EXPECT_NEAR(lowest, 0, 1e-6);
}

TEST(Anchor, MovingAPinnedParticleTakesItToTheTarget) {
  World world;
  world.add_body(lone_particle("symplectic_euler", 1));
  world.cloths()[0].pin(0);
  world.cloths()[0].move_particle(0, Vec3(1, 2, 3));
  for (int n = 0; n < 10; ++n) world.step();
  EXPECT_EQ(world.cloths()[0].state().x[0], Vec3(1, 2, 3));
  world.cloths()[0].remove_anchor(0);  // removing an anchor it never had changes nothing
  EXPECT_TRUE(world.cloths()[0].anchors().empty());
}

}  // namespace
}  // namespace felt
