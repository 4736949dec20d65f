#include "core/solids/penetration_depth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "core/geometry/triangle_geometry.hpp"
#include "core/solids/tet_lattice.hpp"

namespace felt {
namespace {

constexpr Real kMinDepth = 1e-6;

SolidBody lattice_body(std::array<int, 3> cells, Real cell_size, const Vec3& origin,
                       const std::function<bool(int, int, int)>& keep = {},
                       bool self_collision = false) {
  LatticeGrid grid;
  grid.cells = cells;
  grid.cell_size = Vec3::Constant(cell_size);
  grid.origin = origin;
  SolidMaterial material;
  material.self_collision = self_collision;
  return SolidBody("lattice", keep ? make_cell_lattice(grid, keep) : make_box_lattice(grid),
                   material);
}

/// Detection, triangle collection and penetration vectors, as a step runs them.
class Pipeline {
 public:
  std::vector<PenetrationContact> run(const std::vector<SolidBody>& bodies) {
    detector_.set_cell_size(mean_rest_edge_length(bodies));
    detector_.detect(bodies, set_);
    detector_.collect_triangles(bodies, set_);
    std::vector<PenetrationContact> contacts;
    estimator_.compute(bodies, set_, kMinDepth, contacts);
    EXPECT_EQ(contacts.size(), set_.nodes.size());
    return contacts;
  }

