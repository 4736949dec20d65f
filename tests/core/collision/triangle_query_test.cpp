// The haptic broad phase (thesis 1 §6, §8.2) against brute force: every structure must return
// each triangle whose bounding box over [from, to] overlaps the region, once, whatever the
// surface does between refits; the hierarchies must keep their shape and their volumes nested.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "core/cloth/cloth_grid.hpp"
#include "core/collision/spatial_hash.hpp"
#include "core/collision/triangle_bvh.hpp"
#include "core/collision/triangle_hash.hpp"
#include "core/collision/triangle_query.hpp"

namespace felt {
namespace {

constexpr std::array kKinds{
    TriangleQueryKind::kBruteForce, TriangleQueryKind::kBvhSphere2, TriangleQueryKind::kBvhSphere4,
    TriangleQueryKind::kBvhAabb2,   TriangleQueryKind::kBvhAabb4,   TriangleQueryKind::kSpatialHash,
};
constexpr std::array kBvhVolumes{BvhVolume::kSphere, BvhVolume::kAabb};
constexpr std::array kBranchings{2u, 4u};
constexpr std::array kRefits{BvhRefit::kEscaped, BvhRefit::kReverseOrder};

struct Surface {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

/// A 1 m × 1 m grid cloth of n × n particles: 2 (n − 1)² triangles.
Surface grid_surface(std::uint32_t n) {
  GridClothSpec spec;
  spec.nx = spec.ny = n;
  ClothModel model = make_grid_cloth(spec);
  return {std::move(model.rest_positions), std::move(model.triangles)};
}

/// The reference: the triangles whose box over both states overlaps the region, ascending.
std::vector<std::uint32_t> exact_answer(const Surface& surface, std::span<const Vec3> from,
                                        std::span<const Vec3> to, const Aabb& region) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < surface.triangles.size(); ++i) {
    Aabb box;
    for (const std::uint32_t v : surface.triangles[i]) {
      box.grow(from[v]);
      box.grow(to[v]);
    }
    if (box.overlaps(region)) out.push_back(i);
  }
  return out;
}

struct Structure {
  std::string name;
  std::unique_ptr<TriangleQuery> query;
};

/// Every kind from the factory, and every hierarchy with each refit.
std::vector<Structure> every_structure(const Surface& surface) {
  std::vector<Structure> out;
  for (const TriangleQueryKind kind : kKinds) {
    out.push_back({std::string(to_string(kind)),
                   make_triangle_query(kind, surface.triangles, surface.positions)});
  }
  for (const BvhVolume volume : kBvhVolumes) {
    for (const std::uint32_t branching : kBranchings) {
      for (const BvhRefit refit : kRefits) {
        out.push_back(
            {"bvh volume " + std::to_string(static_cast<int>(volume)) + " branching " +
                 std::to_string(branching) + " refit " + std::to_string(static_cast<int>(refit)),
             std::make_unique<TriangleBvh>(surface.triangles, surface.positions,
                                           TriangleBvhOptions{volume, branching, refit})});
      }
    }
  }
  return out;
}

/// Regions of every sort: small boxes about the surface, flat and point regions (on vertices,
/// where only closed-interval tests find the touching triangles), an empty and a huge one.
std::vector<Aabb> regions_about(std::span<const Vec3> from, std::span<const Vec3> to,
                                std::mt19937& rng) {
  std::vector<Aabb> out{Aabb{}, Aabb{Vec3::Constant(-1e6), Vec3::Constant(1e6)}};
  std::uniform_int_distribution<std::size_t> vertex(0, to.size() - 1);
  std::uniform_real_distribution<Real> unit(-1, 1);
  std::uniform_real_distribution<Real> size(0, 0.15);
  for (int i = 0; i < 40; ++i) {
    const Vec3 c = to[vertex(rng)] + 0.1 * Vec3(unit(rng), unit(rng), unit(rng));
    const Vec3 half(size(rng), size(rng), size(rng));
    out.push_back({c - half, c + half});
  }
  for (int i = 0; i < 10; ++i) {
    const Vec3 on_vertex = (i % 2 == 0 ? from : to)[vertex(rng)];
    out.push_back({on_vertex, on_vertex});
    const Vec3 anywhere = on_vertex + 0.05 * Vec3(unit(rng), unit(rng), unit(rng));
    out.push_back({anywhere, anywhere});
    Vec3 flat = Vec3::Constant(0.1);
    flat[i % 3] = 0;
    out.push_back({anywhere - flat, anywhere + flat});
  }
  return out;
}

/// The query's answer is a superset of the reference, without duplicates or strangers.
void expect_superset(const TriangleQuery& query, const std::string& name, const Surface& surface,
                     std::span<const Vec3> from, std::span<const Vec3> to, const Aabb& region) {
  std::vector<std::uint32_t> found{7777777};  // collect appends: what was there must stay
  query.collect(region, found);
  ASSERT_EQ(found.front(), 7777777u) << name;
  found.erase(found.begin());
  std::vector<std::uint32_t> sorted = found;
  std::sort(sorted.begin(), sorted.end());
  ASSERT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end())
      << name << ": a triangle reported twice";
  ASSERT_TRUE(sorted.empty() || sorted.back() < surface.triangles.size()) << name;
  const std::vector<std::uint32_t> expected = exact_answer(surface, from, to, region);
  ASSERT_TRUE(std::includes(sorted.begin(), sorted.end(), expected.begin(), expected.end()))
      << name << ": misses triangles; region " << region.lo.transpose() << " .. "
      << region.hi.transpose() << ", " << expected.size() << " expected, " << sorted.size()
      << " found";
}

