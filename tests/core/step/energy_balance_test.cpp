// The energy balance against budgets of known shape: steady exponential growth is flagged within
// a few steps of a reset, before its first window closes; a bounded swing of the size a
// symplectic scheme shows is never flagged; an infinite tolerance flags nothing.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/step/energy_balance.hpp"

namespace felt {
namespace {

constexpr Real kTolerance = 0.25;  // HealthSettings::energy_tolerance's default
constexpr int kWindow = 25;        // 0.25 s of 10 ms steps

/// The step at which a budget growing `factor` times a step from 1 (scale 1 + the budget's
/// rise, as a body's kinetic and elastic energy rises with it) is first flagged, or -1.
int first_flagged_step(Real factor, Real tolerance, int steps) {
  EnergyBalance balance;
  balance.reset(1, 1);
  Real energy = 1;
  for (int s = 1; s <= steps; ++s) {
    energy *= factor;
    const Real scale = energy;
    if (!balance.within(balance.budget_after(energy, 0), scale, tolerance, kWindow)) return s;
    balance.accept(energy, 0, scale, kWindow);
  }
  return -1;
}

TEST(EnergyBalance, SteadyGrowthIsFlaggedBeforeItsFirstWindowCloses) {
  // 1.8 times a step: explicit Euler on an undamped solid at 352 substeps. Judged only at the
  // ends of windows it grew 10⁵ times before the second closed.
  const int flagged = first_flagged_step(1.8, kTolerance, 4 * kWindow);
  ASSERT_GT(flagged, 0);
  EXPECT_LT(flagged, kWindow / 4);
  // the budget rose at most 2 scales of the reset plus one step's growth
  EXPECT_LE(std::pow(1.8, flagged), 1 + 2 * 2 * 1.8);
}

TEST(EnergyBalance, SlowGrowthIsFlaggedByItsWindows) {
  // 1 % a step: 28 % a window, which no single step shows
  const int flagged = first_flagged_step(1.01, kTolerance, 10 * kWindow);
  ASSERT_GT(flagged, kWindow);
  EXPECT_LE(flagged, 3 * kWindow);
}

TEST(EnergyBalance, ASwingOfASymplecticSchemeIsNeverFlagged) {
  // energy swinging by 1.5 times its size (ωh = 1.6, the edge of the stable steps' margin)
  // over a period of 7 steps, for 20 windows, without growing
  EnergyBalance balance;
  balance.reset(1, 1);
  for (int s = 1; s <= 20 * kWindow; ++s) {
    const Real energy = 1 + 1.5 * std::pow(std::sin(std::numbers::pi * s / 7.0), 2);
    ASSERT_TRUE(balance.within(balance.budget_after(energy, 0), 1, kTolerance, kWindow))
        << "step " << s;
    balance.accept(energy, 0, 1, kWindow);
  }
}

TEST(EnergyBalance, WorkOfAppliedForcesIsNotGrowth) {
  // a push giving 0.5 J a step is what the energy rises by
  EnergyBalance balance;
  balance.reset(1, 1);
  Real energy = 1;
  for (int s = 1; s <= 4 * kWindow; ++s) {
    energy += 0.5;
    ASSERT_TRUE(balance.within(balance.budget_after(energy, 0.5), energy, kTolerance, kWindow));
    balance.accept(energy, 0.5, energy, kWindow);
  }
}

TEST(EnergyBalance, AnInfiniteToleranceFlagsNothing) {
  EXPECT_EQ(first_flagged_step(1.8, std::numeric_limits<Real>::infinity(), 4 * kWindow), -1);
}

}  // namespace
}  // namespace felt