 private:
  SolidCollisionDetector detector_;
  PenetrationDepthEstimator estimator_;
  CollisionSet set_;
};

/// The point where a contact's ray hit its triangle.
Vec3 hit_point(const std::vector<SolidBody>& bodies, const PenetrationContact& c) {
  const Triangle& tri = bodies[c.penetrated_body].topology().surface[c.triangle];
  const std::vector<Vec3>& x = bodies[c.penetrated_body].positions();
  return c.barycentric[0] * x[tri[0]] + c.barycentric[1] * x[tri[1]] + c.barycentric[2] * x[tri[2]];
}

// A wide lattice slab, top face at y = 0, and a finer cube sunk into it by `depth` (placed off
// the slab's lattice planes so no node lies on a face of the other body).
constexpr Real kSlabCell = 0.1;
constexpr Real kCubeCell = 0.04;

std::vector<SolidBody> cube_in_slab(Real depth, Real shift_x = 0) {
  std::vector<SolidBody> bodies;
  bodies.push_back(lattice_body({8, 2, 8}, kSlabCell, Vec3(-0.4, -0.2, -0.4)));
  bodies.push_back(lattice_body({3, 3, 3}, kCubeCell, Vec3(-0.0537 + shift_x, -depth, -0.0481)));
  return bodies;
}

// A flat face with vertex normals all (0, 1, 0): every crossing gives (x_e − x_i)·n = −y_i, so
// a border node's depth is exactly its distance below the face, and propagation through
// (x_j − x_i)·r_j + h_j keeps it exact further in. Several depths, from a fraction of the cube's
// cell to nearly its height; at 0.11 the cube's bottom is nearer the slab's bottom face than
// its top, where a nearest-surface estimate would push it out the wrong way.
TEST(PenetrationDepth, CubeInSlabGetsItsDepthBelowTheTopFace) {
  for (Real depth : {0.013, 0.031, 0.058, 0.093, 0.11}) {
    const std::vector<SolidBody> bodies = cube_in_slab(depth);
    Pipeline pipeline;
    const std::vector<PenetrationContact> contacts = pipeline.run(bodies);

    std::map<std::uint32_t, const PenetrationContact*> cube;
    for (const PenetrationContact& c : contacts) {
      if (c.body == 1) cube[c.node] = &c;
    }
    const SolidBody& slab = bodies[0];
    for (std::uint32_t n = 0; n < bodies[1].node_count(); ++n) {
      const Vec3& x = bodies[1].positions()[n];
      if (x.y() > 0) {
        EXPECT_FALSE(cube.contains(n));
        continue;
      }
      ASSERT_TRUE(cube.contains(n)) << "depth " << depth << " node " << n;
      const PenetrationContact& c = *cube[n];
      EXPECT_EQ(c.penetrated_body, 0u);
      EXPECT_NEAR((c.depth - Vec3(0, -x.y(), 0)).norm(), 0, 1e-12) << "depth " << depth;

      // the ray x + t·d meets the top face at t = 1, inside the triangle it names
      ASSERT_GE(c.triangle, 0);
      for (std::uint32_t corner : slab.topology().surface[c.triangle]) {
        EXPECT_NEAR(slab.positions()[corner].y(), 0, 1e-15);
      }
      EXPECT_GE(c.barycentric.minCoeff(), -1e-12);
      EXPECT_NEAR(c.barycentric.sum(), 1, 1e-12);
      EXPECT_NEAR((hit_point(bodies, c) - (x + c.depth)).norm(), 0, 1e-12);
    }
  }
}

// A cube sunk into the slab near its edge (x = 0.4), wholly over its top face: with the slab's
// default crease angle its depths are exactly vertical there too; with smooth vertex normals
// (crease 180°), tilted by up to 45° at the rim, they point sideways, out over the edge.
TEST(PenetrationDepth, NearABoxsEdgeTheDepthsStayVerticalUnlessItsEdgesAreSmooth) {
  for (const Real crease : {kDefaultCreaseAngle, std::numbers::pi}) {
    std::vector<SolidBody> bodies = cube_in_slab(0.013, 0.32);
    SolidMaterial slab = bodies[0].material();
    slab.crease_angle = crease;
    bodies[0].set_material(slab);
    Pipeline pipeline;
    Real largest_tilt = 0;
    std::size_t cube_contacts = 0;
    for (const PenetrationContact& c : pipeline.run(bodies)) {
      if (c.body != 1) continue;
      ++cube_contacts;
      const Vec3& x = bodies[1].positions()[c.node];
      largest_tilt = std::max(largest_tilt, std::abs(c.depth.x()) / c.depth.norm());
      if (crease < std::numbers::pi) {
        EXPECT_NEAR((c.depth - Vec3(0, -x.y(), 0)).norm(), 0, 1e-12) << "node " << c.node;
      }
    }
    EXPECT_GT(cube_contacts, 0u);
    if (crease == std::numbers::pi) {
      EXPECT_GT(largest_tilt, 0.1);
    }
  }
}

// The same slab with a sine wave in its top, sampled by the slab's nodes at quarter
// wavelengths (a zigzag of slope ±0.2), and the cube sliding across a whole wavelength in
// steps of 1/20 of its cell, at two depths.
constexpr Real kWaveAmplitude = 0.02;
constexpr Real kWaveLength = 0.4;
constexpr Real kWaveSlope = kWaveAmplitude / (kWaveLength / 4);

void make_wavy(SolidBody& slab) {
  for (Vec3& x : slab.positions()) {
    if (std::abs(x.y()) < 1e-12) {
      x.y() = kWaveAmplitude * std::sin(2 * std::numbers::pi * x.x() / kWaveLength);
    }
  }
}

/// Distance from p to the wavy top face, by brute force over its triangles.
Real distance_to_top(const SolidBody& slab, const Vec3& p) {
  Real nearest = std::numeric_limits<Real>::infinity();
  const std::vector<Vec3>& x = slab.positions();
  for (const Triangle& t : slab.topology().surface) {
    const bool on_top = std::ranges::all_of(
        t, [&](std::uint32_t c) { return std::abs(x[c].y()) <= kWaveAmplitude + 1e-12; });
    if (!on_top) continue;
    nearest = std::min(nearest,
                       (closest_point_on_triangle(p, x[t[0]], x[t[1]], x[t[2]]).point - p).norm());
  }
  return nearest;
}

// The consistency the method exists for. The true depth changes by at most slope × step per
// move, and every estimate is built from the face's normals, which span an angle of
// 2·atan(slope); so a vector of length h may turn by that angle, not more: |Δd| ≤ slope ×
// step + 2·atan(slope)·h. A jump to another surface (the nearest one, for a node closer to the
// slab's bottom) or a contact that appears or vanishes with a length would break it. The
// lengths also stay within 20% of the distance to the face (below a tenth of the cube's cell,
// within 20% of that).
TEST(PenetrationDepth, SlidingCubeGetsContinuousPenetrationVectors) {
  const Real step = kCubeCell / 20;
  const Real normal_spread = 2 * std::atan(kWaveSlope);
  for (Real sink : {0.03, 0.07}) {
    Pipeline pipeline;
    std::map<std::uint32_t, Vec3> last;  // cube node -> its penetration vector one move ago
    Real worst_change = 0;               // relative to the bound
    Real worst_length_error = 0;
    for (int move = 0; move <= static_cast<int>(std::round(kWaveLength / step)); ++move) {
      std::vector<SolidBody> bodies = cube_in_slab(sink, -0.2 + move * step);
      make_wavy(bodies[0]);
      std::map<std::uint32_t, Vec3> now;
      for (const PenetrationContact& c : pipeline.run(bodies)) {
        if (c.body != 1) continue;
        now[c.node] = c.depth;
        const Real distance = distance_to_top(bodies[0], bodies[1].positions()[c.node]);
        worst_length_error = std::max(worst_length_error, std::abs(c.depth.norm() - distance) /
                                                              std::max(distance, kCubeCell / 10));
      }
      if (move > 0) {
        // a node that starts or stops colliding has the vector zero on the other side
        for (const auto& [node, depth] : last) now.try_emplace(node, Vec3::Zero());
        for (const auto& [node, depth] : now) {
          const Vec3 before = last.contains(node) ? last[node] : Vec3::Zero();
          const Real bound =
              kWaveSlope * step + normal_spread * std::max(depth.norm(), before.norm());
          worst_change = std::max(worst_change, (depth - before).norm() / bound);
        }
        std::erase_if(now, [](const auto& entry) { return entry.second.isZero(); });
      }
      last = std::move(now);
    }
    EXPECT_LE(worst_change, 1) << "sunk by " << sink;
    EXPECT_LE(worst_length_error, 0.2) << "sunk by " << sink;
  }
}

// Temporal coherence only saves time: with one crossing per edge, an estimator that remembers
// the last step's triangles gives what a fresh one gives.
TEST(PenetrationDepth, CachedTrianglesGiveTheSameVectorsAsAFreshSearch) {
  Pipeline warm;
  for (int move = 0; move < 20; ++move) {
    std::vector<SolidBody> bodies = cube_in_slab(0.05, move * 0.003);
    make_wavy(bodies[0]);
    const std::vector<PenetrationContact> cached = warm.run(bodies);
    const std::vector<PenetrationContact> fresh = Pipeline().run(bodies);
    ASSERT_EQ(cached.size(), fresh.size());
    for (std::size_t k = 0; k < fresh.size(); ++k) {
      EXPECT_NEAR((cached[k].depth - fresh[k].depth).norm(), 0, 1e-12);
      EXPECT_EQ(cached[k].triangle, fresh[k].triangle);
    }
  }
}

// A cube pushed into the corner where a floor slab (top y = 0) and a wall (face x = b) overlap:
// nodes below the floor and behind the wall are inside both and get a contact for each, out
// of the floor's top and out of the wall's face.
TEST(PenetrationDepth, ANodeInsideTwoBodiesGetsAVectorOutOfEach) {
  const Real wall_face = 0.0031;
  std::vector<SolidBody> bodies;
  bodies.push_back(lattice_body({6, 3, 6}, 0.1, Vec3(-0.3, -0.3, -0.3)));
  bodies.push_back(lattice_body({3, 6, 6}, 0.1, Vec3(wall_face - 0.3, -0.2877, -0.2877)));
  bodies.push_back(lattice_body({2, 2, 2}, 0.03, Vec3(wall_face - 0.035, -0.035, -0.0217)));
  Pipeline pipeline;
  std::map<std::pair<std::uint32_t, std::uint32_t>, PenetrationContact> cube;
  for (const PenetrationContact& c : pipeline.run(bodies)) {
    if (c.body == 2) cube[{c.node, c.penetrated_body}] = c;
  }
  int inside_both = 0;
  for (std::uint32_t n = 0; n < bodies[2].node_count(); ++n) {
    const Vec3& x = bodies[2].positions()[n];
    ASSERT_EQ(cube.contains({n, 0}), x.y() < 0);
    ASSERT_EQ(cube.contains({n, 1}), x.x() < wall_face);
    if (x.y() < 0) {
      EXPECT_NEAR((cube[{n, 0}].depth - Vec3(0, -x.y(), 0)).norm(), 0, 1e-12);
      EXPECT_GE((cube[{n, 0}].triangle), 0);
    }
    if (x.x() < wall_face) {
      EXPECT_NEAR((cube[{n, 1}].depth - Vec3(wall_face - x.x(), 0, 0)).norm(), 0, 1e-12);
      EXPECT_GE((cube[{n, 1}].triangle), 0);
    }
    inside_both += x.y() < 0 && x.x() < wall_face;
  }
  EXPECT_EQ(inside_both, 2 * 2 * 3);
}

// Self-collision: a C-shaped body (a floor arm and an upper arm joined by a post) whose upper
// arm is bent down into its own floor arm by `depth`. The sunk nodes get vectors out of the
// floor arm's top face, found among its own triangles but never through their own.
TEST(PenetrationDepth, SelfContactsPointOutOfTheBodysOwnSurface) {
  const auto keep = [](int i, int j, int k) {
    const bool arm_or_post = k >= 1 && k < 4 && ((i == 0 && j < 4) || (j == 4 && i < 8));
    return j < 2 || arm_or_post;
  };
  for (Real depth : {0.03, 0.07}) {
    std::vector<SolidBody> bodies;
    bodies.push_back(lattice_body({10, 5, 6}, 0.1, Vec3::Zero(), keep, true));
    SolidBody& body = bodies[0];
    const Real floor_top = 0.2;
    for (std::size_t n = 0; n < body.node_count(); ++n) {
      const Vec3& rest = body.rest().nodes[n];
      if (rest.y() > 0.35 && rest.x() > 0.25) {
        body.positions()[n] = rest + Vec3(0.013, -(0.2 + depth), 0.007);
      }
    }
    Pipeline pipeline;
    std::map<std::uint32_t, PenetrationContact> contacts;
    for (const PenetrationContact& c : pipeline.run(bodies)) contacts[c.node] = c;

    int sunk = 0;
    for (std::uint32_t n = 0; n < body.node_count(); ++n) {
      const Vec3& rest = body.rest().nodes[n];
      const Vec3& x = body.positions()[n];
      if (!(rest.y() > 0.35 && x.y() < floor_top)) continue;
      ++sunk;
      ASSERT_TRUE(contacts.contains(n));
      const PenetrationContact& c = contacts[n];
      EXPECT_NEAR((c.depth - Vec3(0, floor_top - x.y(), 0)).norm(), 0, 1e-12);
      ASSERT_GE(c.triangle, 0);
      const Triangle& tri = body.topology().surface[c.triangle];
      EXPECT_EQ(std::ranges::find(tri, n), tri.end());
      for (std::uint32_t corner : tri) EXPECT_NEAR(body.positions()[corner].y(), floor_top, 1e-15);
      EXPECT_NEAR((hit_point(bodies, c) - (x + c.depth)).norm(), 0, 1e-12);
    }
    EXPECT_EQ(sunk, 6 * 4);  // the sunk arm's lower layer: 6 × 4 nodes
  }
}

}  // namespace
}  // namespace felt
