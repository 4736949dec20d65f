// find_sphere_contact on a unit square in the z = 0 plane, where depths and normals follow from
// plane geometry by hand.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/collision/sphere_contact.hpp"

namespace felt {
namespace {

using test::expect_vec_near;

// The unit square [0, 1]² at z = 0, split along the diagonal 0-2, counter-clockwise from +z:
// triangle 0 is below the diagonal (y < x), triangle 1 above it.
struct Square {
  std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}};
};

// The contact must describe itself consistently: its point from its barycentrics, a unit
// normal and a positive depth.
void expect_consistent(const SphereContact& c, const std::vector<Vec3>& x,
                       const std::vector<Triangle>& triangles) {
  ASSERT_LT(c.triangle, triangles.size());
  const Triangle& t = triangles[c.triangle];
  const Vec3 rebuilt =
      c.barycentric.x() * x[t[0]] + c.barycentric.y() * x[t[1]] + c.barycentric.z() * x[t[2]];
  expect_vec_near(rebuilt, c.point, 1e-12);
  EXPECT_NEAR(c.barycentric.sum(), 1.0, 1e-12);
  EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
  EXPECT_GT(c.depth, 0);
}

TEST(SphereContact, SphereAboveTheFacePushesUp) {
  const Square s;
  const auto c = find_sphere_contact(s.x, s.triangles, Vec3(0.3, 0.4, 0.01), 0.02);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->triangle, 1u);  // (0.3, 0.4) has y > x
  expect_vec_near(c->point, Vec3(0.3, 0.4, 0), 1e-12);
  expect_vec_near(c->normal, Vec3(0, 0, 1), 1e-12);
  EXPECT_NEAR(c->depth, 0.01, 1e-12);
  expect_consistent(*c, s.x, s.triangles);
}

TEST(SphereContact, SphereBelowTheFacePushesDown) {
  const Square s;
  const auto c = find_sphere_contact(s.x, s.triangles, Vec3(0.3, 0.4, -0.01), 0.02);
  ASSERT_TRUE(c.has_value());
  expect_vec_near(c->point, Vec3(0.3, 0.4, 0), 1e-12);
  expect_vec_near(c->normal, Vec3(0, 0, -1), 1e-12);
  EXPECT_NEAR(c->depth, 0.01, 1e-12);
  expect_consistent(*c, s.x, s.triangles);
}

TEST(SphereContact, CentreOnTheSurfaceUsesTheFaceNormal) {
  Square s;
  const Vec3 center(0.7, 0.2, 0);  // inside triangle 0
  const auto up = find_sphere_contact(s.x, s.triangles, center, 0.02);
  ASSERT_TRUE(up.has_value());
  EXPECT_EQ(up->triangle, 0u);
  expect_vec_near(up->normal, Vec3(0, 0, 1), 1e-12);
  EXPECT_NEAR(up->depth, 0.02, 1e-15);
  expect_consistent(*up, s.x, s.triangles);

  // the face normal follows the winding: flipped triangles push the other way
  for (Triangle& t : s.triangles) std::swap(t[1], t[2]);
  const auto down = find_sphere_contact(s.x, s.triangles, center, 0.02);
  ASSERT_TRUE(down.has_value());
  expect_vec_near(down->normal, Vec3(0, 0, -1), 1e-12);
  EXPECT_NEAR(down->depth, 0.02, 1e-15);
}

TEST(SphereContact, FarSphereHasNoContact) {
  const Square s;
  EXPECT_FALSE(find_sphere_contact(s.x, s.triangles, Vec3(0.3, 0.4, 0.03), 0.02).has_value());
  EXPECT_FALSE(find_sphere_contact(s.x, s.triangles, Vec3(0.3, 0.4, -0.5), 0.02).has_value());
  EXPECT_FALSE(find_sphere_contact(s.x, s.triangles, Vec3(1.5, 0.5, 0), 0.02).has_value());
  // diagonally off a corner: 0.015 along x and y is 0.0212 > 0.02 from the corner
  EXPECT_FALSE(find_sphere_contact(s.x, s.triangles, Vec3(1.015, 1.015, 0), 0.02).has_value());
}

TEST(SphereContact, TouchingWithoutPenetrationIsNoContact) {
  // depth must be > 0; 0.25 and 0.5 are exact, so the distance equals the radius exactly
  const Square s;
  EXPECT_FALSE(find_sphere_contact(s.x, s.triangles, Vec3(0.5, 0.5, 0.25), 0.25).has_value());
}

TEST(SphereContact, EmptyMeshHasNoContact) {
  const std::vector<Vec3> x;
  const std::vector<Triangle> t;
  EXPECT_FALSE(find_sphere_contact(x, t, Vec3::Zero(), 1).has_value());
}

