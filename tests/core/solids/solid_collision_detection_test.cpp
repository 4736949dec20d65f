#include "core/solids/solid_collision_detection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "core/solids/tet_lattice.hpp"

namespace felt {
namespace {

SolidBody lattice_body(std::array<int, 3> cells, Real cell_size, const Vec3& origin,
                       bool self_collision = false) {
  LatticeGrid grid;
  grid.cells = cells;
  grid.cell_size = Vec3::Constant(cell_size);
  grid.origin = origin;
  SolidMaterial material;
  material.self_collision = self_collision;
  return SolidBody("lattice", make_box_lattice(grid), material);
}

/// (body, node, penetrated body)
using Contact = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>;

/// Inside the closed tetrahedron by solving for the barycentric coordinates (a different route
/// from the detector's signed sub-volumes).
bool inside_by_barycentric(const std::vector<Vec3>& x, const Tetrahedron& t, const Vec3& p) {
  Mat3 edges;
  edges << x[t[1]] - x[t[0]], x[t[2]] - x[t[0]], x[t[3]] - x[t[0]];
  if (edges.determinant() == 0) return false;
  const Vec3 lambda = edges.fullPivLu().solve(p - x[t[0]]);
  return lambda.minCoeff() >= 0 && lambda.sum() <= 1;
}

/// Whether node n shares a tetrahedron with a corner of t: a corner itself or an edge
/// neighbour of one, the nodes excluded from self-collision.
bool shares_tet_with_corner(const SolidBody& body, const Tetrahedron& t, std::uint32_t n) {
  for (const Tetrahedron& other : body.rest().tets) {
    const bool has_n = std::ranges::find(other, n) != other.end();
    const bool has_corner = std::ranges::any_of(
        t, [&](std::uint32_t c) { return std::ranges::find(other, c) != other.end(); });
    if (has_n && has_corner) return true;
  }
  return false;
}

struct BruteForce {
  std::set<Contact> contacts;
  /// per body: the surface triangles with a colliding corner or a corner of a tetrahedron
  /// that contains a colliding node
  std::vector<std::set<std::uint32_t>> triangles;
};

/// Every node against every tetrahedron.
BruteForce brute_force(const std::vector<SolidBody>& bodies) {
  BruteForce result;
  std::vector<std::vector<bool>> flagged;
  for (const SolidBody& body : bodies) flagged.emplace_back(body.node_count(), false);
  for (std::uint32_t a = 0; a < bodies.size(); ++a) {
    for (std::uint32_t n = 0; n < bodies[a].node_count(); ++n) {
      const Vec3& p = bodies[a].positions()[n];
      for (std::uint32_t b = 0; b < bodies.size(); ++b) {
        const SolidBody& body = bodies[b];
        if (a == b && !body.material().self_collision) continue;
        for (const Tetrahedron& t : body.rest().tets) {
          if (!inside_by_barycentric(body.positions(), t, p)) continue;
          if (a == b && shares_tet_with_corner(body, t, n)) continue;
          result.contacts.insert({a, n, b});
          flagged[a][n] = true;
          for (std::uint32_t c : t) flagged[b][c] = true;
        }
      }
    }
  }
  result.triangles.resize(bodies.size());
  for (std::uint32_t b = 0; b < bodies.size(); ++b) {
    const std::vector<Triangle>& surface = bodies[b].topology().surface;
    for (std::uint32_t s = 0; s < surface.size(); ++s) {
      if (std::ranges::any_of(surface[s], [&](std::uint32_t c) { return flagged[b][c]; })) {
        result.triangles[b].insert(s);
      }
    }
  }
  return result;
}

/// Runs the detector and checks it against the brute force: the same (node, penetrated body)
/// set, once each, each in a tetrahedron that contains it; the same triangles. Returns the
/// number of contacts.
std::size_t expect_matches_brute_force(const std::vector<SolidBody>& bodies) {
  SolidCollisionDetector detector;
  detector.set_cell_size(mean_rest_edge_length(bodies));
  CollisionSet set;
  detector.detect(bodies, set);
  detector.collect_triangles(bodies, set);

  std::set<Contact> found;
  for (const CollidingNode& c : set.nodes) {
    EXPECT_TRUE(found.insert({c.body, c.node, c.penetrated_body}).second) << "reported twice";
    const SolidBody& penetrated = bodies[c.penetrated_body];
    EXPECT_TRUE(inside_by_barycentric(penetrated.positions(), penetrated.rest().tets[c.tet],
                                      bodies[c.body].positions()[c.node]));
  }
  const BruteForce expected = brute_force(bodies);
  EXPECT_EQ(found, expected.contacts);

  EXPECT_EQ(set.triangles.size(), bodies.size());
  std::size_t triangle_count = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::set<std::uint32_t> triangles(set.triangles[b].begin(), set.triangles[b].end());
    EXPECT_EQ(triangles.size(), set.triangles[b].size()) << "a triangle collected twice";
    EXPECT_EQ(triangles, expected.triangles[b]) << "body " << b;
    triangle_count += triangles.size();
  }
  EXPECT_EQ(detector.counts().colliding_nodes, set.nodes.size());
  EXPECT_EQ(detector.counts().colliding_triangles, triangle_count);
  return set.nodes.size();
}

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<Real> normal;
  Eigen::Quaternion<Real> q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

// Several lattice cubes at random positions and rotations in a small region, some of them with
// every node jittered (deformed, some tetrahedra inverted), over many seeds.
TEST(SolidCollisionDetection, RandomConfigurationsMatchBruteForce) {
  std::size_t total_contacts = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> unit(0, 1);
    std::vector<SolidBody> bodies;
    const int body_count = 2 + static_cast<int>(seed % 3);
    for (int i = 0; i < body_count; ++i) {
      const int cells = 2 + static_cast<int>(unit(rng) * 2);
      const Real cell_size = 0.15 + 0.15 * unit(rng);
      SolidBody body = lattice_body({cells, cells, cells}, cell_size, Vec3::Zero());
      const Mat3 rotation = random_rotation(rng);
      const Vec3 translation = 0.6 * Vec3(unit(rng), unit(rng), unit(rng));
      const Real jitter = (i + seed) % 3 == 0 ? 0.4 * cell_size : 0;
      for (std::size_t n = 0; n < body.node_count(); ++n) {
        const Vec3 noise = jitter * (2 * Vec3(unit(rng), unit(rng), unit(rng)) - Vec3::Ones());
        body.positions()[n] = rotation * body.rest().nodes[n] + translation + noise;
      }
      bodies.push_back(std::move(body));
    }
    total_contacts += expect_matches_brute_force(bodies);
  }
  EXPECT_GT(total_contacts, 300u);  // the configurations do overlap
}

