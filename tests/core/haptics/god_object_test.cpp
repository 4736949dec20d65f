// The god-object proxy against geometry worked out by hand (a plane, a crease, a corner, a
// sphere), against the invariant it exists for (a thin cloth, still or moving, is never
// popped through), and against the friction cones, damping, the clamps and force shading.
//
// Over 500 lines: the tests of one class whose stages are not yet split (see god_object.cpp).

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
#include "core/collision/triangle_query.hpp"
#include "core/geometry/procedural_surfaces.hpp"
#include "core/geometry/surface_normals.hpp"
#include "core/geometry/triangle_geometry.hpp"
#include "core/haptics/god_object.hpp"

namespace felt {
namespace {

using test::expect_vec_near;

/// A triangle surface moving linearly from one snapshot to the next, as the physics thread
/// would publish it: `advance` makes the newer snapshot the older one. Snapshots are shared
/// and immutable, as the runtime's are, so a proxy may keep one past `advance`.
struct Sheet {
  struct Snapshot {
    std::vector<Vec3> positions, normals;
  };

  std::uint32_t id = 0;
  std::vector<Triangle> triangles;
  std::shared_ptr<const Snapshot> older, newer;
  std::unique_ptr<TriangleQuery> query;
  SurfaceMotion motion{0, 0, 1};  ///< one chain of its own

  Sheet(std::uint32_t body_id, std::vector<Vec3> positions, std::vector<Triangle> tris)
      : id(body_id), triangles(std::move(tris)) {
    newer = snapshot(std::move(positions));
    older = newer;
    query = make_triangle_query(TriangleQueryKind::kBruteForce, triangles, newer->positions);
  }

  const std::vector<Vec3>& from() const { return older->positions; }
  const std::vector<Vec3>& to() const { return newer->positions; }

  void advance(std::vector<Vec3> next) {
    older = newer;
    newer = snapshot(std::move(next));
    query->refit(from(), to());
    motion = motion.then(from(), to());
  }

  HapticBody body() const {
    return {id, triangles, from(), to(), older->normals, newer->normals, query.get(), motion};
  }

