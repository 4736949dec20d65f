// Position Verlet, velocity Verlet and leapfrog against the analytic oscillator and free fall:
// order, energy, stability, pins, changes of step size and edits made from outside.

#include "core/integrate/verlet_integrators.hpp"

#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "core/integrate/oscillator.hpp"

namespace felt {
namespace {

using test::kMass;
using test::kOmega;
using test::kStiffness;
using test::measured_order;
using test::Oscillator;
using test::start_at;

std::vector<std::unique_ptr<Integrator>> verlet_family() {
  std::vector<std::unique_ptr<Integrator>> list;
  list.push_back(std::make_unique<PositionVerlet>());
  list.push_back(std::make_unique<VelocityVerlet>());
  list.push_back(std::make_unique<Leapfrog>());
  return list;
}

const Vec3 kGravity(0, -9.81, 0);

/// What "exact to rounding" means for a run of about 1000 steps of 1e-3 s falling about 5 m.
/// Position Verlet's velocity is a difference of positions over h, so its rounding is about
/// ε|x|/h ≈ 1e-12 per step; the others' stays near ε|v|.
Real rounding(const Integrator& integrator) {
  return integrator.name() == "verlet" ? 1e-10 : 1e-12;
}

TEST(VerletIntegrators, ConvergeWithOrderTwo) {
  for (const auto& integrator : verlet_family()) {
    EXPECT_NEAR(measured_order(*integrator, 1e-3), 2.0, 0.15) << integrator->name();
    // with damping (ζ = 0.1): the velocity the damping force sees must be second order too
    EXPECT_NEAR(measured_order(*integrator, 1e-3, 0.1), 2.0, 0.15) << integrator->name();
    // with steps alternating between ⅔h and 4⁄3h: the step-size corrections are second order
    EXPECT_NEAR(measured_order(*integrator, 1e-3, 0, true), 2.0, 0.15) << integrator->name();
  }
}

TEST(VerletIntegrators, FreeFallIsExact) {
  const Real h = 1e-3;
  const int steps = 1000;
  const Real t = steps * h;
  Oscillator falling(kMass, 0, kMass * kGravity);
  for (const auto& integrator : verlet_family()) {
    ParticleState state = start_at(Vec3::Zero());
    for (int n = 0; n < steps; ++n) integrator->step(falling, state, n * h, h);
    // far below any truncation error (½ g h t ≈ 5e-3 for a first-order scheme)
    EXPECT_NEAR((state.x[0] - 0.5 * kGravity * t * t).norm(), 0, rounding(*integrator))
        << integrator->name();
    EXPECT_NEAR((state.v[0] - kGravity * t).norm(), 0, rounding(*integrator)) << integrator->name();
  }
}

/// Free fall from rest at the origin: `first` steps of h1, optionally reset(), then `second`
/// steps of h2; returns the state.
ParticleState fall(Integrator& integrator, Real h1, int first, bool reset, Real h2, int second) {
  Oscillator falling(kMass, 0, kMass * kGravity);
  ParticleState state = start_at(Vec3::Zero());
  Real t = 0;
  for (int n = 0; n < first; ++n, t += h1) integrator.step(falling, state, t, h1);
  if (reset) integrator.reset();
  for (int n = 0; n < second; ++n, t += h2) integrator.step(falling, state, t, h2);
  return state;
}

TEST(VerletIntegrators, FreeFallStaysExactWhenTheStepSizeChanges) {
  const Real h1 = 1e-3;
  const Real h2 = 2.5e-3;
  const Real t = 300 * h1 + 200 * h2;
  for (const auto& integrator : verlet_family()) {
    for (bool reset : {true, false}) {
      const ParticleState state = fall(*integrator, h1, 300, reset, h2, 200);
      EXPECT_NEAR((state.x[0] - 0.5 * kGravity * t * t).norm(), 0, rounding(*integrator))
          << integrator->name() << (reset ? " with reset" : " without reset");
      EXPECT_NEAR((state.v[0] - kGravity * t).norm(), 0, rounding(*integrator))
          << integrator->name() << (reset ? " with reset" : " without reset");
    }
  }
}

TEST(PositionVerlet, ResetThenANewStepSizeIsConsistent) {
  // the rescue path of World: reset(), then substeps of half the size, on an oscillator. The
  // restart from (x, v) must continue the solution, not kick it: the error stays that of a
  // second-order run, and far below what a stale x_prev rescaled wrongly would give
  PositionVerlet verlet;
  Oscillator system(kMass, kStiffness);
  ParticleState state = start_at(Vec3(1, 0, 0));
  const Real h = 1e-3;
  for (int n = 0; n < 400; ++n) verlet.step(system, state, n * h, h);
  verlet.reset();
  for (int n = 0; n < 1200; ++n) verlet.step(system, state, 0.4 + n * h / 2, h / 2);
  const test::Exact exact = test::exact_oscillator(1.0);
  EXPECT_NEAR(state.x[0].x(), exact.x, 1e-4);
  EXPECT_NEAR(state.v[0].x() / kOmega, exact.v / kOmega, 1e-4);
}

TEST(VerletIntegrators, EnergyStaysBoundedOverLongRuns) {
  const Real h = 0.01;  // ωh ≈ 0.063
  for (const auto& integrator : verlet_family()) {
    Oscillator system(kMass, kStiffness);
    ParticleState state = start_at(Vec3(1, 0, 0));
    const Real e0 = system.energy(state);
    Real max_error = 0;
    for (int n = 0; n < 100000; ++n) {
      integrator->step(system, state, n * h, h);
      max_error = std::max(max_error, std::abs(system.energy(state) - e0) / e0);
    }
    // a modified energy is conserved exactly; the true one oscillates within O((ωh)²), and
    // does not drift: after 10⁵ steps it is still within that band
    EXPECT_LT(max_error, (kOmega * h) * (kOmega * h)) << integrator->name();
    EXPECT_NEAR(system.energy(state) / e0, 1.0, (kOmega * h) * (kOmega * h)) << integrator->name();
  }
}

TEST(VerletIntegrators, StabilityLimitIsTwoOverOmega) {
  auto amplitude_after = [](Integrator& integrator, Real h) {
    integrator.reset();
    Oscillator system(kMass, kStiffness);
    ParticleState state = start_at(Vec3(1, 0, 0));
    for (int n = 0; n < 500; ++n) integrator.step(system, state, n * h, h);
    return std::sqrt(2 * system.energy(state) / kStiffness);
  };
  // the characteristic roots of x_{n+1} − (2 − (ωh)²) x_n + x_{n−1} = 0 leave the unit circle
  // at ωh = 2: |λ| ≈ 1.63 at 1.03× the limit, 1.63⁵⁰⁰ overflows anything
  const Real limit = 2 / kOmega;
  for (const auto& integrator : verlet_family()) {
    EXPECT_LT(amplitude_after(*integrator, 0.97 * limit), 20.0) << integrator->name();
    EXPECT_FALSE(amplitude_after(*integrator, 1.03 * limit) < 1e6) << integrator->name();
  }
}

TEST(VerletIntegrators, PinnedParticleNeverMoves) {
  // particle 1 is pinned, displaced (so a force acts on it) and even given a velocity
  for (const auto& integrator : verlet_family()) {
    Oscillator system({1 / kMass, 0}, kStiffness, kGravity, 0.3);
    const Vec3 pin(0.3, 0.2, -0.1);
    ParticleState state{{Vec3(1, 0, 0), pin}, {Vec3::Zero(), Vec3(1, 2, 3)}};
    const Real h = 1e-3;
    for (int n = 0; n < 1000; ++n) {
      if (n == 500) integrator->reset();
      integrator->step(system, state, n * h, h);
      ASSERT_EQ(state.x[1], pin) << integrator->name() << " step " << n;
      ASSERT_EQ(state.v[1], Vec3::Zero()) << integrator->name() << " step " << n;
    }
    EXPECT_GT((state.x[0] - Vec3(1, 0, 0)).norm(), 0.1) << integrator->name();
  }
}

TEST(VerletIntegrators, AnUnpinnedParticleStartsAfresh) {
  // pinned for 100 steps under gravity, then released: it falls ½ g τ² from where it was held
  const Real h = 1e-3;
  for (const auto& integrator : verlet_family()) {
    Oscillator falling(std::vector<Real>{0}, 0, kMass * kGravity);  // pinned
    const Vec3 held(0, 1, 0);
    ParticleState state = start_at(held);
    for (int n = 0; n < 100; ++n) integrator->step(falling, state, n * h, h);
    falling.set_inv_mass(0, 1 / kMass);
    for (int n = 100; n < 300; ++n) integrator->step(falling, state, n * h, h);
    const Real tau = 200 * h;
    EXPECT_NEAR((state.x[0] - (held + 0.5 * kGravity * tau * tau)).norm(), 0, rounding(*integrator))
        << integrator->name();
    EXPECT_NEAR((state.v[0] - kGravity * tau).norm(), 0, rounding(*integrator))
        << integrator->name();
  }
}

TEST(VerletIntegrators, AVelocityEditedFromOutsideTakesEffect) {
  // as stretch limiting or a "stop" does between steps, without reset(): falling for 100 steps,
  // stopped, then falling again must follow ½ g τ² from where it was stopped
  const Real h = 1e-3;
  for (const auto& integrator : verlet_family()) {
    Oscillator falling(kMass, 0, kMass * kGravity);
    ParticleState state = start_at(Vec3::Zero());
    for (int n = 0; n < 100; ++n) integrator->step(falling, state, n * h, h);
    const Vec3 stopped_at = state.x[0];
    state.v[0].setZero();
    for (int n = 100; n < 300; ++n) integrator->step(falling, state, n * h, h);
    const Real tau = 200 * h;
    EXPECT_NEAR((state.x[0] - (stopped_at + 0.5 * kGravity * tau * tau)).norm(), 0,
                rounding(*integrator))
        << integrator->name();
    EXPECT_NEAR((state.v[0] - kGravity * tau).norm(), 0, rounding(*integrator))
        << integrator->name();
  }
}

TEST(PositionVerlet, APositionEditedFromOutsideBecomesVelocity) {
  // Jakobsen's constraint projection: moving a particle at rest by d (v untouched) gives it the
  // velocity d/h, since the velocity is x − x_prev
  PositionVerlet verlet;
  Oscillator free(kMass, 0);
  ParticleState state = start_at(Vec3::Zero());
  const Real h = 1e-2;
  verlet.step(free, state, 0, h);
  const Vec3 d(1e-3, 0, 0);
  state.x[0] += d;
  verlet.step(free, state, h, h);
  EXPECT_NEAR((state.x[0] - 2 * d).norm(), 0, 1e-15);
  EXPECT_NEAR((state.v[0] - d / h).norm(), 0, 1e-12);
}

TEST(VelocityVerlet, EvaluatesForcesOncePerStepUntilTheStateIsEdited) {
  VelocityVerlet verlet;
  Oscillator system(kMass, kStiffness);
  ParticleState state = start_at(Vec3(1, 0, 0));
  const Real h = 1e-3;
  verlet.step(system, state, 0, h);
  EXPECT_EQ(system.evaluations(), 2);  // the first step has no kept force
  for (int n = 1; n < 11; ++n) verlet.step(system, state, n * h, h);
  EXPECT_EQ(system.evaluations(), 12);
  verlet.reset();
  verlet.step(system, state, 11 * h, h);
  EXPECT_EQ(system.evaluations(), 14);
  state.x[0].x() += 1e-6;  // moved from outside: the kept force is stale
  verlet.step(system, state, 12 * h, h);
  EXPECT_EQ(system.evaluations(), 16);
  verlet.step(system, state, 13 * h, h);
  EXPECT_EQ(system.evaluations(), 17);
}

TEST(VerletIntegrators, AreNamedAsScenesSelectThem) {
  EXPECT_EQ(PositionVerlet().name(), "verlet");
  EXPECT_EQ(VelocityVerlet().name(), "velocity_verlet");
  EXPECT_EQ(Leapfrog().name(), "leapfrog");
}

}  // namespace
}  // namespace felt
