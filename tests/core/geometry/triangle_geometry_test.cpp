// closest_point_on_triangle against hand-computed Voronoi-region answers and a brute-force
// search over a dense barycentric sampling of the triangle.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/geometry/triangle_geometry.hpp"

namespace felt {
namespace {

using test::expect_vec_near;

// The result must be a point of the triangle, described by its own barycentric coordinates.
void expect_consistent(const ClosestPoint& r, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3& w = r.barycentric;
  EXPECT_GE(w.x(), -1e-12);
  EXPECT_GE(w.y(), -1e-12);
  EXPECT_GE(w.z(), -1e-12);
  EXPECT_NEAR(w.sum(), 1.0, 1e-12);
  const Vec3 rebuilt = w.x() * a + w.y() * b + w.z() * c;
  const Real scale = std::max({a.norm(), b.norm(), c.norm(), Real{1}});
  EXPECT_LE((rebuilt - r.point).norm(), 1e-12 * scale);
}

// Brute force: the nearest of the points i/n a + j/n b + (n-i-j)/n c.
Real sampled_min_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, int n) {
  Real best = std::numeric_limits<Real>::infinity();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const Real u = static_cast<Real>(i) / n;
      const Real v = static_cast<Real>(j) / n;
      const Vec3 q = u * a + v * b + (1 - u - v) * c;
      best = std::min(best, (p - q).squaredNorm());
    }
  }
  return std::sqrt(best);
}

// Nearest point on segment [a, b], for the degenerate-triangle reference.
Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const Real len_sq = ab.squaredNorm();
  if (len_sq == 0) return a;
  const Real t = std::clamp((p - a).dot(ab) / len_sq, Real{0}, Real{1});
  return a + t * ab;
}

// Right triangle in z = 0 with legs along x and y: every region's answer is easy by hand.
const Vec3 kA(0, 0, 0);
const Vec3 kB(1, 0, 0);
const Vec3 kC(0, 1, 0);

struct RegionCase {
  const char* region;
  Vec3 p;
  Vec3 point;
  Vec3 barycentric;
};