 private:
  std::shared_ptr<const Snapshot> snapshot(std::vector<Vec3> positions) const {
    auto s = std::make_shared<Snapshot>();
    s->positions = std::move(positions);
    compute_vertex_normals(s->positions, triangles, s->normals);
    return s;
  }
};

HapticSurface surface_of(std::initializer_list<const Sheet*> sheets, std::uint64_t step = 1,
                         Real alpha = 1) {
  HapticSurface surface;
  auto storage = std::make_shared<std::vector<std::shared_ptr<const Sheet::Snapshot>>>();
  for (const Sheet* sheet : sheets) {
    surface.bodies.push_back(sheet->body());
    storage->push_back(sheet->older);
    storage->push_back(sheet->newer);
  }
  surface.storage = std::move(storage);
  surface.step = step;
  surface.alpha = alpha;
  return surface;
}

/// An n × n grid of vertices over [−size/2, size/2]² at height z, two triangles per cell.
struct Grid {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

Grid grid(std::uint32_t n, Real size, Real z) {
  Grid g;
  for (std::uint32_t j = 0; j < n; ++j) {
    for (std::uint32_t i = 0; i < n; ++i) {
      g.positions.emplace_back(size * (Real(i) / (n - 1) - 0.5), size * (Real(j) / (n - 1) - 0.5),
                               z);
    }
  }
  for (std::uint32_t j = 0; j + 1 < n; ++j) {
    for (std::uint32_t i = 0; i + 1 < n; ++i) {
      const std::uint32_t v = j * n + i;
      g.triangles.push_back({v, v + 1, v + n + 1});
      g.triangles.push_back({v, v + n + 1, v + n});
    }
  }
  return g;
}

std::vector<Vec3> shifted(std::vector<Vec3> positions, const Vec3& by) {
  for (Vec3& p : positions) p += by;
  return positions;
}

/// Squares given by their corners, appended as two triangles each.
Grid squares(std::initializer_list<std::array<Vec3, 4>> quads) {
  Grid g;
  for (const auto& q : quads) {
    const auto first = static_cast<std::uint32_t>(g.positions.size());
    g.positions.insert(g.positions.end(), q.begin(), q.end());
    g.triangles.push_back({first, first + 1, first + 2});
    g.triangles.push_back({first, first + 2, first + 3});
  }
  return g;
}

ProxySettings plain_settings(Real radius) {
  ProxySettings s;
  s.radius = radius;
  s.stiffness = 400;
  s.max_force = 1e6;
  s.max_force_change = 0;
  return s;
}

/// Moves the device from `a` to `b` in `updates` equal steps at 1 kHz; returns the last reply.
HapticContact stroke(GodObject& proxy, const HapticSurface& surface, const Vec3& a, const Vec3& b,
                     int updates) {
  HapticContact last;
  for (int i = 1; i <= updates; ++i) {
    last = proxy.update(surface, a + (b - a) * (Real(i) / updates), 1e-3);
  }
  return last;
}

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

// ---- a thin cloth: never popped through

/// Height of a height-field grid surface at (x, y), from its triangles at `alpha`.
Real height_at(const Sheet& sheet, Real alpha, Real x, Real y) {
  for (const Triangle& t : sheet.triangles) {
    Vec3 c[3];
    for (int k = 0; k < 3; ++k) c[k] = (1 - alpha) * sheet.from()[t[k]] + alpha * sheet.to()[t[k]];
    const Vec2 p(x, y);
    const Vec2 a = c[0].head<2>(), b = c[1].head<2>(), cc = c[2].head<2>();
    const Real area = (b - a).x() * (cc - a).y() - (b - a).y() * (cc - a).x();
    const Real u = ((b - p).x() * (cc - p).y() - (b - p).y() * (cc - p).x()) / area;
    const Real v = ((cc - p).x() * (a - p).y() - (cc - p).y() * (a - p).x()) / area;
    const Real w = 1 - u - v;
    if (u >= -1e-12 && v >= -1e-12 && w >= -1e-12)
      return u * c[0].z() + v * c[1].z() + w * c[2].z();
  }
  ADD_FAILURE() << "(" << x << ", " << y << ") is off the cloth";
  return 0;
}

struct Crossing {
  Real radius;
  Vec3 lateral;  ///< the device's sideways velocity, m/s
};

class ThinCloth : public ::testing::TestWithParam<Crossing> {};

// The device goes straight through a still cloth at 1 m/s, sampled at 1 kHz.
TEST_P(ThinCloth, AStillClothIsNeverPoppedThrough) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, 0);
  const Sheet cloth(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&cloth});
  const Vec3 start(0.05, 0.05, 0.06);  // above a vertex of the grid
  GodObject proxy(plain_settings(r), start);
  for (int i = 1; i <= 200; ++i) {
    const Vec3 device = start + 1e-3 * i * (Vec3(0, 0, -1) + lateral);
    const HapticContact c = proxy.update(surface, device, 1e-3);
    ASSERT_GE(c.proxy.z(), r - 1e-9) << "tick " << i;
    if (device.z() < r) {
      ASSERT_TRUE(c.in_contact) << "tick " << i;
    }
  }
}

