// The god-object's force against what it is made of: the friction cones, damping, the device's
// limits and force shading.

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

// ---- friction

TEST(GodObjectFriction, StickingHoldsTheProxyUntilTheDeviceLeavesTheStaticCone) {
  const Grid g = grid(11, 2, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  ProxySettings settings = plain_settings(0.01);
  settings.static_friction = 0.5;
  settings.dynamic_friction = 0.3;
  GodObject proxy(settings, Vec3(0, 0, 0.05));
  const Real depth = 0.01;
  HapticContact c = stroke(proxy, surface, Vec3(0, 0, 0.05), Vec3(0, 0, 0.01 - depth), 20);
  ASSERT_TRUE(c.in_contact);
  // inside the static cone (0.5 · 1 cm = 5 mm): stuck, pulled back along the surface
  c = stroke(proxy, surface, Vec3(0, 0, 0), Vec3(0.004, 0, 0), 8);
  EXPECT_FALSE(c.slipping);
  expect_vec_near(c.proxy, Vec3(0, 0, 0.01), 1e-12);
  expect_vec_near(c.force, 400 * Vec3(-0.004, 0, depth), 1e-9);
  // beyond it: slipping, dragged so the device is on the dynamic cone (3 mm behind)
  c = stroke(proxy, surface, Vec3(0.004, 0, 0), Vec3(0.02, 0, 0), 16);
  EXPECT_TRUE(c.slipping);
  expect_vec_near(c.proxy, Vec3(0.02 - 0.3 * depth, 0, 0.01), 1e-9);
  expect_vec_near(c.force, 400 * Vec3(-0.3 * depth, 0, depth), 1e-6);
  // the device stops: it is inside the cone again and sticks
  c = proxy.update(surface, Vec3(0.0195, 0, 0), 1e-3);
  EXPECT_FALSE(c.slipping);
  expect_vec_near(c.proxy, Vec3(0.02 - 0.3 * depth, 0, 0.01), 1e-9);
}

TEST(GodObjectFriction, WithoutFrictionTheProxySlidesFreely) {
  const Grid g = grid(11, 2, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  GodObject proxy(plain_settings(0.01), Vec3(0, 0, 0.05));
  stroke(proxy, surface, Vec3(0, 0, 0.05), Vec3(0, 0, 0), 20);
  const HapticContact c = stroke(proxy, surface, Vec3(0, 0, 0), Vec3(0.004, 0.002, 0), 4);
  EXPECT_FALSE(c.slipping);
  expect_vec_near(c.proxy, Vec3(0.004, 0.002, 0.01), 1e-12);
  expect_vec_near(c.force, Vec3(0, 0, 4), 1e-9);
}

// ---- damping

TEST(GodObjectDamping, ItResistsPressingInAndNeverPullsOnTheWayOut) {
  const Grid g = grid(2, 2, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  ProxySettings settings = plain_settings(0.01);
  settings.damping = 2;  // N·s/m
  GodObject proxy(settings, Vec3(0, 0, 0.02));
  // in at 1 m/s: 1 mm per 1 ms update
  HapticContact c;
  for (int i = 1; i <= 20; ++i) c = proxy.update(surface, Vec3(0, 0, 0.02 - 1e-3 * i), 1e-3);
  // 1 cm deep, the spring 1 cm long, and (proxy − device) growing at 1 m/s
  expect_vec_near(c.force, Vec3(0, 0, 400 * 0.01 + 2 * 1.0), 1e-9);
  // out at 1 m/s: 4 N of spring less 2 N of damping
  c = proxy.update(surface, Vec3(0, 0, 0.001), 1e-3);
  expect_vec_near(c.force, Vec3(0, 0, 400 * 0.009 - 2 * 1.0), 1e-9);
  // out at 10 m/s: the damping would pull; the force stops at zero
  c = proxy.update(surface, Vec3(0, 0, 0.009), 1e-3);
  ASSERT_TRUE(c.in_contact);
  expect_vec_near(c.force, Vec3::Zero(), 1e-12);
}

// ---- the device's limits

TEST(GodObjectClamps, TheForceNeverExceedsTheMaximum) {
  const Grid g = grid(2, 2, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  ProxySettings settings = plain_settings(0.01);
  settings.max_force = 10;
  GodObject proxy(settings, Vec3(0, 0, 0.05));
  const HapticContact c = stroke(proxy, surface, Vec3(0, 0, 0.05), Vec3(0, 0, -0.5), 30);
  expect_vec_near(c.force, Vec3(0, 0, 10), 1e-12);
}

TEST(GodObjectClamps, AJumpInForceIsSpreadOverUpdates) {
  const Grid g = grid(2, 2, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  ProxySettings settings = plain_settings(0.01);
  settings.max_force_change = 1;
  GodObject proxy(settings, Vec3(0, 0, 0.05));
  proxy.update(surface, Vec3(0, 0, 0.012), 1e-3);
  // through the plane in one update: 400 N/m · 1.5 cm = 6 N, reached 1 N per update
  for (int i = 1; i <= 8; ++i) {
    const HapticContact c = proxy.update(surface, Vec3(0, 0, -0.005), 1e-3);
    expect_vec_near(c.force, Vec3(0, 0, std::min(Real(i), 6.0)), 1e-9);
  }
  // and released the same way
  for (int i = 1; i <= 7; ++i) {
    const HapticContact c = proxy.update(surface, Vec3(0, 0, 0.5), 1e-3);
    expect_vec_near(c.force, Vec3(0, 0, std::max(6.0 - i, 0.0)), 1e-9);
  }
}

// ---- force shading

/// The largest turn of the force's direction from one update to the next while the device
/// slides 5 mm deep along a great circle of a coarse sphere (facets 20° apart).
Real largest_turn(bool shading) {
  const TriangleMesh mesh = make_sphere_surface(0.1, 1);
  const Sheet sphere(0, mesh.positions, mesh.triangles);
  const HapticSurface surface = surface_of({&sphere});
  ProxySettings settings = plain_settings(0);
  settings.force_shading = shading;
  const auto device_at = [](Real angle) -> Vec3 {
    return Vec3(std::cos(angle), 0.2, std::sin(angle)).normalized() * 0.085;
  };
  GodObject proxy(settings, 2 * device_at(0));
  Vec3 previous = stroke(proxy, surface, 2 * device_at(0), device_at(0), 50).force.normalized();
  Real largest = 0;
  for (int i = 1; i <= 2000; ++i) {
    const Vec3 force = proxy.update(surface, device_at(std::numbers::pi * i / 2000), 1e-3).force;
    const Vec3 direction = force.normalized();
    largest = std::max(largest, std::acos(std::clamp(direction.dot(previous), -1.0, 1.0)));
    previous = direction;
  }
  return largest;
}

TEST(GodObjectShading, TheForceTurnsSmoothlyAcrossEdges) {
  const Real degree = std::numbers::pi / 180;
  const Real faceted = largest_turn(false);
  const Real shaded = largest_turn(true);
  EXPECT_GT(faceted, 15 * degree);  // the facets are felt: the dihedral angle at each edge
  // The device is 15 mm deep, so at an edge the proxy passes over to where the device projects
  // onto the next face, a few mm on; the shaded normal turns only by what it turns over those
  // mm, the faceted one by the whole angle between the faces.
  EXPECT_LT(shaded, 3 * degree);
  EXPECT_LT(shaded, faceted / 5);
}

}  // namespace
}  // namespace felt