// A bar folded back over itself: its far end lies inside its near end.
std::vector<SolidBody> folded_bar(bool self_collision) {
  std::vector<SolidBody> bodies;
  bodies.push_back(lattice_body({6, 1, 1}, 1.0, Vec3::Zero(), self_collision));
  SolidBody& bar = bodies.back();
  for (std::size_t n = 0; n < bar.node_count(); ++n) {
    const Vec3& rest = bar.rest().nodes[n];
    if (rest.x() > 3) bar.positions()[n] = Vec3(6.13 - rest.x(), rest.y() + 0.37, rest.z() + 0.21);
  }
  return bodies;
}

TEST(SolidCollisionDetection, SelfCollisionOnlyWhenEnabled) {
  SolidCollisionDetector detector;
  detector.set_cell_size(1.0);
  CollisionSet set;
  detector.detect(folded_bar(false), set);
  EXPECT_TRUE(set.nodes.empty());

  const std::vector<SolidBody> folded = folded_bar(true);
  EXPECT_GT(expect_matches_brute_force(folded), 0u);
}

// At rest a mesh does not collide with itself: no node lies in a tetrahedron it is not a
// corner of.
TEST(SolidCollisionDetection, ABodyAtRestHasNoSelfContacts) {
  std::vector<SolidBody> bodies;
  bodies.push_back(lattice_body({3, 3, 3}, 0.5, Vec3(-0.7, 0.2, 0.1), true));
  SolidCollisionDetector detector;
  detector.set_cell_size(mean_rest_edge_length(bodies));
  CollisionSet set;
  detector.detect(bodies, set);
  EXPECT_TRUE(set.nodes.empty());
}

// A small cube in the overlap of two big ones: each of its nodes is inside both, and is
// reported once for each.
TEST(SolidCollisionDetection, ANodeInsideTwoBodiesIsReportedForBoth) {
  std::vector<SolidBody> bodies;
  bodies.push_back(lattice_body({4, 4, 4}, 0.5, Vec3::Zero()));
  bodies.push_back(lattice_body({4, 4, 4}, 0.5, Vec3(1.05, 0.03, 0.07)));
  bodies.push_back(lattice_body({1, 1, 1}, 0.2, Vec3(1.4, 0.9, 0.9)));
  expect_matches_brute_force(bodies);

  SolidCollisionDetector detector;
  detector.set_cell_size(mean_rest_edge_length(bodies));
  CollisionSet set;
  detector.detect(bodies, set);
  std::multiset<std::pair<std::uint32_t, std::uint32_t>> small_cube;  // (node, penetrated)
  for (const CollidingNode& c : set.nodes) {
    if (c.body == 2) small_cube.insert({c.node, c.penetrated_body});
  }
  EXPECT_EQ(small_cube.size(), 2 * bodies[2].node_count());
  for (std::uint32_t n = 0; n < bodies[2].node_count(); ++n) {
    EXPECT_EQ(small_cube.count({n, 0}), 1u);
    EXPECT_EQ(small_cube.count({n, 1}), 1u);
  }
}

// The mean edge length of a lattice cube, by its edge count: 3 axis directions and the face
// and cell diagonals of the five-tetrahedron split.
TEST(SolidCollisionDetection, MeanRestEdgeLengthOfOneCell) {
  std::vector<SolidBody> bodies;
  bodies.push_back(lattice_body({1, 1, 1}, 2.0, Vec3::Zero()));
  // one cell: 12 cube edges of 2 and 6 face diagonals of 2√2 (the central tetrahedron's edges)
  EXPECT_EQ(bodies[0].topology().edges.size(), 18u);
  EXPECT_NEAR(mean_rest_edge_length(bodies), (12 * 2.0 + 6 * 2 * std::sqrt(2.0)) / 18, 1e-12);
}

}  // namespace
}  // namespace felt
