#include "core/geometry/procedural_surfaces.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/geometry/closed_surface.hpp"

namespace felt {
namespace {

using std::numbers::pi;

void expect_uv_per_vertex_in_unit_square(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.uv.size(), mesh.positions.size());
  for (const Vec2& uv : mesh.uv) {
    EXPECT_TRUE((uv.array() >= 0).all() && (uv.array() <= 1).all()) << uv.transpose();
  }
}

// Table 7.1 of the second thesis: the fine cube is a 20 × 20 × 20 grid surface.
TEST(ProceduralSurfaces, ThesisFineCubeHasTheTableCounts) {
  const TriangleMesh box = make_box_surface(Vec3::Ones(), 20);
  EXPECT_EQ(box.positions.size(), 2402u);
  EXPECT_EQ(box.triangles.size(), 4800u);
}

TEST(ProceduralSurfaces, BoxIsClosedOutwardAndExact) {
  const Vec3 size(2, 3, 5);
  const TriangleMesh box = make_box_surface(size, 4);
  EXPECT_TRUE(test::is_closed_and_oriented(box.triangles));
  EXPECT_EQ(test::euler_characteristic(box.triangles), 2);
  EXPECT_NEAR(test::enclosed_volume(box.positions, box.triangles), 30, 1e-12);
  EXPECT_NEAR(test::surface_area(box.positions, box.triangles), 2 * (6 + 15 + 10), 1e-12);
  for (const Vec3& p : box.positions) {
    // on the surface: some coordinate at ± half the size, none beyond
    EXPECT_NEAR((p.cwiseAbs() - size / 2).maxCoeff(), 0, 1e-15) << p.transpose();
  }
  expect_uv_per_vertex_in_unit_square(box);
}

TEST(ProceduralSurfaces, TorusIsAClosedOutwardSurfaceOfGenusOne) {
  const TriangleMesh torus = make_torus_surface(2, 0.5, 24, 12);
  EXPECT_EQ(torus.positions.size(), 24u * 12u);
  EXPECT_EQ(torus.triangles.size(), 2u * 24u * 12u);
  EXPECT_TRUE(test::is_closed_and_oriented(torus.triangles));
  EXPECT_EQ(test::euler_characteristic(torus.triangles), 0);
  for (const Vec3& p : torus.positions) {
    // every vertex on the tube: its distance from the core circle is the minor radius
    const Real from_axis = std::hypot(p.x(), p.z());
    EXPECT_NEAR(std::hypot(from_axis - 2, p.y()), 0.5, 1e-12);
  }
  expect_uv_per_vertex_in_unit_square(torus);
}

// Pappus: the torus encloses 2π²Rr². The inscribed polygonal torus falls short by a
// second-order error, so doubling both segment counts cuts the error about fourfold.
TEST(ProceduralSurfaces, TorusVolumeConvergesToPappus) {
  const Real R = 1.5, r = 0.4;
  const Real exact = 2 * pi * pi * R * r * r;
  Real previous_error = 0;
  for (int segments = 12; segments <= 96; segments *= 2) {
    const TriangleMesh torus = make_torus_surface(R, r, segments, segments / 2);
    const Real error = exact - test::enclosed_volume(torus.positions, torus.triangles);
    EXPECT_GT(error, 0) << segments;  // inscribed
    if (previous_error > 0) {
      EXPECT_GT(previous_error / error, 3.5) << segments;
    }
    previous_error = error;
  }
  EXPECT_LT(previous_error / exact, 5e-3);
}

TEST(ProceduralSurfaces, SphereIsAClosedOutwardIcosphere) {
  for (int level = 0; level <= 3; ++level) {
    const TriangleMesh sphere = make_sphere_surface(0.7, level);
    const auto faces = 20 * static_cast<std::size_t>(std::pow(4, level));
    EXPECT_EQ(sphere.positions.size(), faces / 2 + 2);
    EXPECT_EQ(sphere.triangles.size(), faces);
    EXPECT_TRUE(test::is_closed_and_oriented(sphere.triangles));
    EXPECT_EQ(test::euler_characteristic(sphere.triangles), 2);
    EXPECT_GT(test::enclosed_volume(sphere.positions, sphere.triangles), 0);
    for (const Vec3& p : sphere.positions) EXPECT_NEAR(p.norm(), 0.7, 1e-12);
    // no sliver: the smallest triangle keeps a good part of the largest one's area
    Real smallest = INFINITY, largest = 0;
    for (const Triangle& t : sphere.triangles) {
      const Real area = test::surface_area(sphere.positions, std::span(&t, 1));
      smallest = std::min(smallest, area);
      largest = std::max(largest, area);
    }
    EXPECT_GT(smallest / largest, 0.5) << level;
    expect_uv_per_vertex_in_unit_square(sphere);
  }
}

// Each subdivision halves the edges, so the inscribed area's shortfall drops about fourfold.
TEST(ProceduralSurfaces, SphereAreaConvergesTo4PiRSquared) {
  const Real r = 1.3;
  const Real exact = 4 * pi * r * r;
  Real previous_error = 0;
  for (int level = 1; level <= 5; ++level) {
    const TriangleMesh sphere = make_sphere_surface(r, level);
    const Real error = exact - test::surface_area(sphere.positions, sphere.triangles);
    EXPECT_GT(error, 0) << level;
    if (previous_error > 0) {
      EXPECT_GT(previous_error / error, 3.5) << level;
    }
    previous_error = error;
  }
  EXPECT_LT(previous_error / exact, 1e-3);
}

}  // namespace
}  // namespace felt
