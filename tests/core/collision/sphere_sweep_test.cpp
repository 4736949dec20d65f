// sweep_sphere_triangle against hand-computed first contacts (face, edge capsule, corner
// sphere) and against a fine sampling of the path; point_passes_moving_triangle against
// hand-computed crossings and a fine sampling of the signed volume.

#include <cmath>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/collision/sphere_sweep.hpp"
#include "core/geometry/triangle_geometry.hpp"

namespace felt {
namespace {

using test::expect_vec_near;

// The right triangle with its right angle at the origin, in the z = 0 plane.
const Vec3 kA(0, 0, 0);
const Vec3 kB(1, 0, 0);
const Vec3 kC(0, 1, 0);

Real distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return (p - closest_point_on_triangle(p, a, b, c).point).norm();
}

TEST(SphereSweep, FallingOntoTheFaceStopsOneRadiusAbove) {
  const auto hit = sweep_sphere_triangle(Vec3(0.2, 0.3, 1), Vec3(0.2, 0.3, -1), 0.1, kA, kB, kC);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 0.45, 1e-15);
  expect_vec_near(hit->normal, Vec3(0, 0, 1), 1e-15);
  expect_vec_near(hit->barycentric, Vec3(0.5, 0.2, 0.3), 1e-15);
}

TEST(SphereSweep, RisingFromBelowTouchesTheUnderside) {
  const auto hit = sweep_sphere_triangle(Vec3(0.2, 0.3, -1), Vec3(0.2, 0.3, 0.5), 0.1, kA, kB, kC);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 0.9 / 1.5, 1e-15);
  expect_vec_near(hit->normal, Vec3(0, 0, -1), 1e-15);
}

TEST(SphereSweep, APointStopsOnTheFace) {
  const auto hit = sweep_sphere_triangle(Vec3(0.2, 0.3, 1), Vec3(0.2, 0.3, -3), 0, kA, kB, kC);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 0.25, 1e-15);
  expect_vec_near(hit->normal, Vec3(0, 0, 1), 1e-15);
  expect_vec_near(hit->barycentric, Vec3(0.5, 0.2, 0.3), 1e-15);
}

TEST(SphereSweep, PassingBesideAnEdgeTouchesItsCapsule) {
  // 5 cm beside edge ab: contact when the centre is 0.1 from the edge's line
  const auto hit =
      sweep_sphere_triangle(Vec3(0.5, -0.05, 1), Vec3(0.5, -0.05, -1), 0.1, kA, kB, kC);
  ASSERT_TRUE(hit.has_value());
  const Real z = std::sqrt(0.1 * 0.1 - 0.05 * 0.05);
  EXPECT_NEAR(hit->t, (1 - z) / 2, 1e-14);
  expect_vec_near(hit->normal, Vec3(0, -0.05, z) / 0.1, 1e-13);
  expect_vec_near(hit->barycentric, Vec3(0.5, 0.5, 0), 1e-14);
}

TEST(SphereSweep, ComingAtACornerTouchesItsSphere) {
  // along the diagonal away from the triangle, toward corner a
  const Vec3 away = Vec3(-1, -1, 1).normalized();
  const auto hit = sweep_sphere_triangle(away, -away, 0.2, kA, kB, kC);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 0.4, 1e-14);  // centre 0.2 from a after 0.8 of the 2-long path
  expect_vec_near(hit->normal, away, 1e-14);
  expect_vec_near(hit->barycentric, Vec3(1, 0, 0), 0);
}

TEST(SphereSweep, MissingPathGivesNoHit) {
  EXPECT_FALSE(sweep_sphere_triangle(Vec3(2, 2, 1), Vec3(2, 2, -1), 0.1, kA, kB, kC));
  EXPECT_FALSE(sweep_sphere_triangle(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 0.2), 0.1, kA, kB, kC));
  EXPECT_FALSE(sweep_sphere_triangle(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 2), 0.1, kA, kB, kC));
}

TEST(SphereSweep, AlreadyWithinReachBlocksOnlyInwardMotion) {
  const Vec3 start(0.2, 0.2, 0.05);  // 0.05 above the face, radius 0.1
  const auto inward = sweep_sphere_triangle(start, Vec3(0.3, 0.2, 0.04), 0.1, kA, kB, kC);
  ASSERT_TRUE(inward.has_value());
  EXPECT_EQ(inward->t, 0);
  expect_vec_near(inward->normal, Vec3(0, 0, 1), 1e-15);
  EXPECT_FALSE(sweep_sphere_triangle(start, Vec3(0.3, 0.2, 0.06), 0.1, kA, kB, kC));
  EXPECT_FALSE(sweep_sphere_triangle(start, Vec3(0.3, 0.25, 0.05), 0.1, kA, kB, kC));
  // below the face, moving up: inward from that side
  const auto below =
      sweep_sphere_triangle(Vec3(0.2, 0.2, -0.05), Vec3(0.2, 0.2, 0), 0.1, kA, kB, kC);
  ASSERT_TRUE(below.has_value());
  EXPECT_EQ(below->t, 0);
  expect_vec_near(below->normal, Vec3(0, 0, -1), 1e-15);
}

