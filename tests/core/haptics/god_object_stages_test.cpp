// The god-object's stages one at a time, each against what it promises: the candidates' cheap
// bounds never exceed the brute-force distance, a placement moves rigidly with its triangle, the
// carry moves the proxy with a translated sheet, the constrained move stops a skin off a plane,
// and friction holds the proxy inside the static cone.

#include <cmath>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/geometry/triangle_geometry.hpp"
#include "core/haptics/candidate_triangles.hpp"
#include "core/haptics/constrained_move.hpp"
#include "core/haptics/god_object_fixtures.hpp"
#include "core/haptics/proxy_anchor.hpp"
#include "core/haptics/proxy_friction.hpp"
#include "core/haptics/proxy_skin.hpp"
#include "core/haptics/surface_carry.hpp"
#include "core/haptics/triangle_placement.hpp"

namespace felt {
namespace {

using namespace felt::test;  // the god-object fixtures and expect_vec_near

/// A wavy 6 x 6 sheet: triangles in many orientations.
Sheet wavy_sheet() {
  Grid g = grid(6, 1.0, 0);
  for (Vec3& p : g.positions) p.z() = 0.2 * std::sin(5 * p.x()) * std::cos(3 * p.y());
  return Sheet(0, g.positions, g.triangles);
}

TEST(CandidateTriangles, TheCheapBoundsNeverExceedTheDistance) {
  const Sheet sheet = wavy_sheet();
  const HapticSurface surface = surface_of({&sheet});
  CandidateTriangles candidates;
  candidates.forget();
  candidates.gather(surface, segment_box(Vec3::Zero(), Vec3::Zero(), 10));
  ASSERT_EQ(candidates.size(), sheet.triangles.size());
  std::mt19937 random(7);
  std::uniform_real_distribution<Real> coordinate(-0.8, 0.8);
  for (int n = 0; n < 300; ++n) {
    const Vec3 p0(coordinate(random), coordinate(random), coordinate(random));
    const Vec3 p1(coordinate(random), coordinate(random), coordinate(random));
    const Real length = (p1 - p0).norm();
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const TriangleCorners& t = candidates.corners(i);
      const Real distance = (p0 - closest_point_on_triangle(p0, t.a, t.b, t.c).point).norm();
      EXPECT_LE(candidates.distance_bound(i, p0), distance + 1e-12);
      // the segment's nearest approach, sampled finely: never within a reach it was ruled out of
      Real nearest = distance;
      for (int k = 1; k <= 100; ++k) {
        const Vec3 p = p0 + (p1 - p0) * (k / 100.0);
        nearest = std::min(nearest, (p - closest_point_on_triangle(p, t.a, t.b, t.c).point).norm());
      }
      if (candidates.out_of_reach(i, p0, p1, length, 0.05)) {
        EXPECT_GT(nearest, 0.05 - 1e-12);
      }
    }
  }
}

TEST(TrianglePlacement, APlacementMovesRigidlyWithItsTriangle) {
  const TriangleCorners t{Vec3(0, 0, 0), Vec3(0.1, 0, 0.02), Vec3(0.03, 0.08, -0.01)};
  const Mat3 turn = Eigen::AngleAxis<Real>(0.7, Vec3(1, 2, -1).normalized()).toRotationMatrix();
  const Vec3 shift(0.3, -0.2, 0.5);
  const auto moved = [&](const Vec3& p) { return Vec3(turn * p + shift); };
  const TriangleCorners t2{moved(t.a), moved(t.b), moved(t.c)};
  for (const Vec3& p : {Vec3(0.04, 0.02, 0.03), Vec3(-0.05, 0.1, -0.02), Vec3(0.2, 0.2, 0.0)}) {
    const std::optional<Placement> placement = place(t, p);
    ASSERT_TRUE(placement);
    const std::optional<Vec3> there = position_of(t2, *placement);
    ASSERT_TRUE(there);
    expect_vec_near(*there, moved(p), 1e-14);
  }
  // a triangle without area has no frame to place against
  EXPECT_FALSE(place({Vec3::Zero(), Vec3(1, 0, 0), Vec3(2, 0, 0)}, Vec3(0, 1, 0)));
}

TEST(SurfaceCarry, ASheetMovedSidewaysAndUpCarriesItsProxyAlong) {
  Grid g = grid(4, 1.0, 0);
  Sheet sheet(0, g.positions, g.triangles);
  const Vec3 rest(0.1, 0.05, 0.01 + kProxySkin);
  const HapticSurface first = surface_of({&sheet}, 1);
  CandidateTriangles candidates;
  candidates.forget();
  SurfaceCarry carry;
  carry.follow(first);
  const Touch touch = find_touch(first, candidates, rest, 0.01, 0);
  ASSERT_TRUE(touch.anchor);
  carry.remember(first);

  const Vec3 shift(0.02, -0.01, 0.03);
  sheet.advance(shifted(g.positions, shift));
  const HapticSurface second = surface_of({&sheet}, 2);
  candidates.forget();
  carry.follow(second);
  EXPECT_NEAR(carry.margin(), shift.norm(), 1e-11);
  expect_vec_near(carry.carry(second, candidates, rest, touch.anchor), rest + shift, 1e-12);
}

TEST(ConstrainedMove, APushThroughAPlaneStopsASkinOffItHeldByOnePlane) {
  const Grid g = grid(2, 1.0, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  CandidateTriangles candidates;
  candidates.forget();
  const Real radius = 0.01;
  const ConstrainedMove move =
      move_proxy(surface, candidates, Vec3(0, 0, 0.05), Vec3(0.02, 0.01, -0.03), radius);
  EXPECT_EQ(move.constraints, 1);
  // the goal projected onto the plane's free side: radius and skin above, straight over it
  expect_vec_near(move.position, Vec3(0.02, 0.01, radius + kProxySkin), 1e-9);
  ASSERT_TRUE(move.first_stop);
  EXPECT_NEAR(move.first_stop->z(), radius + kProxySkin, 1e-9);
}

TEST(ProxyFriction, TheProxyStaysWhereItStuckInsideTheStaticConeAndSlipsOutside) {
  const Grid g = grid(2, 1.0, 0);
  const Sheet plane(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&plane});
  CandidateTriangles candidates;
  candidates.forget();
  ProxySettings settings = plain_settings(0);
  settings.static_friction = 0.5;
  settings.dynamic_friction = 0.4;
  const Vec3 stuck(0, 0, kProxySkin);
  // 1 cm deep: the static cone's radius is 5 mm
  const auto slide_to = [&](Real x) {
    const ConstrainedMove frictionless{Vec3(x, 0, kProxySkin), 1, std::nullopt};
    return hold_by_friction(surface, candidates, settings, frictionless, stuck, Vec3(x, 0, -0.01),
                            0, true, false);
  };
  const FrictionStop inside = slide_to(0.004);
  EXPECT_FALSE(inside.slipping);
  expect_vec_near(inside.rest, stuck, 0);
  const FrictionStop outside = slide_to(0.008);
  EXPECT_TRUE(outside.slipping);
  // dragged to the dynamic cone: 0.4 · 1 cm behind the device
  expect_vec_near(outside.rest, Vec3(0.008 - 0.004, 0, kProxySkin), 1e-9);
}

}  // namespace
}  // namespace felt
