// Midpoint, RK4 and adaptive Dormand–Prince against the analytic oscillator, free fall, their
// amplification factors and stability limits.

#include "core/integrate/runge_kutta_integrators.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "core/integrate/oscillator.hpp"

namespace felt {
namespace {

using test::exact_oscillator;
using test::kMass;
using test::kOmega;
using test::kStiffness;
using test::measured_order;
using test::Oscillator;
using test::start_at;

/// Particle 0 on a spring to the origin (f = −k x); particle 1 pushed by a force growing with
/// time, f = m g t, so that x₁ = g t³/6 from rest at the origin. Any scheme of order ≥ 3 follows
/// that cubic exactly whatever its step sizes, so particle 1 is a clock that tells whether a
/// call covered exactly [t, t + h]. Records the times it was asked at.
class SpringAndRamp final : public DynamicSystem {
 public:
  SpringAndRamp(Real stiffness, Vec3 g) : stiffness_(stiffness), g_(g) {}
  std::span<const Real> inv_mass() const override { return inv_mass_; }
  void compute_forces(std::span<const Vec3> x, std::span<const Vec3>, Real t,
                      std::span<Vec3> f) const override {
    f[0] = -stiffness_ * x[0];
    f[1] = kMass * g_ * t;
    times_.push_back(t);
  }
  const std::vector<Real>& times() const { return times_; }
  void forget_times() { times_.clear(); }
  Real earliest() const { return *std::min_element(times_.begin(), times_.end()); }
  Real latest() const { return *std::max_element(times_.begin(), times_.end()); }

