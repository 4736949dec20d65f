// A solid's stiffness at its points (solid_point_compliance): held by what it rests on, linear in
// its material's stiffness, and unknown where nothing holds it or its model has no stiffness.

#include <array>

#include <gtest/gtest.h>

#include "core/solids/solid_point_compliance.hpp"
#include "solid_fixtures.hpp"

namespace felt {
namespace {

/// A 2 × 2 × 2 box of 5 cm cells of corotated FEM, its bottom at z = 0.
SolidBody block(Real young) {
  return SolidBody("block", test::box({2, 2, 2}, 0.05), test::fem(0.01, young, 0.3, 0));
}

/// The node at the middle of the top face.
std::uint32_t top_middle(const SolidBody& body) {
  for (std::uint32_t n = 0; n < body.node_count(); ++n) {
    if ((body.positions()[n] - Vec3(0.05, 0.05, 0.1)).norm() < 1e-9) return n;
  }
  ADD_FAILURE() << "no top middle node";
  return 0;
}

Real pressed_down(const PointCompliance& compliance, std::uint32_t node) {
  const std::array<WeightedNode, 1> load{WeightedNode{node, 1}};
  return compliance.stiffness(load, Vec3::UnitZ());
}

Collider floor_plane() {
  Collider floor;
  floor.shape = Collider::Shape::kPlane;
  floor.normal = Vec3::UnitZ();
  return floor;
}

TEST(SolidPointCompliance, AFloorHoldsABlockAndItsStiffnessScalesWithItsMaterial) {
  const std::array<Collider, 1> floor{floor_plane()};
  const SolidBody soft = block(5e4), stiff = block(1e5);
  const Real k_soft = pressed_down(point_compliance(soft, floor), top_middle(soft));
  const Real k_stiff = pressed_down(point_compliance(stiff, floor), top_middle(stiff));
  EXPECT_GT(k_soft, 0);
  // K is linear in Young's modulus, so is every point's stiffness
  EXPECT_NEAR(k_stiff, 2 * k_soft, 1e-9 * k_stiff);
  // a node on the floor does not move
  const std::array<WeightedNode, 1> bottom{WeightedNode{0, 1}};
  EXPECT_EQ(point_compliance(soft, floor).stiffness(bottom, Vec3::UnitZ()), 0);
}

TEST(SolidPointCompliance, ABlockNothingHoldsHasOnlyItsInertiaOverAHorizon) {
  const SolidBody free = block(5e4);
  EXPECT_FALSE(point_compliance(free, {}).known());  // it moves as a whole under any push
  const Real tau = 0.05, total_mass = 0.01 * static_cast<Real>(free.node_count());
  const Real k = pressed_down(point_compliance(free, {}, tau), top_middle(free));
  // K + 2M/τ² ⪰ 2M/τ²: no softer than its own node's mass
  EXPECT_GT(k, 2 * 0.01 / (tau * tau));
  // a push through the centre of mass held for τ moves a rigid block by F τ² / 2M: a block far
  // stiffer than the push's horizon is that, and a softer one gives more
  const SolidBody rigid = block(1e10);
  const Real k_rigid = pressed_down(point_compliance(rigid, {}, tau), top_middle(rigid));
  EXPECT_NEAR(k_rigid, 2 * total_mass / (tau * tau), 1e-3 * k_rigid);
  EXPECT_LT(k, k_rigid);
}

TEST(SolidPointCompliance, ShapeMatchingHasNoStiffnessMatrix) {
  SolidMaterial material = test::fem(0.01, 5e4, 0.3, 0);
  material.model = SolidModel::kShapeMatching;
  const SolidBody body("block", test::box({2, 2, 2}, 0.05), material);
  const std::array<Collider, 1> floor{floor_plane()};
  EXPECT_FALSE(point_compliance(body, floor).known());
}

}  // namespace
}  // namespace felt