// The cloth itself moves 1 cm per 10 ms physics step toward a still device; the haptic loop
// renders ten states between each pair of snapshots.
TEST_P(ThinCloth, AClothMovingOntoAStillDeviceCarriesTheProxy) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, 0.05);
  Sheet cloth(0, g.positions, g.triangles);
  const Vec3 device(0.05, 0.05, 0);
  GodObject proxy(plain_settings(r), Vec3(0.05, 0.05, -0.01));
  std::uint64_t step = 1;
  for (int physics = 0; physics < 15; ++physics, ++step) {
    cloth.advance(shifted(cloth.to(), Vec3(0, 0, -0.01) + 0.01 * lateral));
    for (int k = 1; k <= 10; ++k) {
      const HapticSurface surface = surface_of({&cloth}, step, 0.1 * k);
      const HapticContact c = proxy.update(surface, device, 1e-3);
      const Real below = height_at(cloth, 0.1 * k, c.proxy.x(), c.proxy.y()) - c.proxy.z();
      ASSERT_GE(below, r - 1e-9) << "physics step " << physics << " tick " << k;
    }
  }
  // pushed down by the cloth, the proxy pulls the device along
  EXPECT_LT(proxy.update(surface_of({&cloth}, step - 1, 1), device, 1e-3).force.z(), 0);
}

// The device moves up at 1 m/s while the cloth comes down at 1 m/s.
TEST_P(ThinCloth, ADeviceAgainstAnOncomingClothStaysOnItsSide) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, 0.05);
  Sheet cloth(0, g.positions, g.triangles);
  const Vec3 start(0.05, 0.05, -0.05);
  GodObject proxy(plain_settings(r), start);
  std::uint64_t step = 1;
  int tick = 0;
  for (int physics = 0; physics < 10; ++physics, ++step) {
    cloth.advance(shifted(cloth.to(), Vec3(0, 0, -0.01)));
    for (int k = 1; k <= 10; ++k) {
      ++tick;
      const Vec3 device = start + 1e-3 * tick * (Vec3(0, 0, 1) + lateral);
      const HapticContact c = proxy.update(surface_of({&cloth}, step, 0.1 * k), device, 1e-3);
      const Real below = height_at(cloth, 0.1 * k, c.proxy.x(), c.proxy.y()) - c.proxy.z();
      ASSERT_GE(below, r - 1e-9) << "tick " << tick;
    }
  }
}

// A cloth that waves (each vertex on its own vertical path) while the device pushes through.
TEST_P(ThinCloth, AWavingClothIsNeverPoppedThrough) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, 0);
  Sheet cloth(0, g.positions, g.triangles);
  const auto wave = [&](Real time) {
    std::vector<Vec3> x = g.positions;
    for (Vec3& p : x) p.z() = 0.02 * std::sin(8 * p.x() + 5 * p.y() - 30 * time);
    return x;
  };
  cloth.advance(wave(0));
  const Vec3 start(0.05, 0.05, 0.06);
  GodObject proxy(plain_settings(r), start);
  std::uint64_t step = 1;
  int tick = 0;
  for (int physics = 1; physics <= 20; ++physics, ++step) {
    cloth.advance(wave(0.01 * physics));
    for (int k = 1; k <= 10; ++k) {
      ++tick;
      const Vec3 device = start + 1e-3 * tick * (Vec3(0, 0, -1) + lateral);
      const HapticContact c = proxy.update(surface_of({&cloth}, step, 0.1 * k), device, 1e-3);
      const Real below = c.proxy.z() - height_at(cloth, 0.1 * k, c.proxy.x(), c.proxy.y());
      ASSERT_GT(below, -1e-9) << "tick " << tick;
    }
  }
}

// A cloth at rest 5 mm from the proxy (too far for the proxy to hold on to it) whose next
// snapshot is 10 cm away: it sweeps past the proxy between two updates. The proxy is tested
// against that motion and keeps its side.
TEST_P(ThinCloth, AClothFasterThanItsLastStepStillPushes) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, r + 0.005);
  Sheet cloth(0, g.positions, g.triangles);
  const Vec3 device(0.05, 0.05, 0);
  GodObject proxy(plain_settings(r), device);
  EXPECT_FALSE(proxy.update(surface_of({&cloth}, 1, 1), device, 1e-3).in_contact);
  cloth.advance(shifted(cloth.to(), Vec3(0, 0, -0.1) + 0.1 * lateral));
  for (int k = 1; k <= 10; ++k) {
    const HapticContact c = proxy.update(surface_of({&cloth}, 2, 0.1 * k), device, 1e-3);
    const Real below = height_at(cloth, 0.1 * k, c.proxy.x(), c.proxy.y()) - c.proxy.z();
    ASSERT_GE(below, r - 1e-9) << "tick " << k;
  }
}