/// The hierarchy's shape: breadth-first ids, consecutive siblings, one triangle per leaf.
void expect_well_formed(const TriangleBvh& bvh, std::size_t triangle_count) {
  const auto nodes = bvh.nodes();
  std::vector<int> leaves_of_triangle(triangle_count, 0);
  std::vector<std::uint32_t> leaves;
  std::uint32_t next_child = 1;
  for (std::uint32_t id = 0; id < nodes.size(); ++id) {
    const TriangleBvh::Node& node = nodes[id];
    if (id == 0) {
      EXPECT_EQ(node.parent, TriangleBvh::kNoParent);
    } else {
      EXPECT_LT(node.parent, id) << "a parent's id is below its child's";
    }
    if (node.leaf()) {
      ASSERT_LT(node.first, triangle_count);
      ++leaves_of_triangle[node.first];
      leaves.push_back(id);
      continue;
    }
    EXPECT_GE(node.child_count, 2u);
    EXPECT_LE(node.child_count, bvh.options().branching);
    EXPECT_GT(node.first, id);
    for (std::uint32_t c = 0; c < node.child_count; ++c) {
      ASSERT_LT(node.first + c, nodes.size());
      EXPECT_EQ(nodes[node.first + c].parent, id);
    }
    // breadth-first: each internal node's children follow the previous internal node's
    EXPECT_EQ(node.first, next_child);
    next_child = node.first + node.child_count;
  }
  EXPECT_EQ(next_child, nodes.size());
  for (std::size_t t = 0; t < triangle_count; ++t) EXPECT_EQ(leaves_of_triangle[t], 1) << t;
  EXPECT_TRUE(std::ranges::equal(leaves, bvh.leaves()));
}

// rounding of a sphere's centre distance: a few ulps of the scene's size
constexpr Real kSlack = 1e-12;

bool sphere_holds(const BoundingSphere& s, const Vec3& p) {
  return (p - s.center).norm() <= s.radius + kSlack;
}

/// Every node's volume contains its children's, every leaf's its triangle in both states.
void expect_nested(const TriangleBvh& bvh, const Surface& surface, std::span<const Vec3> from,
                   std::span<const Vec3> to) {
  const auto nodes = bvh.nodes();
  for (std::uint32_t id = 0; id < nodes.size(); ++id) {
    const TriangleBvh::Node& node = nodes[id];
    if (node.leaf()) {
      // the corners in both states, and for a sphere the corners of their box too, so that it
      // finds all that brute force's box test finds
      Aabb box;
      for (const std::uint32_t v : surface.triangles[node.first]) {
        for (const Vec3& p : {from[v], to[v]}) {
          box.grow(p);
          if (bvh.options().volume == BvhVolume::kSphere) {
            ASSERT_TRUE(sphere_holds(bvh.spheres()[id], p)) << "leaf " << id;
          } else {
            ASSERT_TRUE(bvh.boxes()[id].contains(Aabb{p, p})) << "leaf " << id;
          }
        }
      }
      if (bvh.options().volume == BvhVolume::kSphere) {
        for (int corner = 0; corner < 8; ++corner) {
          const Vec3 p((corner & 1 ? box.hi : box.lo).x(), (corner & 2 ? box.hi : box.lo).y(),
                       (corner & 4 ? box.hi : box.lo).z());
          ASSERT_TRUE(sphere_holds(bvh.spheres()[id], p)) << "leaf " << id << " box corner";
        }
      }
      continue;
    }
    for (std::uint32_t c = node.first; c < node.first + node.child_count; ++c) {
      if (bvh.options().volume == BvhVolume::kSphere) {
        const BoundingSphere& parent = bvh.spheres()[id];
        const BoundingSphere& child = bvh.spheres()[c];
        ASSERT_LE((child.center - parent.center).norm() + child.radius, parent.radius + kSlack)
            << "node " << id << " child " << c;
      } else {
        ASSERT_TRUE(bvh.boxes()[id].contains(bvh.boxes()[c])) << "node " << id << " child " << c;
      }
    }
  }
}

