// Soft-solid nodes against static colliders: projected onto the surface with no normal
// velocity left, and Coulomb friction that takes μ times the push off the slide.

#include "core/solids/solid_collider_contact.hpp"

#include <gtest/gtest.h>

#include "core/solids/solid_contact_fixtures.hpp"

namespace felt::test {
namespace {

Collider floor_plane(Real friction) {
  Collider floor;
  floor.friction = friction;
  return floor;
}

// One cube cell above the floor with its corner node moved over the step from x_prev to x.
struct Corner {
  SolidBody body = box_body({1, 1, 1}, Vec3::Ones(), Vec3(0, 0.5, 0));
  std::uint32_t node = node_at(body, Vec3(0, 0.5, 0));

  Corner(const Vec3& x_prev, const Vec3& x, Real friction) {
    SolidMaterial material = body.material();
    material.friction = friction;
    body.set_material(material);
    body.previous_positions()[node] = x_prev;
    body.positions()[node] = x;
  }
  Vec3 x() const { return body.positions()[node]; }
  Vec3 motion() const { return x() - body.previous_positions()[node]; }
};

// Sliding in from 2 mm above to 1 mm below: the node ends on the floor with no normal motion,
// and its 5 mm slide loses μ times the 3 mm approach stopped (μ = √(0.5·0.5)).
TEST(SolidColliderContact, ProjectsOntoTheFloorAndSlowsTheSlide) {
  Corner corner(Vec3(0, 0.002, 0), Vec3(0.005, -0.001, 0), 0.5);
  const Collider floor = floor_plane(0.5);
  EXPECT_EQ(resolve_collider_contacts({&floor, 1}, corner.body), 1u);
  EXPECT_DOUBLE_EQ(corner.x().y(), 0);
  EXPECT_DOUBLE_EQ(corner.motion().y(), 0);
  EXPECT_NEAR(corner.motion().x(), 0.005 - 0.5 * 0.003, 1e-15);
}

// A slide shorter than μ times the approach is stopped where it started, not reversed.
TEST(SolidColliderContact, StaticFrictionHoldsTheNode) {
  Corner corner(Vec3(0.3, 0, 0), Vec3(0.3004, -0.001, 0), 0.5);
  const Collider floor = floor_plane(0.5);
  resolve_collider_contacts({&floor, 1}, corner.body);
  EXPECT_LT(corner.motion().norm(), 1e-15);
}

TEST(SolidColliderContact, FrictionlessFloorKeepsTheSlide) {
  Corner corner(Vec3(0, 0, 0), Vec3(0.005, -0.001, 0.002), 0.5);
  const Collider floor = floor_plane(0);
  resolve_collider_contacts({&floor, 1}, corner.body);
  EXPECT_EQ(corner.motion(), Vec3(0.005, 0, 0.002));
}

// A node inside a ball ends on its surface, moved along the radius.
TEST(SolidColliderContact, NodeInsideABallEndsOnItsSurface) {
  Collider ball;
  ball.shape = Collider::Shape::kSphere;
  ball.center = Vec3(0.2, 0.1, 0.1);
  ball.radius = 0.3;
  Corner corner(Vec3(0, 0.5, 0), Vec3(0, 0.25, 0), 0);
  resolve_collider_contacts({&ball, 1}, corner.body);
  EXPECT_NEAR((corner.x() - ball.center).norm(), ball.radius, 1e-15);
  EXPECT_NEAR((corner.x() - ball.center).normalized().dot(Vec3(-0.2, 0.15, -0.1).normalized()), 1,
              1e-15);
}

// Free nodes above every collider are left alone, pinned ones even inside.
TEST(SolidColliderContact, LeavesFreeNodesOutsideAndPinnedNodes) {
  Corner corner(Vec3(0, 0, 0), Vec3(0, -0.01, 0), 0.5);
  corner.body.pin(corner.node);
  const Collider floor = floor_plane(0.5);
  EXPECT_EQ(resolve_collider_contacts({&floor, 1}, corner.body), 0u);
  EXPECT_EQ(corner.x(), Vec3(0, -0.01, 0));
}

}  // namespace
}  // namespace felt::test
