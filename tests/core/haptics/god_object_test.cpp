// The god-object proxy against geometry worked out by hand (a plane, a crease, a corner, a
// sphere), and against input that is no reading (non-finite, out of bounds, too large).

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/geometry/procedural_surfaces.hpp"
#include "core/geometry/triangle_geometry.hpp"
#include "core/haptics/god_object.hpp"
#include "core/haptics/god_object_fixtures.hpp"

namespace felt {
namespace {

using namespace felt::test;  // the god-object fixtures and expect_vec_near

// ---- a static plane

class StaticPlane : public ::testing::TestWithParam<Real> {};

TEST_P(StaticPlane, PushedBelowFeelsStiffnessTimesDepthAlongTheNormal) {
  const Real r = GetParam();
  const Grid g = grid(2, 2, 0);
  const Sheet plane(7, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  GodObject proxy(plain_settings(r), Vec3(0.1, 0.2, 0.3));
  const Real d = 0.013;
  const HapticContact c = stroke(proxy, surface, Vec3(0.1, 0.2, 0.3), Vec3(0.1, 0.2, r - d), 30);
  ASSERT_TRUE(c.in_contact);
  expect_vec_near(c.force, Vec3(0, 0, 400 * d), 1e-9);
  expect_vec_near(c.contact_point, Vec3(0.1, 0.2, 0), 1e-12);
  expect_vec_near(c.proxy, Vec3(0.1, 0.2, r), 1e-12);
  expect_vec_near(proxy.proxy(), c.proxy, 0);
  expect_vec_near(c.normal, Vec3(0, 0, 1), 1e-12);
  EXPECT_EQ(c.constraints, 1);
  EXPECT_EQ(c.body_id, 7u);
  ASSERT_GE(c.triangle, 0);
  const Triangle& t = g.triangles[static_cast<std::size_t>(c.triangle)];
  expect_vec_near(c.barycentric.x() * g.positions[t[0]] + c.barycentric.y() * g.positions[t[1]] +
                      c.barycentric.z() * g.positions[t[2]],
                  c.contact_point, 1e-12);

  // lifted off: free, no force, the proxy back on the device
  const HapticContact free = proxy.update(surface, Vec3(0.1, 0.2, r + 0.01), 1e-3);
  EXPECT_FALSE(free.in_contact);
  expect_vec_near(free.force, Vec3::Zero(), 0);
  expect_vec_near(free.proxy, Vec3(0.1, 0.2, r + 0.01), 0);
}

TEST_P(StaticPlane, FromBelowItPushesDown) {
  const Real r = GetParam();
  const Grid g = grid(2, 2, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  GodObject proxy(plain_settings(r), Vec3(-0.3, 0.1, -0.2));
  const HapticContact c =
      stroke(proxy, surface, Vec3(-0.3, 0.1, -0.2), Vec3(-0.3, 0.1, -r + 0.02), 30);
  ASSERT_TRUE(c.in_contact);
  expect_vec_near(c.force, Vec3(0, 0, -400 * 0.02), 1e-9);
  expect_vec_near(c.proxy, Vec3(-0.3, 0.1, -r), 1e-12);
}

TEST_P(StaticPlane, SlidingKeepsTheProxyOnThePlane) {
  const Real r = GetParam();
  const Grid g = grid(11, 2, 0);  // 200 triangles: the slide crosses many edges
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  GodObject proxy(plain_settings(r), Vec3(-0.5, -0.3, 0.1));
  stroke(proxy, surface, Vec3(-0.5, -0.3, 0.1), Vec3(-0.5, -0.3, r - 0.01), 20);
  for (int i = 0; i <= 1000; ++i) {  // 1 mm per update, diagonally through vertices too
    const Vec3 device = Vec3(-0.5, -0.3, r - 0.01) + Real(i) * Vec3(1e-3, 0.6e-3, 0);
    const HapticContact c = proxy.update(surface, device, 1e-3);
    ASSERT_TRUE(c.in_contact) << i;
    expect_vec_near(c.proxy, Vec3(device.x(), device.y(), r), 1e-12);
    expect_vec_near(c.force, Vec3(0, 0, 4), 1e-9);
  }
}

INSTANTIATE_TEST_SUITE_P(Radius, StaticPlane, ::testing::Values(0.0, 0.02));

// ---- a sphere, circled from inside

/// Distance from p to the nearest triangle of a mesh, by brute force.
Real distance_to_mesh(const Vec3& p, const std::vector<Vec3>& x, const std::vector<Triangle>& t) {
  Real best = std::numeric_limits<Real>::infinity();
  for (const Triangle& tri : t) {
    best = std::min(
        best, (p - closest_point_on_triangle(p, x[tri[0]], x[tri[1]], x[tri[2]]).point).norm());
  }
  return best;
}

/// The largest angle between the force and the radial direction at the contact point while
/// the device circles 5 mm below the surface; every contact point checked on the mesh.
Real circle_inside_sphere(bool shading, Real r) {
  const Real big = 0.1;
  const TriangleMesh mesh = make_sphere_surface(big, 3);
  const Sheet sphere(0, mesh.positions, mesh.triangles);
  const HapticSurface surface = surface_of({&sphere});
  ProxySettings settings = plain_settings(r);
  settings.force_shading = shading;
  const Real depth = 0.005;
  const auto device_at = [&](Real angle) -> Vec3 {
    return Vec3(std::cos(angle), std::sin(angle), 0.3).normalized() * (big + r - depth);
  };
  GodObject proxy(settings, 2 * device_at(0));
  stroke(proxy, surface, 2 * device_at(0), device_at(0), 50);
  Real worst = 0;
  const int updates = 1200;  // about 0.5 mm per update
  for (int i = 0; i <= updates; ++i) {
    const HapticContact c =
        proxy.update(surface, device_at(2 * std::numbers::pi * i / updates), 1e-3);
    EXPECT_TRUE(c.in_contact) << i;
    EXPECT_LE(distance_to_mesh(c.contact_point, mesh.positions, mesh.triangles), 1e-12) << i;
    EXPECT_GE(distance_to_mesh(c.proxy, mesh.positions, mesh.triangles), r - 1e-9) << i;
    const Vec3 radial = c.contact_point.normalized();
    worst = std::max(worst, std::acos(std::clamp(c.force.normalized().dot(radial), -1.0, 1.0)));
  }
  return worst;
}

TEST(GodObjectSphere, ContactStaysOnTheSurfaceAndTheForceIsRadial) {
  const Real degree = std::numbers::pi / 180;
  // the facets of this sphere turn about 8° from one to the next: the flat faces tilt the force
  // by up to half that, the interpolated normals by much less
  const Real faceted = circle_inside_sphere(false, 0.01);
  EXPECT_LT(faceted, 8 * degree);
  EXPECT_LT(circle_inside_sphere(true, 0), 1.5 * degree);
  EXPECT_LT(circle_inside_sphere(true, 0.01), 1.5 * degree);
  EXPECT_LT(circle_inside_sphere(true, 0.01), faceted / 3);
}

// ---- a concave crease and a corner

TEST(GodObjectCrease, TheProxyStaysOutsideBothPlanesAndSlidesAlongTheCrease) {
  const Real r = 0.01;
  // floor z = 0 and wall x = 0, meeting along the y axis; the free space is x > 0, z > 0
  const Grid g = squares({{Vec3(0, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)},
                          {Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(0, 1, 1), Vec3(0, -1, 1)}});
  const Sheet crease(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&crease});
  GodObject proxy(plain_settings(r), Vec3(0.2, 0, 0.15));
  HapticContact c = stroke(proxy, surface, Vec3(0.2, 0, 0.15), Vec3(-0.02, 0, -0.03), 40);
  ASSERT_TRUE(c.in_contact);
  EXPECT_EQ(c.constraints, 2);
  expect_vec_near(c.proxy, Vec3(r, 0, r), 1e-5);
  EXPECT_GE(c.proxy.x(), r - 1e-9);
  EXPECT_GE(c.proxy.z(), r - 1e-9);
  expect_vec_near(c.force, 400 * Vec3(r + 0.02, 0, r + 0.03), 1e-3);
  for (int i = 1; i <= 300; ++i) {
    const Vec3 device(-0.02, 1e-3 * i, -0.03);
    c = proxy.update(surface, device, 1e-3);
    ASSERT_EQ(c.constraints, 2) << i;
    expect_vec_near(c.proxy, Vec3(r, device.y(), r), 1e-5);
    EXPECT_GE(c.proxy.x(), r - 1e-9);
    EXPECT_GE(c.proxy.z(), r - 1e-9);
    EXPECT_LE(std::min(c.contact_point.x(), c.contact_point.z()), 1e-12);  // on a plane
  }
}

TEST(GodObjectCorner, TheProxyHoldsTheCornerAndTheForcePointsOut) {
  for (const Real r : {0.0, 0.01}) {
    // three walls of the positive octant
    const Grid g = squares({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)},
                            {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 1), Vec3(0, 0, 1)},
                            {Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 0, 0)}});
    const Sheet corner(0, g.positions, g.triangles);
    const HapticSurface surface = surface_of({&corner});
    GodObject proxy(plain_settings(r), Vec3(0.2, 0.3, 0.25));
    const HapticContact c =
        stroke(proxy, surface, Vec3(0.2, 0.3, 0.25), Vec3(-0.02, -0.01, -0.03), 50);
    ASSERT_TRUE(c.in_contact);
    EXPECT_EQ(c.constraints, 3);
    expect_vec_near(c.proxy, Vec3(r, r, r), 1e-5);
    EXPECT_GE(c.proxy.minCoeff(), r - 1e-9);
    EXPECT_GT(c.force.minCoeff(), 0);  // out of the corner along every axis
    expect_vec_near(c.force, 400 * (Vec3(r, r, r) - Vec3(-0.02, -0.01, -0.03)), 1e-3);
    // pressed harder, still there
    const HapticContact deeper = proxy.update(surface, Vec3(-0.05, -0.04, -0.06), 1e-3);
    EXPECT_EQ(deeper.constraints, 3);
    EXPECT_GE(deeper.proxy.minCoeff(), r - 1e-9);
  }
}