/// A new state: every vertex displaced by Gaussian noise of the given size.
std::vector<Vec3> displaced(std::span<const Vec3> x, Real size, std::mt19937& rng) {
  std::normal_distribution<Real> noise(0, size);
  std::vector<Vec3> out(x.begin(), x.end());
  for (Vec3& p : out) p += Vec3(noise(rng), noise(rng), noise(rng));
  return out;
}

TEST(TriangleQuery, NamesRoundTrip) {
  std::set<std::string_view> names;
  for (const TriangleQueryKind kind : kKinds) {
    names.insert(to_string(kind));
    EXPECT_EQ(triangle_query_kind(to_string(kind)), kind) << to_string(kind);
  }
  EXPECT_EQ(names.size(), kKinds.size());
  EXPECT_EQ(triangle_query_kind("bvh_sphere_3"), std::nullopt);
  EXPECT_EQ(triangle_query_kind(""), std::nullopt);
}

TEST(TriangleQuery, TheFactoryMakesEveryKind) {
  const Surface surface = grid_surface(5);
  for (const TriangleQueryKind kind : kKinds) {
    EXPECT_EQ(make_triangle_query(kind, surface.triangles, surface.positions)->kind(), kind);
  }
}

TEST(TriangleQuery, EveryStructureFindsWhatBruteForceFindsOnADeformingCloth) {
  std::mt19937 rng(5);
  const Surface surface = grid_surface(17);
  std::vector<Structure> structures = every_structure(surface);
  std::vector<Vec3> from = surface.positions;
  // large jumps (triangles flung across the cloth and stretched over many hash cells) and
  // small steps, in turn, each refit starting where the last ended
  for (const Real motion : {0.0, 0.3, 0.002, 0.002, 1.0, 0.0005, 0.05}) {
    const std::vector<Vec3> to = displaced(from, motion, rng);
    for (Structure& s : structures) s.query->refit(from, to);
    for (const Aabb& region : regions_about(from, to, rng)) {
      for (const Structure& s : structures) {
        expect_superset(*s.query, s.name, surface, from, to, region);
      }
    }
    from = to;
  }
}

TEST(TriangleQuery, DegenerateTrianglesAreFound) {
  // a zero-area sliver, a triangle on one vertex, one with a repeated vertex, three corners at
  // one point, and an ordinary one
  Surface surface;
  surface.positions = {Vec3(0, 0, 0),       Vec3(1, 0, 0),       Vec3(2, 0, 0), Vec3(0.5, 0.5, 0.5),
                       Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.5), Vec3(0, 1, 0)};
  surface.triangles = {{0, 1, 2}, {3, 3, 3}, {0, 1, 1}, {3, 4, 5}, {0, 1, 6}};
  std::vector<Structure> structures = every_structure(surface);
  std::mt19937 rng(11);
  std::vector<Vec3> from = surface.positions;
  for (const Real motion : {0.0, 0.01, 0.5}) {
    const std::vector<Vec3> to = displaced(from, motion, rng);
    for (Structure& s : structures) s.query->refit(from, to);
    std::vector<Aabb> regions = regions_about(from, to, rng);
    for (const Vec3& p : to) regions.push_back({p, p});
    for (const Aabb& region : regions) {
      for (const Structure& s : structures) {
        expect_superset(*s.query, s.name, surface, from, to, region);
      }
    }
    from = to;
  }
}

TEST(TriangleQuery, ASingleTriangleIsFoundExactlyWhereItIs) {
  Surface surface;
  surface.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  surface.triangles = {{0, 1, 2}};
  for (Structure& s : every_structure(surface)) {
    std::vector<std::uint32_t> found;
    s.query->collect({Vec3(0.2, 0.2, -0.1), Vec3(0.3, 0.3, 0.1)}, found);
    EXPECT_EQ(found, std::vector<std::uint32_t>{0}) << s.name;
    found.clear();
    s.query->collect({Vec3(5, 5, 5), Vec3(6, 6, 6)}, found);
    if (s.query->kind() != TriangleQueryKind::kBruteForce) {
      EXPECT_TRUE(found.empty()) << s.name;
    }
  }
  const TriangleBvh bvh(surface.triangles, surface.positions);
  ASSERT_EQ(bvh.nodes().size(), 1u);
  EXPECT_TRUE(bvh.nodes()[0].leaf());
}

