// A cloth's stable step (core/cloth/cloth_stable_step.hpp) against a single spring-mass, whose
// only mode is ω² = k/m, and against a brute-force eigenvalue: the dense matrices of a small
// cloth's force derivatives, taken by finite differences of its forces, solved by Eigen.

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/cloth/cloth_stable_step.hpp"

namespace felt {
namespace {

TEST(ClothStableStep, ASpringMassHasOmegaSquaredKOverM) {
  // k = 400 N/m, m = 0.25 kg, damping 2 N·s/m along the spring: ω² = 1600/s², c = d/m = 8/s
  const ClothBody pair = test::spring_pair(0.25, 400, 1, 2, "symplectic_euler");
  const ClothFastestMode mode = fastest_mode(pair);
  EXPECT_NEAR(mode.omega_squared, 1600, 1e-9 * 1600);
  EXPECT_NEAR(mode.most_rate, 8, 1e-9 * 8);
  EXPECT_NEAR(mode.least_rate, 8, 1e-9 * 8);
  // symplectic Euler: ω²h² + 2ch = 4, h = (−c + √(c² + 4ω²))/ω²
  EXPECT_NEAR(stable_cloth_step(pair), kClothStepMargin * (-8 + std::sqrt(64 + 4 * 1600)) / 1600,
              1e-12);
  // explicit Euler: h = c/ω² = d/k
  const ClothBody euler = test::spring_pair(0.25, 400, 1, 2, "explicit_euler");
  EXPECT_NEAR(stable_cloth_step(euler), kClothStepMargin * 2.0 / 400, 1e-12);
  // without damping explicit Euler has no step, and an implicit integrator no limit
  EXPECT_EQ(stable_cloth_step(test::spring_pair(0.25, 400, 1, 0, "explicit_euler")), 0);
  EXPECT_EQ(stable_cloth_step(test::spring_pair(0.25, 400, 1, 0, "implicit_euler")), kNoStepLimit);
}

/// −∂f/∂x (or −∂f/∂v with `velocity`) of `body` at its rest shape, at rest, by central
/// differences of compute_forces, scaled by √(M⁻¹) on both sides.
Eigen::MatrixXd scaled_derivative(const ClothBody& body, bool velocity) {
  const std::size_t n = body.model().particle_count();
  std::vector<Vec3> x = body.model().rest_positions, v(n, Vec3::Zero());
  std::vector<Vec3> plus(n), minus(n);
  Eigen::MatrixXd matrix(3 * n, 3 * n);
  constexpr Real kDelta = 1e-6;
  for (std::size_t column = 0; column < 3 * n; ++column) {
    std::vector<Vec3>& moved = velocity ? v : x;
    const Real saved = moved[column / 3][column % 3];
    moved[column / 3][column % 3] = saved + kDelta;
    body.compute_forces(x, v, 0, plus);
    moved[column / 3][column % 3] = saved - kDelta;
    body.compute_forces(x, v, 0, minus);
    moved[column / 3][column % 3] = saved;
    for (std::size_t row = 0; row < 3 * n; ++row) {
      const Real scale = std::sqrt(body.inv_mass()[row / 3] * body.inv_mass()[column / 3]);
      matrix(row, column) =
          -scale * (plus[row / 3][row % 3] - minus[row / 3][row % 3]) / (2 * kDelta);
    }
  }
  return 0.5 * (matrix + matrix.transpose());  // the differences' rounding is not symmetric
}

TEST(ClothStableStep, MatchesTheDenseEigenvaluesOfASmallCloth) {
  // 5 × 4 with every spring kind, drag, uneven masses (a grid's corners and edges are lighter),
  // two pins and an anchor
  ClothBody body = test::small_grid_body(5, 4, 300, 0.3, "leapfrog");
  body.pin(0);
  body.pin(4);
  body.set_anchor({12, body.state().x[12], 50, 0.5});
  const ClothFastestMode mode = fastest_mode(body);

  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> stiffness(scaled_derivative(body, false));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> damping(scaled_derivative(body, true));
  const Real omega_squared = stiffness.eigenvalues().maxCoeff();
  const Real most_rate = damping.eigenvalues().maxCoeff();
  // Lanczos approaches from above within 1e-3 (largest_eigenvalue)
  EXPECT_GE(mode.omega_squared, omega_squared * (1 - 1e-6));
  EXPECT_LE(mode.omega_squared, omega_squared * (1 + 2e-3));
  EXPECT_GE(mode.most_rate, most_rate * (1 - 1e-6));
  EXPECT_LE(mode.most_rate, most_rate * (1 + 2e-3));
  // the fastest mode's own damping (its Rayleigh quotient) lies between the two rates
  Eigen::Index top = 0;
  stiffness.eigenvalues().maxCoeff(&top);
  const Eigen::VectorXd u = stiffness.eigenvectors().col(top);
  const Real felt_rate = u.dot(scaled_derivative(body, true) * u);
  EXPECT_LE(mode.least_rate, felt_rate);
  EXPECT_GE(mode.most_rate, felt_rate);

  // the step then keeps leapfrog's fastest mode within ω²h² + 2ch ≤ 4 at either rate
  const Real h = stable_cloth_step(body) / kClothStepMargin;
  EXPECT_LE(omega_squared * h * h + 2 * felt_rate * h, 4 * (1 + 1e-9));
}

}  // namespace
}  // namespace felt
