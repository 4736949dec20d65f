#include "core/math/polar_decomposition.hpp"

#include <random>

#include <gtest/gtest.h>

namespace felt {
namespace {

Mat3 rotation(const Vec3& axis, Real angle) {
  return Eigen::AngleAxis<Real>(angle, axis.normalized()).toRotationMatrix();
}

/// R is a proper rotation, S symmetric and R S = F, to `tolerance` relative to ‖F‖.
void expect_decomposes(const Mat3& f, const PolarDecomposition& p, Real tolerance) {
  EXPECT_LT((p.rotation.transpose() * p.rotation - Mat3::Identity()).norm(), 1e-14);
  EXPECT_NEAR(p.rotation.determinant(), 1, 1e-14);
  EXPECT_EQ(p.stretch, p.stretch.transpose());
  EXPECT_LE((p.rotation * p.stretch - f).norm(), tolerance * f.norm());
}

// On deformations from tiny strains to large ones, turned every way and at the scale of a
// deformation gradient or of a cluster's moment (m², shape matching), the Newton iteration
// decomposes F and agrees with the singular value decomposition.
TEST(PolarDecomposition, AgreesWithTheSvd) {
  std::mt19937 random(11);
  std::normal_distribution<Real> normal;
  for (Real strain : {1e-6, 1e-3, 0.1, 0.3}) {
    std::uniform_real_distribution<Real> uniform(-strain, strain);
    for (Real scale : {1e-3, 1.0, 50.0}) {
      for (int i = 0; i < 200; ++i) {
        Mat3 e;
        for (int r = 0; r < 3; ++r) {
          for (int c = r; c < 3; ++c) e(r, c) = e(c, r) = uniform(random);
        }
        const Vec3 axis(normal(random), normal(random), normal(random));
        const Mat3 f = scale * rotation(axis, 4 * normal(random)) * (Mat3::Identity() + e);
        const PolarDecomposition fast = polar_decomposition(f);
        const PolarDecomposition svd = polar_decomposition_svd(f);
        expect_decomposes(f, fast, 1e-14);
        EXPECT_LT((fast.rotation - svd.rotation).norm(), 1e-13) << strain << " " << scale;
        EXPECT_LT((fast.stretch - svd.stretch).norm(), 1e-13 * f.norm());
      }
    }
  }
}

// F = R₀ V Σ Vᵀ with Σ positive has the rotation R₀ and the stretch V Σ Vᵀ, also when one
// direction is squeezed to 10⁻⁴ of the others (still the Newton iteration) or to 10⁻⁹ (the SVD).
TEST(PolarDecomposition, RecoversAKnownRotationAndStretch) {
  const Mat3 r0 = rotation(Vec3(1, -2, 0.5), 2.2);
  const Mat3 v = rotation(Vec3(0.3, 1, 1), 0.7);
  for (Real smallest : {0.5, 1e-4, 1e-9}) {
    const Mat3 stretch = v * Vec3(3, 1, smallest).asDiagonal() * v.transpose();
    const Mat3 f = r0 * stretch;
    const PolarDecomposition p = polar_decomposition(f);
    expect_decomposes(f, p, 1e-15);
    EXPECT_LT((p.rotation - r0).norm(), 1e-12) << smallest;
    EXPECT_LT((p.stretch - stretch).norm(), 1e-14) << smallest;
  }
}

// An inverted F (a reflection) keeps a proper rotation; the reflection goes into the stretch
// along F's smallest singular direction, where it disturbs the fit the least: F = R₀ V Σ Vᵀ
// with Σ = (2, 1, −0.5) gives back R₀ and a stretch with the eigenvalue −0.5.
TEST(PolarDecomposition, InvertedDeformationKeepsAProperRotation) {
  const Mat3 r0 = rotation(Vec3(2, 1, -1), 1.1);
  const Mat3 v = rotation(Vec3(-1, 0.4, 2), 2.5);
  const Mat3 stretch = v * Vec3(2, 1, -0.5).asDiagonal() * v.transpose();
  const Mat3 f = r0 * stretch;
  ASSERT_LT(f.determinant(), 0);
  const PolarDecomposition p = polar_decomposition(f);
  expect_decomposes(f, p, 1e-15);
  EXPECT_LT((p.rotation - r0).norm(), 1e-14);
  EXPECT_LT((p.stretch - stretch).norm(), 1e-14);
}

// A flat element (rank 2), a collinear one (rank 1) and a collapsed one still give a rotation
// with R S = F; in the directions F keeps, R is F's own rotation.
TEST(PolarDecomposition, FlatAndCollapsedDeformationsGiveARotation) {
  const Mat3 r0 = rotation(Vec3(1, 1, 1), 0.9);
  const Vec3 x = Vec3::UnitX(), y = Vec3::UnitY();
  for (const Vec3& sigma : {Vec3(2, 1, 0), Vec3(2, 0, 0), Vec3(0, 0, 0)}) {
    const Mat3 f = r0 * sigma.asDiagonal();
    const PolarDecomposition p = polar_decomposition(f);
    expect_decomposes(f, p, 1e-14);
    if (sigma(0) > 0) {
      EXPECT_LT((p.rotation * x - r0 * x).norm(), 1e-14);
    }
    if (sigma(1) > 0) {
      EXPECT_LT((p.rotation * y - r0 * y).norm(), 1e-14);
    }
  }
}

}  // namespace
}  // namespace felt