TEST(TriangleQuery, AnEmptySurfaceHasNothingToFind) {
  const Surface surface;
  for (Structure& s : every_structure(surface)) {
    s.query->refit({}, {});
    std::vector<std::uint32_t> found;
    s.query->collect({Vec3::Constant(-1e6), Vec3::Constant(1e6)}, found);
    EXPECT_TRUE(found.empty()) << s.name;
  }
}

TEST(TriangleBvh, ABinaryTreeOver3042TrianglesHas6083Nodes) {
  const Surface surface = grid_surface(40);  // the thesis's 40 × 40 cloth
  ASSERT_EQ(surface.triangles.size(), 3042u);
  for (const BvhVolume volume : kBvhVolumes) {
    for (const std::uint32_t branching : kBranchings) {
      const TriangleBvh bvh(surface.triangles, surface.positions,
                            TriangleBvhOptions{volume, branching, BvhRefit::kEscaped});
      if (branching == 2) {
        EXPECT_EQ(bvh.nodes().size(), 6083u);  // thesis 1 §8.2
      }
      EXPECT_EQ(bvh.leaves().size(), 3042u);
      expect_well_formed(bvh, surface.triangles.size());
      expect_nested(bvh, surface, surface.positions, surface.positions);
    }
  }
}

TEST(TriangleBvh, EveryRefitKeepsTheVolumesNestedAndUpdatesEachNodeAtMostOnce) {
  std::mt19937 rng(17);
  const Surface surface = grid_surface(23);
  for (const BvhVolume volume : kBvhVolumes) {
    for (const std::uint32_t branching : kBranchings) {
      for (const BvhRefit refit : kRefits) {
        TriangleBvh bvh(surface.triangles, surface.positions,
                        TriangleBvhOptions{volume, branching, refit});
        std::vector<Vec3> from = surface.positions;
        for (const Real motion : {0.001, 0.2, 0.0, 0.01, 0.003, 1.0}) {
          const std::vector<Vec3> to = displaced(from, motion, rng);
          bvh.refit(from, to);
          EXPECT_LE(bvh.last_refit_updates(), bvh.nodes().size());
          expect_nested(bvh, surface, from, to);
          from = to;
        }
        expect_well_formed(bvh, surface.triangles.size());
      }
    }
  }
}

TEST(TriangleBvh, TheThesisRefitTouchesOnlyEscapedLeavesAndTheirAncestors) {
  const Surface surface = grid_surface(20);
  for (const BvhVolume volume : kBvhVolumes) {
    for (const std::uint32_t branching : kBranchings) {
      TriangleBvh bvh(surface.triangles, surface.positions,
                      TriangleBvhOptions{volume, branching, BvhRefit::kEscaped});
      bvh.refit(surface.positions, surface.positions);
      EXPECT_EQ(bvh.last_refit_updates(), 0u) << "nothing moved";

      // one vertex flung a metre off the cloth: its triangles' leaves must be refitted, and
      // nothing but them and their ancestors may be
      const std::uint32_t vertex = 7 * 20 + 9;
      std::vector<Vec3> to = surface.positions;
      to[vertex] += Vec3(0, 0, 1);
      std::set<std::uint32_t> moved_leaves, ancestors;
      for (const std::uint32_t leaf : bvh.leaves()) {
        const Triangle& t = surface.triangles[bvh.nodes()[leaf].first];
        if (std::ranges::find(t, vertex) == t.end()) continue;
        moved_leaves.insert(leaf);
        for (std::uint32_t p = bvh.nodes()[leaf].parent; p != TriangleBvh::kNoParent;
             p = bvh.nodes()[p].parent) {
          ancestors.insert(p);
        }
      }
      std::vector<std::uint32_t> deformed;
      bvh.find_deformed_leaves(surface.positions, to, DeformedLeafSearch::kLeafArray, deformed);
      EXPECT_TRUE(std::ranges::equal(deformed, moved_leaves));
      deformed.clear();
      bvh.find_deformed_leaves(surface.positions, to, DeformedLeafSearch::kTopDown, deformed);
      std::ranges::sort(deformed);
      EXPECT_TRUE(std::ranges::equal(deformed, moved_leaves));

      bvh.refit(surface.positions, to);
      EXPECT_GT(bvh.last_refit_updates(), moved_leaves.size()) << "the root at least is escaped";
      EXPECT_LE(bvh.last_refit_updates(), moved_leaves.size() + ancestors.size());
      expect_nested(bvh, surface, surface.positions, to);
    }
  }
}