TEST(SphereSweep, ATriangleWithoutAreaIsItsEdges) {
  const Vec3 a(0, 0, 0);
  const Vec3 b(1, 0, 0);
  const Vec3 c(2, 0, 0);
  const auto hit = sweep_sphere_triangle(Vec3(0.5, 0, 1), Vec3(0.5, 0, -1), 0.1, a, b, c);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 0.45, 1e-15);
  expect_vec_near(hit->normal, Vec3(0, 0, 1), 1e-15);
  EXPECT_NEAR(hit->barycentric.sum(), 1, 1e-15);
  expect_vec_near(hit->barycentric.x() * a + hit->barycentric.y() * b + hit->barycentric.z() * c,
                  Vec3(0.5, 0, 0), 1e-15);
  // all three corners in one place: a sphere
  const auto point = sweep_sphere_triangle(Vec3(0, 0, 1), Vec3(0, 0, -1), 0.1, a, a, a);
  ASSERT_TRUE(point.has_value());
  EXPECT_NEAR(point->t, 0.45, 1e-15);
  // a point cannot hit something without area
  EXPECT_FALSE(sweep_sphere_triangle(Vec3(0.5, 0, 1), Vec3(0.5, 0, -1), 0, a, b, c));
}

TEST(SphereSweep, NonFiniteInputGivesNoHit) {
  const Real nan = std::nan("");
  EXPECT_FALSE(
      sweep_sphere_triangle(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -1), 0.1, kA, kB, Vec3(nan, 0, 0)));
  EXPECT_FALSE(sweep_sphere_triangle(Vec3(nan, 0.2, 1), Vec3(0.2, 0.2, -1), 0.1, kA, kB, kC));
}

// A point through the shared edge of two triangles must hit one of them, whatever rounding
// does on the edge (the thesis's proxy fell through such cracks).
TEST(SphereSweep, APointThroughASharedEdgeHitsOneSide) {
  const Vec3 a(0.1, 0.3, 0.7);
  const Vec3 b(1.3, 0.2, 0.9);
  const Vec3 c(0.2, 1.1, 0.5);
  const Vec3 d(1.4, 1.3, 0.8);  // triangles (a, b, c) and (b, d, c) share edge bc
  const Vec3 normal = (b - a).cross(c - a).normalized();
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> unit(0, 1);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 on_edge = b + unit(rng) * (c - b);
    const Vec3 tilt = 0.3 * Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    const Vec3 direction = normal + tilt;
    const Vec3 p0 = on_edge + 0.37 * direction;
    const Vec3 p1 = on_edge - 0.61 * direction;
    const bool hit = sweep_sphere_triangle(p0, p1, 0, a, b, c).has_value() ||
                     sweep_sphere_triangle(p0, p1, 0, b, d, c).has_value();
    EXPECT_TRUE(hit) << "crossing " << i << " slipped through the edge";
  }
}