// A remote client that updates its proxy at 20 Hz while the cloth, stepped at 100 Hz, comes
// down 1 cm per step through its still device: several snapshots go by between two updates,
// and the cloth is on the device's other side at the next. The proxy is tested against all the
// motion since its previous update and is carried down with the cloth.
TEST_P(ThinCloth, AProxyUpdatedRarelyIsCarriedThroughEverySnapshotBetweenItsUpdates) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, r + 0.025);
  Sheet cloth(0, g.positions, g.triangles);
  const Vec3 device(0.05, 0.05, 0);
  GodObject proxy(plain_settings(r), device);
  EXPECT_FALSE(proxy.update(surface_of({&cloth}, 1, 1), device, 1e-3).in_contact);
  std::uint64_t step = 1;
  for (int update = 1; update <= 3; ++update) {
    for (int physics = 0; physics < 5; ++physics) {
      cloth.advance(shifted(cloth.to(), Vec3(0, 0, -0.01) + 0.01 * lateral));
      ++step;
    }
    const Real alpha = update == 2 ? 0.5 : 1;  // anywhere in the newest pair
    const HapticContact c = proxy.update(surface_of({&cloth}, step, alpha), device, 0.05);
    const Real below = height_at(cloth, alpha, c.proxy.x(), c.proxy.y()) - c.proxy.z();
    ASSERT_GE(below, r - 1e-9) << "update " << update;
    if (update > 1) {  // the cloth has passed the device: it pushes the device down
      EXPECT_TRUE(c.in_contact) << "update " << update;
      EXPECT_LT(c.force.z(), 0) << "update " << update;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Paths, ThinCloth,
                         ::testing::Values(Crossing{0, Vec3::Zero()}, Crossing{0.01, Vec3::Zero()},
                                           Crossing{0, Vec3(0.3, 0.1, 0)},
                                           Crossing{0.01, Vec3(0.3, 0.1, 0)}));

// Two sheets 4 mm apart: the device goes through both, the proxy stays above the upper one,
// still and while the fold moves up into the device.
TEST(GodObjectFold, TheProxyStaysAboveTheUpperSheet) {
  for (const Real r : {0.0, 0.01}) {
    const Grid upper = grid(21, 1, 0);
    const Grid lower = grid(21, 1, -0.004);
    Sheet a(0, upper.positions, upper.triangles);
    Sheet b(1, lower.positions, lower.triangles);
    const Vec3 start(0.02, 0.03, 0.05);
    GodObject proxy(plain_settings(r), start);
    for (int i = 1; i <= 120; ++i) {
      const Vec3 device = start + 1e-3 * i * Vec3(0.2, 0, -1);
      const HapticContact c = proxy.update(surface_of({&a, &b}), device, 1e-3);
      ASSERT_GE(c.proxy.z(), r - 1e-9) << "tick " << i;
    }
    // now both sheets rise 5 mm per physics step against the device
    std::uint64_t step = 2;
    const Vec3 device = proxy.proxy() + Vec3(0, 0, -0.02);
    for (int physics = 0; physics < 6; ++physics, ++step) {
      a.advance(shifted(a.to(), Vec3(0, 0, 0.005)));
      b.advance(shifted(b.to(), Vec3(0, 0, 0.005)));
      for (int k = 1; k <= 10; ++k) {
        const HapticContact c = proxy.update(surface_of({&a, &b}, step, 0.1 * k), device, 1e-3);
        ASSERT_GE(c.proxy.z() - height_at(a, 0.1 * k, c.proxy.x(), c.proxy.y()), r - 1e-9)
            << "physics " << physics << " tick " << k;
      }
    }
  }
}

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

// ---- the device's limits and bad input

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
