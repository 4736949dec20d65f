// Witkin constraint forces (thesis 1 §5) against the analytic spherical pendulum and the
// analytic slide down an inclined plane.

#include "core/cloth/constraint_force.hpp"

#include <cmath>
#include <string_view>

#include <gtest/gtest.h>

#include "core/world/world.hpp"

namespace felt {
namespace {

constexpr Real kG = 9.81;
constexpr Real kMass = 0.1;

/// A world holding one free particle of mass kMass at x0 with velocity v0.
World bead_world(const Vec3& x0, const Vec3& v0, std::string_view integrator, Real h) {
  auto model = std::make_shared<ClothModel>();
  model->rest_positions = {x0};
  model->uv = {Vec2::Zero()};
  model->mass = {kMass};
  World world(WorldSettings{Vec3(0, -kG, 0), h, 100, 6});
  world.add_body(ClothBody("bead", model, ClothParams{}, make_integrator(integrator)));
  world.cloths()[0].state().v[0] = v0;
  return world;
}

ConstraintForce sphere(const Vec3& center, Real radius, Real stiffness, Real damping) {
  ConstraintForce c;
  c.kind = ConstraintForce::Kind::kSphere;
  c.point = center;
  c.radius = radius;
  c.stiffness = stiffness;
  c.damping = damping;
  return c;
}

ConstraintForce plane(const Vec3& point, const Vec3& normal, Real stiffness, Real damping) {
  ConstraintForce c;
  c.kind = ConstraintForce::Kind::kPlane;
  c.point = point;
  c.normal = normal;
  c.stiffness = stiffness;
  c.damping = damping;
  return c;
}

const Vec3& position(const World& world) {
  return world.cloths()[0].state().x[0];
}
const Vec3& velocity(const World& world) {
  return world.cloths()[0].state().v[0];
}

class SphericalPendulum : public ::testing::TestWithParam<std::string_view> {};

TEST_P(SphericalPendulum, SmallOscillationPeriodIsTwoPiRootROverG) {
  // a bead on a sphere of radius r below its centre is a pendulum of length r; for amplitude
  // θ0 its period is 2π√(r/g) (1 + θ0²/16 + O(θ0⁴))
  const Real r = 0.5;
  const Real theta0 = 0.05;
  const Vec3 center(0, 1, 0);
  World world = bead_world(center + r * Vec3(std::sin(theta0), -std::cos(theta0), 0), Vec3::Zero(),
                           GetParam(), 1e-3);
  world.cloths()[0].add_constraint_force(sphere(center, r, 400, 40));
  // times at which x crosses the centre upward, linearly interpolated between steps
  std::vector<Real> crossings;
  Real previous_x = position(world).x();
  while (crossings.size() < 6) {
    ASSERT_EQ(world.step().flags, StepFlags{});
    const Real x = position(world).x();
    if (previous_x < 0 && x >= 0) {
      const Real h = world.settings().time_step;
      crossings.push_back(world.time() - h * x / (x - previous_x));
    }
    previous_x = x;
  }
  const Real period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const Real expected = 2 * M_PI * std::sqrt(r / kG) * (1 + theta0 * theta0 / 16);
  EXPECT_NEAR(period, expected, 1e-5 * expected);
}

/// The largest drift off the sphere ||x − c| − r| in each half of a 20 s run, and the largest
/// change of ½ m v² + m g y.
struct PendulumRun {
  Real drift_first_half = 0;
  Real drift_second_half = 0;
  Real energy_error = 0;
};

/// A true spherical pendulum of radius 0.5 m: started 60° out with a sideways push it traces a
/// rosette, about 14 swings in 20 s at 1 ms steps.
PendulumRun run_spherical_pendulum(std::string_view integrator, Real stiffness, Real damping) {
  const Real r = 0.5;
  const Vec3 center(0, 1, 0);
  const Real theta = M_PI / 3;
  World world = bead_world(center + r * Vec3(std::sin(theta), -std::cos(theta), 0), Vec3(0, 0, 1.2),
                           integrator, 1e-3);
  world.cloths()[0].add_constraint_force(sphere(center, r, stiffness, damping));
  const auto energy = [&] {
    return 0.5 * kMass * velocity(world).squaredNorm() + kMass * kG * position(world).y();
  };
  const Real e0 = energy();
  PendulumRun run;
  const int steps = 20000;
  for (int n = 0; n < steps; ++n) {
    EXPECT_EQ(world.step().flags, StepFlags{});
    Real& drift = n < steps / 2 ? run.drift_first_half : run.drift_second_half;
    drift = std::max(drift, std::abs((position(world) - center).norm() - r));
    run.energy_error = std::max(run.energy_error, std::abs(energy() - e0));
  }
  return run;
}

TEST_P(SphericalPendulum, StaysOnItsSphereOverALongRun) {
  const PendulumRun run = run_spherical_pendulum(GetParam(), 400, 40);
  EXPECT_LT(run.drift_first_half, 1e-5 * 0.5);
  EXPECT_LE(run.drift_second_half, 1.5 * run.drift_first_half);  // bounded: it does not grow
}

TEST_P(SphericalPendulum, ConservesEnergyWithoutFeedbackDamping) {
  // the constraint force is normal to the sphere and does no work: ½ m v² + m g y is constant
  const PendulumRun run = run_spherical_pendulum(GetParam(), 400, 0);
  const Real scale = kMass * kG * 0.5;  // the energy of a swing from the centre's height
  EXPECT_LT(run.energy_error, 1e-5 * scale);
}

INSTANTIATE_TEST_SUITE_P(Integrators, SphericalPendulum,
                         ::testing::Values("rk4", "velocity_verlet"));

TEST(SphericalPendulumFeedback, IsWhatKeepsASecondOrderIntegratorOnTheSphere) {
  // C̈ = 0 alone lets velocity Verlet's O(h²) errors accumulate off the sphere; the feedback
  // spring pulls them back
  const PendulumRun free = run_spherical_pendulum("velocity_verlet", 0, 0);
  const PendulumRun held = run_spherical_pendulum("velocity_verlet", 400, 40);
  EXPECT_GT(free.drift_second_half, 2 * free.drift_first_half);
  EXPECT_GT(free.drift_second_half, 1000 * held.drift_second_half);
}

TEST(PlaneConstraintForce, LeavesTheSlopeComponentOfGravity) {
  // on a 30° incline the total force on a bead moving along it is m g sinθ down the slope
  const Real theta = M_PI / 6;
  const Vec3 n(-std::sin(theta), std::cos(theta), 0);
  const Vec3 down_slope(-std::cos(theta), -std::sin(theta), 0);
  World world = bead_world(Vec3(0.3, 0.2, 0.1), Vec3::Zero(), "rk4", 1e-3);
  ClothBody& bead = world.cloths()[0];
  bead.add_constraint_force(plane(Vec3(0.3, 0.2, 0.1), n, 100, 20));
  Vec3 f;
  const Vec3 along(std::cos(theta), std::sin(theta), 0.5);  // in the plane
  const Vec3 x = Vec3(0.3, 0.2, 0.1) + 0.7 * along;
  bead.compute_forces(std::span(&x, 1), std::span(&along, 1), 0, std::span(&f, 1));
  EXPECT_LT((f / kMass - kG * std::sin(theta) * down_slope).norm(), 1e-12);
  bead.remove_constraint_forces(0);  // free again: gravity alone
  bead.compute_forces(std::span(&x, 1), std::span(&along, 1), 0, std::span(&f, 1));
  EXPECT_EQ(f, kMass * Vec3(0, -kG, 0));
}

TEST(PlaneConstraintForce, BeadSlidesDownAnInclineWithGSinTheta) {
  const Real theta = 0.4;
  const Vec3 n(-std::sin(theta), std::cos(theta), 0);
  const Vec3 down_slope(-std::cos(theta), -std::sin(theta), 0);
  const Vec3 x0(0.3, 0.2, 0.1);
  const Vec3 v0(0, 0, 0.5);  // across the slope: unaffected
  World world = bead_world(x0, v0, "rk4", 1e-3);
  world.cloths()[0].add_constraint_force(plane(x0, 2 * n, 100, 20));  // any length of normal
  const Real a = kG * std::sin(theta);
  for (int k = 1; k <= 1000; ++k) {
    ASSERT_EQ(world.step().flags, StepFlags{});
    const Real t = world.time();
    ASSERT_LT((position(world) - (x0 + v0 * t + 0.5 * a * t * t * down_slope)).norm(), 1e-9) << k;
    ASSERT_LT((velocity(world) - (v0 + a * t * down_slope)).norm(), 1e-9) << k;
  }
}

TEST(PlaneConstraintForce, CancelsTheNormalPullOfASpring) {
  // a bead held on the floor y = 0 by the constraint, tied by a zero-length spring to a pin
  // 0.3 m above the origin: the spring's in-plane part −k x makes it oscillate as x = A cos ωt
  // with ω = √(k/m); its vertical pull and gravity are both taken up by the constraint force
  const Real k = 4;
  const Real amplitude = 0.2;
  auto model = std::make_shared<ClothModel>();
  model->rest_positions = {Vec3(0, 0.3, 0), Vec3(amplitude, 0, 0)};
  model->uv = {Vec2::Zero(), Vec2::Zero()};
  model->mass = {kMass, kMass};
  model->springs = {{0, 1, 0, SpringKind::kStructural}};
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, k, 0};
  World world(WorldSettings{Vec3(0, -kG, 0), 1e-3, 100, 6});
  world.add_body(ClothBody("tethered", model, params, make_integrator("rk4")));
  ClothBody& body = world.cloths()[0];
  body.pin(0);
  ConstraintForce floor = plane(Vec3::Zero(), Vec3::UnitY(), 100, 20);
  floor.particle = 1;
  body.add_constraint_force(floor);
  const Real omega = std::sqrt(k / kMass);
  for (int n = 1; n <= 2000; ++n) {
    ASSERT_EQ(world.step().flags, StepFlags{});
    const Vec3& x = world.cloths()[0].state().x[1];
    const Real t = world.time();
    ASSERT_LT((x - Vec3(amplitude * std::cos(omega * t), 0, 0)).norm(), 1e-9) << n;
  }
}

TEST(PlaneConstraintForce, DriftDecaysAsTheFeedbackOscillatorPrescribes) {
  // started 1 cm off the plane, C follows C̈ = −k_s C − k_d Ċ; critically damped
  // (k_s = ω², k_d = 2ω) from rest that is C(t) = C0 (1 + ωt) e^{−ωt}
  const Real omega = 10;
  const Vec3 n = Vec3(1, 2, 2) / 3;
  const Real c0 = 0.01;
  World world = bead_world(c0 * n, Vec3::Zero(), "rk4", 1e-3);
  world.cloths()[0].add_constraint_force(plane(Vec3::Zero(), n, omega * omega, 2 * omega));
  for (int k = 1; k <= 1000; ++k) {
    ASSERT_EQ(world.step().flags, StepFlags{});
    const Real t = world.time();
    ASSERT_NEAR(n.dot(position(world)), c0 * (1 + omega * t) * std::exp(-omega * t), 1e-10) << k;
  }
}

}  // namespace
}  // namespace felt
