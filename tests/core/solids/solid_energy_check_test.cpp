// The solids' energy check against the conservation of energy: an undamped body in free space
// keeps its energy, so growth is the integrator's, however slow. The midpoint rule grows every
// undamped mode by 1 + (ωh)⁴/4 a step (runge_kutta_integrators.hpp); given a step it cannot keep
// stable, the check must catch the growth and report it.

#include <algorithm>
#include <limits>
#include <memory>
#include <utility>

#include <gtest/gtest.h>

#include "core/integrate/runge_kutta_integrators.hpp"
#include "core/solids/solid_contact_fixtures.hpp"
#include "core/solids/solid_system.hpp"

namespace felt {
namespace {

/// The midpoint rule claiming no step limit, as a scheme whose limit is misjudged would: the
/// solids then step it at position Verlet's limit (or max_step), where it grows.
class MidpointWithoutLimit final : public Integrator {
 public:
  std::string_view name() const override { return "midpoint"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override {
    midpoint_.step(system, state, t, h);
  }

 private:
  Midpoint midpoint_;
};

struct VibrationRun {
  Real start_energy = 0;
  Real largest_energy = 0;
  Real end_energy = 0;
  std::uint64_t rescued_steps = 0;
};

/// A 2 × 2 × 2 undamped FEM cube of 1 kg nodes, every node set moving at random (up to
/// 0.1 m/s), stepped for 3 s without gravity or colliders at a step where the midpoint rule
/// grows its fastest mode 1 + (ωh)⁴/4 = 1.02 times a step (ωh = 0.75).
VibrationRun free_vibration(Real energy_tolerance) {
  SolidBody body("cube", test::box({2, 2, 2}, 1), test::fem(1, 100, 0.3, 0));
  body.set_integrator(std::make_unique<MidpointWithoutLimit>());
  body.velocities() = test::random_vectors(body.node_count(), 0.1, 7);
  // stable_time_step() is 0.7 of Verlet's 2/ω
  const Real omega = 1.4 / body.stable_time_step();
  const Real h = 0.75 / omega;
  SolidStepSettings settings;
  settings.max_step = h;
  settings.health.energy_tolerance = energy_tolerance;
  SolidSystem system(settings);
  system.add_body(std::move(body));
  const auto energy = [&] {
    // read through a const system: handing out its bodies mutably starts its balance over
    const SolidBody& b = std::as_const(system).bodies()[0];
    return b.kinetic_energy() + b.elastic_energy();
  };
  VibrationRun run{.start_energy = energy()};
  const auto steps = static_cast<int>(3 / h);
  for (int s = 0; s < steps; ++s) {
    system.step(h, Vec3::Zero(), {});
    run.largest_energy = std::max(run.largest_energy, energy());
  }
  run.end_energy = energy();
  run.rescued_steps = system.substeps().rescued_steps();
  return run;
}

// Each rescue takes the growth the window saw out of the motion (0.23 J back to 0.14 J at the
// first), but the substeps it doubled relax after a second and the growth starts again: at
// most 3.2 times the start in 3 s, where the unchecked run grows 25 times.
TEST(SolidEnergyCheck, SlowGrowthIsCaughtAndReported) {
  const VibrationRun checked = free_vibration(HealthSettings{}.energy_tolerance);
  EXPECT_GT(checked.rescued_steps, 0u);
  EXPECT_LT(checked.largest_energy, 4 * checked.start_energy)
      << "started with " << checked.start_energy << " J";
  // without the check the same run grows unseen
  const VibrationRun unchecked = free_vibration(std::numeric_limits<Real>::infinity());
  EXPECT_EQ(unchecked.rescued_steps, 0u);
  EXPECT_GT(unchecked.end_energy, 10 * unchecked.start_energy);
}

// Contact pushes a body set inside the floor out with energy no force supplied: the first step
// after the solids are set is judged by speed only, so the body comes out and goes on, where
// judging its energy stopped it in the floor at every step (the thesis's two rings start 0.17 m
// into it).
TEST(SolidEnergyCheck, ABodySetInsideTheFloorIsPushedOutNotStopped) {
  constexpr Real kStep = 0.01;
  const Vec3 gravity(0, -9.81, 0);
  SolidSystem system;
  system.add_body(test::box_body({3, 3, 3}, Vec3::Constant(1.0 / 3), Vec3(0, -0.17, 0),
                                 test::fem(0.01, 1e4, 0.3, 0)));
  const Collider floor;  // the plane y = 0
  for (int s = 0; s < 50; ++s) {
    ASSERT_FALSE(system.step(kStep, gravity, {&floor, 1}).unrecoverable) << "step " << s;
  }
  for (const Vec3& x : std::as_const(system).bodies()[0].positions()) EXPECT_GE(x.y(), -1e-9);
}

}  // namespace
}  // namespace felt