TEST(TriangleBvh, BoxesRefittedInReverseOrderFindExactlyTheBruteForceAnswer) {
  // a tight leaf box is the triangle's box, and every ancestor contains it: nothing extra
  std::mt19937 rng(23);
  const Surface surface = grid_surface(15);
  for (const std::uint32_t branching : kBranchings) {
    TriangleBvh tight(surface.triangles, surface.positions,
                      TriangleBvhOptions{BvhVolume::kAabb, branching, BvhRefit::kReverseOrder});
    TriangleBvh loose(surface.triangles, surface.positions,
                      TriangleBvhOptions{BvhVolume::kAabb, branching, BvhRefit::kEscaped});
    std::vector<Vec3> from = surface.positions;
    for (const Real motion : {0.01, 0.001, 0.1}) {
      const std::vector<Vec3> to = displaced(from, motion, rng);
      tight.refit(from, to);
      loose.refit(from, to);
      for (const Aabb& region : regions_about(from, to, rng)) {
        std::vector<std::uint32_t> found, found_loose;
        tight.collect(region, found);
        loose.collect(region, found_loose);
        std::ranges::sort(found);
        std::ranges::sort(found_loose);
        EXPECT_EQ(found, exact_answer(surface, from, to, region));
        // the thesis's boxes only grow until escaped, so they find at least as much
        EXPECT_TRUE(std::ranges::includes(found_loose, found));
      }
      from = to;
    }
  }
}

TEST(TriangleHash, CellsAreTheMeanEdgeAndTheTableTheFirstPrimeAboveFourThirds) {
  const Surface surface = grid_surface(11);  // 0.1 m squares: 200 triangles
  ASSERT_EQ(surface.triangles.size(), 200u);
  const TriangleHash hash(surface.triangles, surface.positions);
  // every triangle has two 0.1 m legs and a 0.1·√2 m diagonal
  EXPECT_NEAR(hash.cell_size(), (0.2 + 0.1 * std::sqrt(2.0)) / 3, 1e-12);
  EXPECT_EQ(hash.table_size(), 269u);  // 4/3 · 200 = 266.7; 267 = 3·89, 268 even
}

TEST(TriangleQuery, ACopyKeepsAnsweringForTheStateItWasFittedTo) {
  std::mt19937 rng(29);
  const Surface surface = grid_surface(12);
  const std::vector<Vec3> moved = displaced(surface.positions, 0.5, rng);
  for (Structure& s : every_structure(surface)) {
    const std::unique_ptr<TriangleQuery> copy = s.query->clone();
    EXPECT_EQ(copy->kind(), s.query->kind());
    s.query->refit(moved, moved);
    for (const Aabb& region : regions_about(surface.positions, surface.positions, rng)) {
      expect_superset(*copy, s.name + " (copy)", surface, surface.positions, surface.positions,
                      region);
      expect_superset(*s.query, s.name, surface, moved, moved, region);
    }
  }
}

TEST(TriangleQuery, ConcurrentQueriesAgreeWithOneAtATime) {
  std::mt19937 rng(31);
  const Surface surface = grid_surface(30);
  const std::vector<Vec3> to = displaced(surface.positions, 0.01, rng);
  std::vector<Aabb> regions;
  for (int i = 0; i < 20; ++i) {
    for (const Aabb& region : regions_about(surface.positions, to, rng)) regions.push_back(region);
  }
  for (Structure& s : every_structure(surface)) {
    s.query->refit(surface.positions, to);
    std::vector<std::vector<std::uint32_t>> expected(regions.size());
    for (std::size_t i = 0; i < regions.size(); ++i) s.query->collect(regions[i], expected[i]);
    std::array<std::vector<std::vector<std::uint32_t>>, 2> found;
    std::vector<std::thread> threads;
    for (auto& answers : found) {
      threads.emplace_back([&, &answers = answers] {
        answers.resize(regions.size());
        for (std::size_t i = 0; i < regions.size(); ++i) s.query->collect(regions[i], answers[i]);
      });
    }
    for (std::thread& t : threads) t.join();
    for (const auto& answers : found) EXPECT_EQ(answers, expected) << s.name;
  }
}

}  // namespace
}  // namespace felt