TEST(SphereContact, DeepestTriangleWins) {
  // a second, smaller triangle at z = 0.015 over the same spot, above the square
  Square s;
  s.x.insert(s.x.end(), {Vec3(0, 0, 0.015), Vec3(1, 0, 0.015), Vec3(0, 1, 0.015)});
  const Triangle roof = {4, 5, 6};
  const Vec3 center(0.3, 0.4, 0.01);  // 0.01 above the square, 0.005 below the roof
  for (int roof_first = 0; roof_first < 2; ++roof_first) {
    SCOPED_TRACE(roof_first ? "roof first" : "roof last");
    std::vector<Triangle> triangles = s.triangles;
    if (roof_first) {
      triangles.insert(triangles.begin(), roof);
    } else {
      triangles.push_back(roof);
    }
    const auto c = find_sphere_contact(s.x, triangles, center, 0.02);
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(triangles[c->triangle], roof);
    expect_vec_near(c->point, Vec3(0.3, 0.4, 0.015), 1e-12);
    expect_vec_near(c->normal, Vec3(0, 0, -1), 1e-12);
    EXPECT_NEAR(c->depth, 0.015, 1e-12);
    expect_consistent(*c, s.x, triangles);
  }
}

TEST(SphereContact, NearAnEdgeTheNormalPointsFromTheEdge) {
  const Square s;
  // beside the x = 1 edge: the nearest point is on the edge, not under the centre
  const Vec3 center(1.01, 0.5, 0.005);
  const auto c = find_sphere_contact(s.x, s.triangles, center, 0.02);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->triangle, 0u);  // the edge 1-2 belongs to triangle 0 only
  expect_vec_near(c->point, Vec3(1, 0.5, 0), 1e-12);
  const Real distance = std::sqrt(0.01 * 0.01 + 0.005 * 0.005);
  expect_vec_near(c->normal, Vec3(0.01, 0, 0.005) / distance, 1e-9);
  EXPECT_NEAR(c->depth, 0.02 - distance, 1e-12);
  expect_consistent(*c, s.x, s.triangles);
}

TEST(SphereContact, NearACornerTheNormalPointsFromTheCorner) {
  const Square s;
  const Vec3 center(-0.006, -0.008, 0);  // 0.01 from corner 0 (a 3-4-5 triangle)
  const auto c = find_sphere_contact(s.x, s.triangles, center, 0.02);
  ASSERT_TRUE(c.has_value());
  expect_vec_near(c->point, Vec3(0, 0, 0), 1e-15);
  expect_vec_near(c->normal, Vec3(-0.6, -0.8, 0), 1e-12);
  EXPECT_NEAR(c->depth, 0.01, 1e-12);
}

TEST(SphereContact, MatchesPlaneDistanceOverTheSquare) {
  // everywhere over the interior the depth is radius − |z| and the normal is ±z
  const Square s;
  const Real radius = 0.05;
  for (int i = 1; i < 20; ++i) {
    for (int j = 1; j < 20; ++j) {
      for (Real z : {-0.04, -0.01, 0.003, 0.049}) {
        const Vec3 center(i / 20.0, j / 20.0, z);
        const auto c = find_sphere_contact(s.x, s.triangles, center, radius);
        ASSERT_TRUE(c.has_value()) << center.transpose();
        EXPECT_NEAR(c->depth, radius - std::abs(z), 1e-12) << center.transpose();
        expect_vec_near(c->normal, Vec3(0, 0, z > 0 ? 1 : -1), 1e-9);
        expect_vec_near(c->point, Vec3(center.x(), center.y(), 0), 1e-12);
      }
    }
  }
}

// Regression: A triangle whose first two vertices coincide makes
// closest_point_on_triangle return NaN (see triangle_geometry_test); `distance_sq >= best` is
// false for NaN, so that triangle replaces the real contact and poisons every comparison after
// it. Here the collapsed triangle is 0.49 m away from the sphere, yet the contact with the
// square is lost.
TEST(SphereContact, CollapsedTriangleElsewhereDoesNotHideTheContact) {
  Square s;
  s.x.insert(s.x.end(), {Vec3(0.5, 0.2, 0.5), Vec3(0.5, 0.8, 0.5)});
  s.triangles.push_back({4, 4, 5});
  const auto c = find_sphere_contact(s.x, s.triangles, Vec3(0.3, 0.4, 0.01), 0.02);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->triangle, 1u);
  EXPECT_NEAR(c->depth, 0.01, 1e-12);
}

// Regression: A zero-area triangle that contains the centre wins the search with
// distance 0 (it comes first), then has no face normal, and the whole query returns nothing,
// although the square's own triangle contains the centre as well and gives depth = radius.
TEST(SphereContact, DegenerateTriangleThroughTheCentreDoesNotHideTheContact) {
  Square s;
  s.x.push_back(Vec3(0.5, 0, 0));  // on the edge 0-1
  s.triangles.insert(s.triangles.begin(), Triangle{0, 4, 1});
  const auto c = find_sphere_contact(s.x, s.triangles, Vec3(0.25, 0, 0), 0.02);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->depth, 0.02, 1e-15);
  expect_vec_near(c->normal, Vec3(0, 0, 1), 1e-12);
}

}  // namespace
}  // namespace felt