// The sweep against a sampling of the path every 1/n: the first contact comes no later than
// the first sample within reach and no earlier than the last sample out of reach before it,
// and the reported contact is where the centre is one radius from the triangle.
TEST(SphereSweep, MatchesAFineSamplingOfThePath) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> coord(-1, 1);
  const auto random_point = [&] { return Vec3(coord(rng), coord(rng), coord(rng)); };
  constexpr int kSamples = 20000;
  int hits = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Vec3 a = random_point();
    const Vec3 b = random_point();
    // every fourth triangle is (nearly) without area
    const Vec3 c =
        trial % 4 == 0 ? Vec3(a + 0.7 * (b - a) + 1e-12 * random_point()) : random_point();
    const Real radius = std::array<Real, 3>{0.05, 0.2, 0.5}[trial % 3];
    // half the paths aim through the triangle, so that contacts are common
    const Vec3 p0 = 2.5 * random_point();
    const Vec3 p1 = trial % 2 == 0 ? Vec3(2.5 * random_point())
                                   : Vec3((a + b + c) / 3 - 0.8 * p0 + 0.5 * random_point());
    if (distance_to_triangle(p0, a, b, c) <= radius) continue;  // tested elsewhere
    std::optional<Real> first_inside;
    for (int i = 0; i <= kSamples; ++i) {
      const Real t = static_cast<Real>(i) / kSamples;
      if (distance_to_triangle(p0 + t * (p1 - p0), a, b, c) <= radius) {
        first_inside = t;
        break;
      }
    }
    const auto hit = sweep_sphere_triangle(p0, p1, radius, a, b, c);
    if (first_inside) {
      ASSERT_TRUE(hit.has_value()) << "trial " << trial;
      EXPECT_LE(hit->t, *first_inside + 1e-12) << "trial " << trial;
      EXPECT_GE(hit->t, *first_inside - 1.0 / kSamples - 1e-12) << "trial " << trial;
    }
    if (!hit) continue;
    ++hits;
    const Vec3 centre = p0 + hit->t * (p1 - p0);
    const ClosestPoint nearest = closest_point_on_triangle(centre, a, b, c);
    EXPECT_NEAR((centre - nearest.point).norm(), radius, 1e-9) << "trial " << trial;
    const Vec3 touched =
        hit->barycentric.x() * a + hit->barycentric.y() * b + hit->barycentric.z() * c;
    EXPECT_LE((touched - nearest.point).norm(), 1e-6) << "trial " << trial;
    EXPECT_LE((centre - radius * hit->normal - touched).norm(), 1e-6) << "trial " << trial;
    EXPECT_LT((p1 - p0).dot(hit->normal), 0) << "trial " << trial;
  }
  EXPECT_GT(hits, 100);  // the sample must exercise contacts, not only misses
}

// A point (radius 0) crosses a triangle where its signed distance changes sign inside it.
TEST(SphereSweep, APointMatchesTheSegmentTriangleCrossing) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<Real> coord(-1, 1);
  const auto random_point = [&] { return Vec3(coord(rng), coord(rng), coord(rng)); };
  int crossings = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 a = random_point();
    const Vec3 b = random_point();
    const Vec3 c = random_point();
    const Vec3 p0 = 1.5 * random_point();
    const Vec3 p1 = 1.5 * random_point();
    const Vec3 normal = (b - a).cross(c - a).normalized();
    const Real h0 = normal.dot(p0 - a);
    const Real h1 = normal.dot(p1 - a);
    const auto hit = sweep_sphere_triangle(p0, p1, 0, a, b, c);
    if (h0 * h1 >= 0) {
      EXPECT_FALSE(hit.has_value()) << "trial " << trial;
      continue;
    }
    const Real t = h0 / (h0 - h1);
    const Vec3 through = p0 + t * (p1 - p0);
    const ClosestPoint nearest = closest_point_on_triangle(through, a, b, c);
    if ((through - nearest.point).norm() > 1e-6) {
      EXPECT_FALSE(hit.has_value()) << "trial " << trial;
    } else if (nearest.barycentric.minCoeff() > 1e-6) {
      ASSERT_TRUE(hit.has_value()) << "trial " << trial;
      EXPECT_NEAR(hit->t, t, 1e-9);
      EXPECT_GT(hit->normal.dot(p0 - p1), 0);
      ++crossings;
    }
  }
  EXPECT_GT(crossings, 100);
}

// ---- point against a moving triangle

TriangleCorners moved(const TriangleCorners& c, const Vec3& by) {
  return {c.a + by, c.b + by, c.c + by};
}

const TriangleCorners kStill{kA, kB, kC};

TEST(PointPassesMovingTriangle, AStaticTriangleIsCrossedWhereThePathMeetsIt) {
  const auto s =
      point_passes_moving_triangle(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -3), kStill, kStill);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(*s, 0.25, 1e-12);
  EXPECT_FALSE(
      point_passes_moving_triangle(Vec3(2, 2, 1), Vec3(2, 2, -3), kStill, kStill).has_value());
}

TEST(PointPassesMovingTriangle, ATriangleSweepingOverAStillPointPassesIt) {
  const Vec3 point(0.2, 0.2, 0);
  const auto s = point_passes_moving_triangle(point, point, moved(kStill, Vec3(0, 0, 1)),
                                              moved(kStill, Vec3(0, 0, -3)));
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(*s, 0.25, 1e-12);
}

TEST(PointPassesMovingTriangle, MovingTogetherNeverPasses) {
  // the point 1 mm above the triangle, both moving 5 cm in the same direction
  const Vec3 by(0.03, -0.01, 0.04);
  EXPECT_FALSE(point_passes_moving_triangle(Vec3(0.2, 0.2, 1e-3), Vec3(0.2, 0.2, 1e-3) + by, kStill,
                                            moved(kStill, by))
                   .has_value());
}