// ---- bad input

TEST(GodObjectBadInput, ANonFiniteDeviceGivesZeroForceAndKeepsTheProxy) {
  const Grid g = grid(2, 2, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  GodObject proxy(plain_settings(0.01), Vec3(0, 0, 0.05));
  stroke(proxy, surface, Vec3(0, 0, 0.05), Vec3(0.1, 0, 0), 20);
  const Vec3 before = proxy.proxy();
  for (const Real bad : {std::nan(""), std::numeric_limits<Real>::infinity()}) {
    const HapticContact c = proxy.update(surface, Vec3(bad, 0, 0), 1e-3);
    expect_vec_near(c.force, Vec3::Zero(), 0);
    expect_vec_near(c.proxy, before, 0);
    expect_vec_near(proxy.proxy(), before, 0);
  }
  // and it carries on from there
  const HapticContact c = proxy.update(surface, Vec3(0.1, 0, 0), 1e-3);
  EXPECT_TRUE(c.in_contact);
  expect_vec_near(c.proxy, before, 1e-12);
}

// Issue 31: a device at 1e308 after a contact came back in contact with a NaN contact point,
// and one sent to DBL_MAX and back stayed there, in contact with zero force. Beyond the bound
// on every vector from outside (±1e6 m) a device position is no reading, as a NaN is.
TEST(GodObjectBadInput, ADeviceBeyondTheBoundIsNoReadingAndTheProxyCarriesOn) {
  const Grid g = grid(2, 2, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  GodObject proxy(plain_settings(0.01), Vec3(0, 0, 0.05));
  const HapticContact pressed = stroke(proxy, surface, Vec3(0, 0, 0.05), Vec3(0.1, 0, 0), 20);
  ASSERT_TRUE(pressed.in_contact);
  const Real huge = std::numeric_limits<Real>::max();
  for (const Vec3& far : {Vec3(1e308, 0, 0), Vec3(huge, huge, huge), Vec3(0.1, 0, -1e200),
                          Vec3(-huge, 0, huge), Vec3(0, std::nextafter(1e6, 2e6), 0)}) {
    const HapticContact c = proxy.update(surface, far, 1e-3);
    EXPECT_FALSE(c.in_contact) << far.transpose();
    expect_vec_near(c.force, Vec3::Zero(), 0);
    expect_vec_near(c.proxy, pressed.proxy, 0);
    expect_vec_near(c.contact_point, pressed.proxy, 0);
    expect_vec_near(c.normal, Vec3::Zero(), 0);
    expect_vec_near(proxy.proxy(), pressed.proxy, 0);
  }
  // back from every one of them: pressed as before, on the same spot
  const HapticContact back = proxy.update(surface, Vec3(0.1, 0, 0), 1e-3);
  ASSERT_TRUE(back.in_contact);
  expect_vec_near(back.proxy, pressed.proxy, 1e-12);
  expect_vec_near(back.force, pressed.force, 1e-9);
  // the bound itself is a reading: 1e6 m away is free space
  const HapticContact far = proxy.update(surface, Vec3(0, 0, 1e6), 1e-3);
  EXPECT_FALSE(far.in_contact);
  expect_vec_near(far.proxy, Vec3(0, 0, 1e6), 0);
}

// Whatever leaves is finite, or the update is no reading: here a square 2e300 m across, whose
// squared sizes overflow, pressed from above.
TEST(GodObjectBadInput, ASurfaceTooLargeForDoublesGivesNoNonFiniteOutput) {
  const Grid g = squares({{Vec3(-1e300, -1e300, 0), Vec3(1e300, -1e300, 0), Vec3(1e300, 1e300, 0),
                           Vec3(-1e300, 1e300, 0)}});
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  GodObject proxy(plain_settings(0.01), Vec3(0, 0, 0.05));
  for (int i = 1; i <= 40; ++i) {
    const HapticContact c = proxy.update(surface, Vec3(0.001 * i, 0, 0.05 - 0.002 * i), 1e-3);
    ASSERT_TRUE(c.force.allFinite() && c.proxy.allFinite() && c.contact_point.allFinite() &&
                c.normal.allFinite() && c.barycentric.allFinite())
        << i;
    EXPECT_LE(c.force.norm(), 1e6) << i;
  }
}

TEST(GodObjectBadInput, ANonFiniteVertexIsSkippedNeverPropagated) {
  Grid g = grid(5, 1, 0);
  g.positions[12] = Vec3(std::nan(""), 0, 0);  // the centre vertex
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  for (const Real r : {0.0, 0.01}) {
    GodObject proxy(plain_settings(r), Vec3(0.4, 0.4, 0.05));
    HapticContact c = stroke(proxy, surface, Vec3(0.4, 0.4, 0.05), Vec3(0.4, 0.4, -0.01), 20);
    EXPECT_TRUE(c.in_contact);        // a triangle away from the bad vertex
    for (int i = 1; i <= 300; ++i) {  // across the triangles around it
      c = proxy.update(surface, Vec3(0.4 - 1.5e-3 * i, 0.4 - 1.4e-3 * i, -0.01), 1e-3);
      ASSERT_TRUE(c.force.allFinite() && c.proxy.allFinite() && c.contact_point.allFinite() &&
                  c.normal.allFinite() && c.barycentric.allFinite())
          << i;
    }
  }
}

}  // namespace
}  // namespace felt
