#include "core/collision/spatial_hash.hpp"

#include <map>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace felt {
namespace {

bool is_prime_by_trial(std::size_t n) {
  if (n < 2) return false;
  for (std::size_t d = 2; d < n; ++d) {
    if (n % d == 0) return false;
  }
  return true;
}

// §6.3.3: the first prime greater than 4/3 of the points, found here by walking up from 0.
TEST(SpatialHash, TableSizeIsTheFirstPrimeAboveFourThirdsOfThePoints) {
  for (std::size_t points : {0u, 1u, 2u, 3u, 7u, 10u, 100u, 648u, 1000u, 12345u}) {
    std::size_t expected = 0;
    while (!(3 * expected > 4 * points && is_prime_by_trial(expected))) ++expected;
    EXPECT_EQ(SpatialHash::table_size_for(points), expected) << points << " points";

    SpatialHash hash;
    hash.begin(0.1, points);
    EXPECT_EQ(hash.table_size(), expected);
  }
}

TEST(SpatialHash, CellsAreFlooredCoordinatesOverTheCellSize) {
  SpatialHash hash;
  hash.begin(0.5, 1);
  EXPECT_EQ(hash.cell_of(Vec3(0.1, 0.6, 1.2)), (SpatialHash::Cell{0, 1, 2}));
  // negative coordinates round down, not toward zero
  EXPECT_EQ(hash.cell_of(Vec3(-0.1, -0.5, -0.51)), (SpatialHash::Cell{-1, -1, -2}));
}

using Point = std::pair<std::uint32_t, std::uint32_t>;

// Random points around the origin (negative keys included) and random boxes, small and large:
// every point inside a box is visited, none twice, and every visited point lies in a cell the
// box overlaps (within one cell of the box).
TEST(SpatialHash, BoxQueriesReturnASupersetOfTheBruteForcePoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> coordinate(-2, 2);
  std::uniform_real_distribution<Real> extent(0, 0.6);
  const Real cell = 0.25;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::vector<Vec3>> bodies(3);
    std::size_t total = 0;
    for (auto& body : bodies) {
      body.resize(100 + 50 * trial);
      for (Vec3& x : body) x = Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
      total += body.size();
    }
    SpatialHash hash;
    hash.begin(cell, total);
    for (std::uint32_t b = 0; b < bodies.size(); ++b) {
      for (std::uint32_t n = 0; n < bodies[b].size(); ++n) hash.insert(b, n, bodies[b][n]);
    }
    EXPECT_EQ(hash.point_count(), total);

    for (int query = 0; query < 50; ++query) {
      const Vec3 lo(coordinate(rng), coordinate(rng), coordinate(rng));
      // one box in ten spans most of the cloud: more cells than points
      const Real scale = query % 10 == 0 ? 8 : 1;
      const Vec3 hi = lo + scale * Vec3(extent(rng), extent(rng), extent(rng));
      std::map<Point, int> visits;
      hash.for_each_in_box(lo, hi, [&](std::uint32_t b, std::uint32_t n) { ++visits[{b, n}]; });

      for (std::uint32_t b = 0; b < bodies.size(); ++b) {
        for (std::uint32_t n = 0; n < bodies[b].size(); ++n) {
          const Vec3& x = bodies[b][n];
          const bool inside = (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
          const bool near =
              (x.array() >= lo.array() - cell).all() && (x.array() <= hi.array() + cell).all();
          const auto it = visits.find({b, n});
          EXPECT_TRUE(!inside || it != visits.end()) << "missed a point inside the box";
          if (it != visits.end()) {
            EXPECT_EQ(it->second, 1) << "visited twice";
            EXPECT_TRUE(near) << "visited a point outside the box's cells";
          }
        }
      }
    }
  }
}

// A new step empties the table by its timestamp: points of the last step are gone, with the
// table kept at the same size.
TEST(SpatialHash, ANewStepForgetsTheLastStepsPoints) {
  SpatialHash hash;
  hash.begin(1.0, 2);
  hash.insert(0, 0, Vec3(0.5, 0.5, 0.5));
  hash.insert(0, 1, Vec3(-3.5, 0.5, 0.5));
  const std::size_t size = hash.table_size();

  hash.begin(1.0, 2);
  hash.insert(1, 7, Vec3(10.5, 0.5, 0.5));
  hash.insert(1, 8, Vec3(11.5, 0.5, 0.5));
  EXPECT_EQ(hash.table_size(), size);
  std::vector<Point> seen;
  hash.for_each_in_box(Vec3(-5, 0, 0), Vec3(0.9, 0.9, 0.9),
                       [&](std::uint32_t b, std::uint32_t n) { seen.emplace_back(b, n); });
  EXPECT_TRUE(seen.empty());
  hash.for_each_in_box(Vec3(10.2, 0.2, 0.2), Vec3(10.8, 0.8, 0.8),
                       [&](std::uint32_t b, std::uint32_t n) { seen.emplace_back(b, n); });
  EXPECT_EQ(seen, (std::vector<Point>{{1, 7}}));
}

}  // namespace
}  // namespace felt