TEST(PointPassesMovingTriangle, HeadOnBothMovingMeetsInTheMiddle) {
  // point from z = 1 down to z = -1, triangle from z = -1 up to z = 1: they meet at s = 0.5
  const auto s =
      point_passes_moving_triangle(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -1),
                                   moved(kStill, Vec3(0, 0, -1)), moved(kStill, Vec3(0, 0, 1)));
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(*s, 0.5, 1e-12);
}

TEST(PointPassesMovingTriangle, AHingedTriangleSwingingThroughThePointPassesIt) {
  // corner c swings from z = +1 to z = -1 about edge ab: the plane passes the point (0.1, 0.5,
  // 0) when c is at z = 0, halfway; the point lies inside the triangle then
  const TriangleCorners up{kA, kB, Vec3(0, 1, 1)};
  const TriangleCorners down{kA, kB, Vec3(0, 1, -1)};
  const auto s = point_passes_moving_triangle(Vec3(0.1, 0.5, 0), Vec3(0.1, 0.5, 0), up, down);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(*s, 0.5, 1e-12);
}

TEST(PointPassesMovingTriangle, EndingOnTheTriangleCountsStartingOnItDoesNot) {
  const auto ends =
      point_passes_moving_triangle(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 0), kStill, kStill);
  ASSERT_TRUE(ends.has_value());
  EXPECT_EQ(*ends, 1);
  EXPECT_FALSE(point_passes_moving_triangle(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.2, 1), kStill, kStill));
}

TEST(PointPassesMovingTriangle, ATriangleWithoutAreaIsNeverPassed) {
  const TriangleCorners line{kA, kB, Vec3(2, 0, 0)};
  EXPECT_FALSE(point_passes_moving_triangle(Vec3(0.5, 0, 1), Vec3(0.5, 0, -1), line, line));
}

// Against a sampling of the signed volume every 1/n: a sign change at which the point is well
// inside the triangle must be found no later than that sample, and whatever is reported must
// be a real crossing: the four points coplanar with the point inside.
TEST(PointPassesMovingTriangle, MatchesAFineSamplingOfTheMotion) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<Real> coord(-1, 1);
  const auto random_point = [&] { return Vec3(coord(rng), coord(rng), coord(rng)); };
  constexpr int kSamples = 4000;
  const auto lerp = [](const Vec3& x0, const Vec3& x1, Real s) { return (1 - s) * x0 + s * x1; };
  int found = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const TriangleCorners from{random_point(), random_point(), random_point()};
    const TriangleCorners to{from.a + 0.8 * random_point(), from.b + 0.8 * random_point(),
                             from.c + 0.8 * random_point()};
    // the point goes from one side of the triangle's centre to the other, more or less
    const Vec3 offset = random_point();
    const Vec3 p0 = (from.a + from.b + from.c) / 3 + offset;
    const Vec3 p1 = (to.a + to.b + to.c) / 3 - offset + 0.5 * random_point();
    const auto state = [&](Real s) {
      const Vec3 a = lerp(from.a, to.a, s);
      const Vec3 b = lerp(from.b, to.b, s);
      const Vec3 c = lerp(from.c, to.c, s);
      const Vec3 p = lerp(p0, p1, s);
      const Vec3 normal = (b - a).cross(c - a);
      const Vec3 onto = p - normal * (normal.dot(p - a) / normal.squaredNorm());
      const ClosestPoint nearest = closest_point_on_triangle(onto, a, b, c);
      return std::pair<Real, Real>{normal.dot(p - a), (onto - nearest.point).norm()};
    };
    std::optional<Real> sampled;
    Real previous = state(0).first;
    for (int i = 1; i <= kSamples && !sampled; ++i) {
      const Real s = static_cast<Real>(i) / kSamples;
      const auto [volume, outside] = state(s);
      // well inside at both samples around the change, so the crossing is inside too
      if (volume * previous < 0 && outside == 0 && state(s - 1.0 / kSamples).second == 0) {
        sampled = s;
      }
      previous = volume;
    }
    const auto s = point_passes_moving_triangle(p0, p1, from, to);
    if (sampled) {
      ASSERT_TRUE(s.has_value()) << "trial " << trial;
      EXPECT_LE(*s, *sampled + 1e-12) << "trial " << trial;
    }
    if (s) {
      ++found;
      const auto [volume, outside] = state(*s);
      EXPECT_LE(outside, 1e-6) << "trial " << trial;
      const Vec3 a = lerp(from.a, to.a, *s);
      const Vec3 normal = (lerp(from.b, to.b, *s) - a).cross(lerp(from.c, to.c, *s) - a);
      EXPECT_LE(std::abs(normal.normalized().dot(lerp(p0, p1, *s) - a)), 1e-9) << "trial " << trial;
    }
  }
  EXPECT_GT(found, 150);
}

}  // namespace
}  // namespace felt