 private:
  std::vector<Real> inv_mass_{1 / kMass, 1 / kMass};
  Real stiffness_;
  Vec3 g_;
  mutable std::vector<Real> times_;
};

/// Error of particle 0 of `state` against the undamped oscillator from x = 1 at time t.
Real error_at(const ParticleState& state, Real t) {
  const test::Exact exact = exact_oscillator(t);
  return std::hypot(state.x[0].x() - exact.x, (state.v[0].x() - exact.v) / kOmega);
}

TEST(RungeKuttaIntegrators, ConvergeWithTheirOrders) {
  Midpoint midpoint;
  RungeKutta4 rk4;
  // RK4 from a larger h: at 1e-3 its error would be down at rounding level
  EXPECT_NEAR(measured_order(midpoint, 1e-3), 2.0, 0.15);
  EXPECT_NEAR(measured_order(rk4, 0.02), 4.0, 0.15);
  // with damping (ζ = 0.1) as well: the velocity stages are used consistently
  EXPECT_NEAR(measured_order(midpoint, 1e-3, 0.1), 2.0, 0.15);
  EXPECT_NEAR(measured_order(rk4, 0.02, 0.1), 4.0, 0.15);
}

TEST(Midpoint, EnergyGrowsByItsAmplificationFactor) {
  // R(iy) = 1 + iy − y²/2 with y = ωh, so the energy grows by |R|² = 1 + y⁴/4 each step
  Midpoint midpoint;
  Oscillator system(kMass, kStiffness);
  ParticleState state = start_at(Vec3(1, 0, 0));
  const Real h = 0.01;
  const int steps = 10000;
  const Real e0 = system.energy(state);
  for (int n = 0; n < steps; ++n) midpoint.step(system, state, n * h, h);
  const Real y = kOmega * h;
  const Real expected = e0 * std::pow(1 + std::pow(y, 4) / 4, steps);
  EXPECT_NEAR(system.energy(state) / expected, 1.0, 1e-9);
  EXPECT_GT(system.energy(state), 1.01 * e0);
}

TEST(RungeKutta4, EnergyDecaysByItsAmplificationFactor) {
  // |R(iy)|² = 1 − y⁶/72 + y⁸/576 < 1: the energy decays, slowly, over 10⁵ steps
  RungeKutta4 rk4;
  Oscillator system(kMass, kStiffness);
  ParticleState state = start_at(Vec3(1, 0, 0));
  const Real h = 0.01;
  const int steps = 100000;
  const Real e0 = system.energy(state);
  for (int n = 0; n < steps; ++n) rk4.step(system, state, n * h, h);
  const Real y = kOmega * h;
  const Real factor = 1 - std::pow(y, 6) / 72 + std::pow(y, 8) / 576;
  const Real expected = e0 * std::pow(factor, steps);
  EXPECT_LT(system.energy(state), e0);  // the sign of the drift
  EXPECT_NEAR(system.energy(state) / e0, expected / e0, 1e-9);
  EXPECT_GT(system.energy(state), 0.999 * e0);  // slowly: about 9e-5 over the run
}

TEST(RungeKutta4, StabilityLimitIsTwoRootTwoOverOmega) {
  auto amplitude_after = [](Real h) {
    RungeKutta4 rk4;
    Oscillator system(kMass, kStiffness);
    ParticleState state = start_at(Vec3(1, 0, 0));
    for (int n = 0; n < 500; ++n) rk4.step(system, state, n * h, h);
    return std::sqrt(2 * system.energy(state) / kStiffness);
  };
  // the stability region of RK4 meets the imaginary axis at ±2√2 (the 2.785 of the real axis
  // is the limit for pure damping); |R| ≈ 0.81 at 0.97× and ≈ 1.23 at 1.03× the limit
  const Real limit = 2 * std::sqrt(2.0) / kOmega;
  EXPECT_LT(amplitude_after(0.97 * limit), 20.0);     // fails on NaN as well
  EXPECT_FALSE(amplitude_after(1.03 * limit) < 1e6);  // NaN counts as blown up
}

TEST(RungeKuttaIntegrators, FreeFallIsExact) {
  // a constant force: x = ½ g t², v = g t, which every scheme of order ≥ 2 integrates exactly
  const Vec3 g(0, -9.81, 0);
  const Real h = 1e-3;
  const int steps = 1000;
  const Real t = steps * h;
  Oscillator falling(kMass, 0, kMass * g);
  Midpoint midpoint;
  RungeKutta4 rk4;
  AdaptiveRungeKutta adaptive;
  for (Integrator* integrator : std::initializer_list<Integrator*>{&midpoint, &rk4, &adaptive}) {
    ParticleState state = start_at(Vec3::Zero());
    for (int n = 0; n < steps; ++n) integrator->step(falling, state, n * h, h);
    EXPECT_NEAR((state.x[0] - 0.5 * g * t * t).norm(), 0, 1e-12) << integrator->name();
    EXPECT_NEAR((state.v[0] - g * t).norm(), 0, 1e-12) << integrator->name();
  }
}

TEST(RungeKutta4, PassesTheStageTimes) {
  // on the ramp x'' = g t, exact for order 4, so wrong stage times would show
  SpringAndRamp system(0, Vec3(0, -9.81, 0));
  RungeKutta4 rk4;
  ParticleState state{{Vec3::Zero(), Vec3::Zero()}, {Vec3::Zero(), Vec3::Zero()}};
  const Real h = 0.01;
  for (int n = 0; n < 100; ++n) rk4.step(system, state, n * h, h);
  const Real t = 1;
  EXPECT_NEAR((state.x[1] - Vec3(0, -9.81, 0) * t * t * t / 6).norm(), 0, 1e-12);
  EXPECT_NEAR((state.v[1] - Vec3(0, -9.81, 0) * t * t / 2).norm(), 0, 1e-12);
}

TEST(AdaptiveRungeKutta, MeetsItsToleranceOverAPeriod) {
  // calls of h = 0.1 (ωh ≈ 0.63), each subdivided; the state must match the analytic solution
  // at every t = n h, which also shows that every call advanced exactly h
  AdaptiveRungeKutta adaptive(1e-8);
  EXPECT_EQ(adaptive.tolerance(), 1e-8);
  Oscillator system(kMass, kStiffness);
  ParticleState state = start_at(Vec3(1, 0, 0));
  const Real h = 0.1;
  Real worst = 0;
  int internal_steps = 0;
  for (int n = 0; n < 10; ++n) {
    adaptive.step(system, state, n * h, h);
    worst = std::max(worst, error_at(state, (n + 1) * h));
    internal_steps += adaptive.last_internal_steps();
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(error_at(state, 1.0), 1e-6);
  EXPECT_GT(internal_steps, 10);  // it did subdivide
}

/// Internal steps (rejected ones included) over one second of the oscillator of stiffness k,
/// in calls of 0.1 s.
int internal_steps_for(Real stiffness, Real tolerance) {
  AdaptiveRungeKutta adaptive(tolerance);
  Oscillator system(kMass, stiffness);
  ParticleState state = start_at(Vec3(1, 0, 0));
  int total = 0;
  for (int n = 0; n < 10; ++n) {
    adaptive.step(system, state, n * 0.1, 0.1);
    total += adaptive.last_internal_steps();
  }
  return total;
}

TEST(AdaptiveRungeKutta, TakesMoreStepsForStifferSpringsAndTighterTolerances) {
  const int base = internal_steps_for(kStiffness, 1e-6);
  const int stiff = internal_steps_for(100 * kStiffness, 1e-6);
  const int tight = internal_steps_for(kStiffness, 1e-10);
  EXPECT_GT(stiff, base);
  EXPECT_GT(tight, base);
  // theory (HNW I §II.4): the local error is ∝ (ω dt)⁵, so dt ∝ tol^(1/5) / ω: ten times ω
  // takes about ten times the steps, a 10⁴ times tighter tolerance about 10^(4/5) ≈ 6.3 times
  EXPECT_NEAR(static_cast<Real>(stiff) / base, 10.0, 4.0);
  EXPECT_NEAR(static_cast<Real>(tight) / base, 6.3, 2.5);
}

TEST(AdaptiveRungeKutta, EveryCallAdvancesExactlyH) {
  // uneven call lengths; the ramp particle is exact for DOPRI5, so it tells the clock
  const Vec3 g(0, -9.81, 0);
  SpringAndRamp system(100 * kStiffness, g);
  AdaptiveRungeKutta adaptive(1e-9);
  ParticleState state{{Vec3(1, 0, 0), Vec3::Zero()}, {Vec3::Zero(), Vec3::Zero()}};
  Real t = 0;
  for (int n = 0; n < 20; ++n) {
    const Real h = n % 3 == 0 ? 0.037 : 0.011;
    system.forget_times();
    adaptive.step(system, state, t, h);
    // forces are asked for inside [t, t + h] only, and at both ends
    EXPECT_EQ(system.earliest(), t);
    EXPECT_NEAR(system.latest(), t + h, 1e-15);
    EXPECT_LE(system.latest(), t + h + 1e-15);
    t += h;
    EXPECT_NEAR((state.x[1] - g * t * t * t / 6).norm(), 0, 1e-12) << "call " << n;
    EXPECT_NEAR((state.v[1] - g * t * t / 2).norm(), 0, 1e-12) << "call " << n;
  }
}

TEST(AdaptiveRungeKutta, KeepsItsInternalStepBetweenCalls) {
  // the second stage of DOPRI5 is evaluated at t + dt/5, which tells the step size tried
  SpringAndRamp system(100 * kStiffness, Vec3::Zero());
  AdaptiveRungeKutta adaptive(1e-8);
  ParticleState state{{Vec3(1, 0, 0), Vec3::Zero()}, {Vec3::Zero(), Vec3::Zero()}};
  const Real h = 0.05;
  EXPECT_EQ(adaptive.internal_step(), 0);
  adaptive.step(system, state, 0, h);
  // the first call tries h itself, far too long here (ωh ≈ 3), and shrinks
  EXPECT_NEAR(system.times()[1], h / 5, 1e-15);
  const int fresh_rejections = adaptive.last_rejected_steps();
  EXPECT_GE(fresh_rejections, 2);
  const Real kept = adaptive.internal_step();
  EXPECT_GT(kept, 0);
  EXPECT_LT(kept, h / 10);

  // the next call starts from the kept step size
  system.forget_times();
  adaptive.step(system, state, h, h);
  EXPECT_EQ(system.times()[0], h);
  EXPECT_NEAR(system.times()[1], h + kept / 5, 1e-15);
  EXPECT_LT(adaptive.last_rejected_steps(), fresh_rejections);
  int accepted = 0;
  int rejected = 0;
  for (int n = 2; n < 20; ++n) {
    adaptive.step(system, state, n * h, h);
    rejected += adaptive.last_rejected_steps();
    accepted += adaptive.last_internal_steps() - adaptive.last_rejected_steps();
  }
  EXPECT_LT(rejected, accepted / 10);

  // reset() forgets it: back to trying h
  adaptive.reset();
  EXPECT_EQ(adaptive.internal_step(), 0);
  system.forget_times();
  adaptive.step(system, state, 20 * h, h);
  EXPECT_NEAR(system.times()[1], 20 * h + h / 5, 1e-15);
}

TEST(AdaptiveRungeKutta, NeverTakesMoreThanItsCapOfInternalSteps) {
  // a spring far too stiff for 5 steps of a 1e-12 tolerance: it hits the cap, accepts its
  // smallest steps and still ends the call at t + h (the ramp particle says so)
  const Vec3 g(0, -9.81, 0);
  SpringAndRamp system(1e4 * kStiffness, g);
  AdaptiveRungeKutta adaptive(1e-12, 5);
  EXPECT_EQ(adaptive.max_internal_steps(), 5);
  ParticleState state{{Vec3(1e-3, 0, 0), Vec3::Zero()}, {Vec3::Zero(), Vec3::Zero()}};
  const Real h = 1e-3;
  for (int n = 0; n < 10; ++n) {
    adaptive.step(system, state, n * h, h);
    EXPECT_LE(adaptive.last_internal_steps(), 5);
  }
  EXPECT_EQ(adaptive.last_internal_steps(), 5);  // it did need them all
  const Real t = 10 * h;
  EXPECT_NEAR((state.x[1] - g * t * t * t / 6).norm(), 0, 1e-15);
  EXPECT_TRUE(state.x[0].allFinite());
}

TEST(RungeKuttaIntegrators, PinnedParticleNeverMoves) {
  // particle 1 is pinned, displaced (so a force acts on it) and even given a velocity
  const std::vector<std::unique_ptr<Integrator>> integrators = [] {
    std::vector<std::unique_ptr<Integrator>> list;
    list.push_back(std::make_unique<Midpoint>());
    list.push_back(std::make_unique<RungeKutta4>());
    list.push_back(std::make_unique<AdaptiveRungeKutta>());
    return list;
  }();
  for (const auto& integrator : integrators) {
    Oscillator system({1 / kMass, 0}, kStiffness, Vec3(0, -9.81, 0), 0.3);
    const Vec3 pin(0.3, 0.2, -0.1);
    ParticleState state{{Vec3(1, 0, 0), pin}, {Vec3::Zero(), Vec3(1, 2, 3)}};
    const Real h = 1e-3;
    for (int n = 0; n < 1000; ++n) {
      integrator->step(system, state, n * h, h);
      ASSERT_EQ(state.x[1], pin) << integrator->name() << " step " << n;
      ASSERT_EQ(state.v[1], Vec3::Zero()) << integrator->name() << " step " << n;
    }
    EXPECT_GT((state.x[0] - Vec3(1, 0, 0)).norm(), 0.1)
        << integrator->name();  // the free one moved
  }
}

TEST(RungeKuttaIntegrators, AreNamedAsScenesSelectThem) {
  EXPECT_EQ(Midpoint().name(), "midpoint");
  EXPECT_EQ(RungeKutta4().name(), "rk4");
  EXPECT_EQ(AdaptiveRungeKutta().name(), "adaptive_rk");
  EXPECT_EQ(AdaptiveRungeKutta().tolerance(), 1e-6);
}

}  // namespace
}  // namespace felt