TEST(TriangleGeometry, EachVoronoiRegionGivesTheExactAnswer) {
  const RegionCase cases[] = {
      {"vertex a", Vec3(-1, -1, 0.5), Vec3(0, 0, 0), Vec3(1, 0, 0)},
      {"vertex b", Vec3(2, -0.5, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
      {"vertex c", Vec3(-0.5, 2, 1), Vec3(0, 1, 0), Vec3(0, 0, 1)},
      {"edge ab", Vec3(0.25, -1, 0.3), Vec3(0.25, 0, 0), Vec3(0.75, 0.25, 0)},
      {"edge ac", Vec3(-2, 0.5, -1), Vec3(0, 0.5, 0), Vec3(0.5, 0, 0.5)},
      // (1, 1) projects onto bc at its midpoint, perpendicular to bc
      {"edge bc", Vec3(1, 1, 0.7), Vec3(0.5, 0.5, 0), Vec3(0, 0.5, 0.5)},
      {"face above", Vec3(0.25, 0.25, 3), Vec3(0.25, 0.25, 0), Vec3(0.5, 0.25, 0.25)},
      {"face below", Vec3(0.125, 0.5, -2), Vec3(0.125, 0.5, 0), Vec3(0.375, 0.125, 0.5)},
      {"face on plane", Vec3(0.2, 0.3, 0), Vec3(0.2, 0.3, 0), Vec3(0.5, 0.2, 0.3)},
      {"on vertex b", Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
  };
  for (const RegionCase& k : cases) {
    SCOPED_TRACE(k.region);
    const ClosestPoint r = closest_point_on_triangle(k.p, kA, kB, kC);
    expect_vec_near(r.point, k.point, 1e-15);
    expect_vec_near(r.barycentric, k.barycentric, 1e-15);
    expect_consistent(r, kA, kB, kC);
  }
}

TEST(TriangleGeometry, RegionBoundariesAgreeFromBothSides) {
  // just inside and just outside each edge the answer must be (nearly) the same point
  const Real e = 1e-9;
  const std::array<std::array<Vec3, 2>, 3> pairs = {{
      {Vec3(0.5, e, 1), Vec3(0.5, -e, 1)},                     // edge ab
      {Vec3(e, 0.5, 1), Vec3(-e, 0.5, 1)},                     // edge ac
      {Vec3(0.5 - e, 0.5 - e, 1), Vec3(0.5 + e, 0.5 + e, 1)},  // edge bc
  }};
  for (const auto& pair : pairs) {
    const Vec3 in = closest_point_on_triangle(pair[0], kA, kB, kC).point;
    const Vec3 out = closest_point_on_triangle(pair[1], kA, kB, kC).point;
    EXPECT_LE((in - out).norm(), 4 * e);
  }
}

TEST(TriangleGeometry, MatchesDenseSamplingOnRandomTriangles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> coord(-1, 1);
  std::uniform_real_distribution<Real> query(-2, 2);
  constexpr int kSamples = 200;
  for (int trial = 0; trial < 150; ++trial) {
    const Vec3 a(coord(rng), coord(rng), coord(rng));
    const Vec3 b(coord(rng), coord(rng), coord(rng));
    const Vec3 c(coord(rng), coord(rng), coord(rng));
    const Real longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    for (int q = 0; q < 4; ++q) {
      // half the queries close to the plane, where the face region is most contested
      Vec3 p(query(rng), query(rng), query(rng));
      if (q % 2 == 1) {
        const Vec3 n = (b - a).cross(c - a).normalized();
        p -= (p - a).dot(n) * n * 0.99;
      }
      SCOPED_TRACE(testing::Message() << "trial " << trial << " query " << q);
      const ClosestPoint r = closest_point_on_triangle(p, a, b, c);
      expect_consistent(r, a, b, c);
      const Real got = (p - r.point).norm();
      const Real sampled = sampled_min_distance(p, a, b, c, kSamples);
      // no sample may be closer than the exact answer ...
      EXPECT_LE(got, sampled + 1e-12);
      // ... and the answer cannot beat the sampling by more than the grid spacing
      EXPECT_GE(got, sampled - longest / kSamples);
    }
  }
}

TEST(TriangleGeometry, VertexOrderDoesNotChangeThePoint) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> coord(-1, 1);
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 a(coord(rng), coord(rng), coord(rng));
    const Vec3 b(coord(rng), coord(rng), coord(rng));
    const Vec3 c(coord(rng), coord(rng), coord(rng));
    const Vec3 p(2 * coord(rng), 2 * coord(rng), 2 * coord(rng));
    const Vec3 p0 = closest_point_on_triangle(p, a, b, c).point;
    // the nearest point of a non-degenerate triangle is unique
    EXPECT_LE((closest_point_on_triangle(p, b, c, a).point - p0).norm(), 1e-9);
    EXPECT_LE((closest_point_on_triangle(p, c, b, a).point - p0).norm(), 1e-9);
  }
}

TEST(TriangleGeometry, ExactlyCollinearTriangleGivesNearestPointOfItsSpan) {
  // coordinates are small dyadic numbers, so every product in the algorithm is exact
  const Vec3 v0(0, 0, 0), v1(1, 0, 0), v2(2, 0, 0);
  const std::array<std::array<Vec3, 3>, 6> orders = {
      {{v0, v1, v2}, {v0, v2, v1}, {v1, v0, v2}, {v1, v2, v0}, {v2, v0, v1}, {v2, v1, v0}}};
  const Vec3 queries[] = {Vec3(-0.5, 1, 0), Vec3(0.25, 1, 0.5), Vec3(0.75, -1, 0),
                          Vec3(1.5, 0, 1),  Vec3(1.75, 2, -3),  Vec3(3, 0.5, 0.5),
                          Vec3(1, 0, 0),    Vec3(0.5, 0, 0)};
  for (const auto& t : orders) {
    for (const Vec3& p : queries) {
      SCOPED_TRACE(testing::Message() << "a " << t[0].x() << " b " << t[1].x() << " c " << t[2].x()
                                      << " p " << p.transpose());
      const ClosestPoint r = closest_point_on_triangle(p, t[0], t[1], t[2]);
      ASSERT_TRUE(r.point.allFinite());
      ASSERT_TRUE(r.barycentric.allFinite());
      const Real nearest_vertex =
          std::min({(p - t[0]).norm(), (p - t[1]).norm(), (p - t[2]).norm()});
      EXPECT_LE((p - r.point).norm(), nearest_vertex + 1e-12);
      // the triangle is the segment [0, 2] of the x axis
      expect_vec_near(r.point, Vec3(std::clamp(p.x(), Real{0}, Real{2}), 0, 0), 1e-12);
      expect_consistent(r, t[0], t[1], t[2]);
    }
  }
}

TEST(TriangleGeometry, PointAndSegmentTrianglesAreHandled) {
  const Vec3 q(0.5, -0.25, 2);
  const Vec3 p(3, 1, -1);
  const ClosestPoint single = closest_point_on_triangle(p, q, q, q);
  expect_vec_near(single.point, q, 0);

  // c coincides with a or with b: the triangle is the segment [a, b]
  const Vec3 a(0, 0, 0), b(0, 4, 0);
  for (const Vec3& query : {Vec3(1, 2, 0), Vec3(-1, -3, 2), Vec3(0.5, 6, 0)}) {
    SCOPED_TRACE(testing::Message() << "p " << query.transpose());
    for (const ClosestPoint& r :
         {closest_point_on_triangle(query, a, b, a), closest_point_on_triangle(query, a, b, b)}) {
      ASSERT_TRUE(r.point.allFinite());
      expect_vec_near(r.point, closest_on_segment(query, a, b), 1e-12);
    }
  }
}

// Regression: With a == b the edge-ab branch is taken whenever p projects past a
// toward c (d1 = d3 = 0, so vc = 0), and computes v = d1 / (d1 - d3) = 0 / 0: the point is NaN.
TEST(TriangleGeometry, FirstTwoVerticesCoincidingGiveTheSegmentPoint) {
  const Vec3 a(0, 0, 0), c(0, 4, 0);
  const Vec3 p(1, 2, 0);
  const ClosestPoint r = closest_point_on_triangle(p, a, a, c);
  ASSERT_TRUE(r.point.allFinite());
  expect_vec_near(r.point, Vec3(0, 2, 0), 1e-12);
}

// Regression: For a triangle that is collinear up to rounding, va, vb and vc come
// out as tiny positive noise (~1e-17) instead of 0, no edge region claims the point, and the
// face branch divides noise by noise: it returns a point strictly inside the segment that is
// farther from p than a vertex is (here 0.7257 against 0.6824 for vertex b).
TEST(TriangleGeometry, RoundedCollinearTriangleIsNoFartherThanItsVertices) {
  const Vec3 a(-0.87006576666761093, 0.22895326222528806, -0.070355526556330872);
  const Vec3 b(-0.22101550662521219, -0.036809015097887747, -0.13302743612529755);
  const Vec3 c(0.7527720166431956, -0.43553929184995538, -0.22705578393564893);
  const Vec3 p(-0.34487321711700814, -0.6867717121813699, -0.29983221980630126);
  const ClosestPoint r = closest_point_on_triangle(p, a, b, c);
  const Vec3 want = [&] {
    Vec3 best = closest_on_segment(p, a, b);
    for (const Vec3& s : {closest_on_segment(p, b, c), closest_on_segment(p, a, c)}) {
      if ((p - s).norm() < (p - best).norm()) best = s;
    }
    return best;
  }();
  EXPECT_LE((p - r.point).norm(), (p - want).norm() + 1e-12);
  EXPECT_LE((p - r.point).norm(), (p - b).norm() + 1e-12);
}

}  // namespace
}  // namespace felt
