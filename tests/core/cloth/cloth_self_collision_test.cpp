// Cloth self-collision: the hashed search against brute force, and particles of a cloth that
// never pass through its own triangles.

#include "core/cloth/cloth_self_collision.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <utility>

#include <gtest/gtest.h>

#include "core/cloth/cloth_body.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/collision/collider.hpp"
#include "core/geometry/triangle_geometry.hpp"

namespace felt {
namespace {

Real distance_to_triangle(std::span<const Vec3> x, const Triangle& tri, std::uint32_t p) {
  return (x[p] - closest_point_on_triangle(x[p], x[tri[0]], x[tri[1]], x[tri[2]]).point).norm();
}

bool is_corner(const Triangle& tri, std::uint32_t p) {
  return std::find(tri.begin(), tri.end(), p) != tri.end();
}

/// The smallest distance from any particle to any triangle it is not a corner of.
Real closest_approach(std::span<const Triangle> triangles, std::span<const Vec3> x) {
  Real closest = std::numeric_limits<Real>::infinity();
  for (const Triangle& tri : triangles) {
    for (std::uint32_t p = 0; p < x.size(); ++p) {
      if (!is_corner(tri, p)) closest = std::min(closest, distance_to_triangle(x, tri, p));
    }
  }
  return closest;
}

/// Height of the surface made of `triangles` straight above or below p: y interpolated on a
/// triangle whose projection onto the floor (xz) contains p, or none when no projection does.
std::optional<Real> surface_height_under(std::span<const Triangle> triangles,
                                         std::span<const Vec3> x, const Vec3& p) {
  for (const Triangle& tri : triangles) {
    const Vec2 a(x[tri[0]].x(), x[tri[0]].z());
    const Vec2 b(x[tri[1]].x(), x[tri[1]].z());
    const Vec2 c(x[tri[2]].x(), x[tri[2]].z());
    const Vec2 q(p.x(), p.z());
    const auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
    const Real area = cross(b - a, c - a);
    if (area == 0) continue;
    const Real wb = cross(q - a, c - a) / area;
    const Real wc = cross(b - a, q - a) / area;
    if (wb < 0 || wc < 0 || wb + wc > 1) continue;
    return (1 - wb - wc) * x[tri[0]].y() + wb * x[tri[1]].y() + wc * x[tri[2]].y();
  }
  return std::nullopt;
}

/// One step as the world takes it: integrate, collide with the colliders, then with itself.
void step(ClothBody& body, ClothSelfCollision& self, std::span<const Collider> colliders, Real t,
          Real h) {
  body.integrator().step(body, body.state(), t, h);
  resolve_collisions(colliders, body.inv_mass(), body.params().thickness, body.state());
  self.resolve(body.model().triangles, body.inv_mass(), body.params().thickness, body.state());
}

class HashedSearch : public ::testing::TestWithParam<Real> {};

TEST_P(HashedSearch, FindsExactlyThePairsBruteForceFinds) {
  // a 15 × 15 sheet crumpled into a ball a third of its size: folds, random dents, many
  // particles near triangles of other parts of the sheet
  GridClothSpec spec;
  spec.nx = spec.ny = 15;
  const ClothModel model = make_grid_cloth(spec);
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> dent(-0.04, 0.04);
  std::vector<Vec3> x;
  for (const Vec3& rest : model.rest_positions) {
    const Vec3 folded(0.3 * rest.x(), 0.3 * rest.y(), 0.1 * std::sin(9 * rest.x() + 5 * rest.y()));
    x.push_back(folded + Vec3(dent(rng), dent(rng), dent(rng)));
  }
  const Real thickness = GetParam();
  std::vector<SelfProximity> expected;
  for (std::uint32_t t = 0; t < model.triangles.size(); ++t) {
    for (std::uint32_t p = 0; p < x.size(); ++p) {
      const Triangle& tri = model.triangles[t];
      if (!is_corner(tri, p) && distance_to_triangle(x, tri, p) < thickness) {
        expected.push_back({p, t});
      }
    }
  }
  ClothSelfCollision self;
  const auto found = self.find_proximities(model.triangles, x, thickness);
  std::vector<SelfProximity> got(found.begin(), found.end());
  const auto order = [](const SelfProximity& a, const SelfProximity& b) {
    return std::pair(a.triangle, a.particle) < std::pair(b.triangle, b.particle);
  };
  std::sort(got.begin(), got.end(), order);
  EXPECT_GT(expected.size(), 20u);
  EXPECT_EQ(got, expected);
}

// thinner than, about as thick as, and thicker than the crumpled sheet's mean edge (≈ 0.03 m)
INSTANTIATE_TEST_SUITE_P(Thicknesses, HashedSearch, ::testing::Values(0.005, 0.02, 0.1));

/// A 0.5 m square of 6 × 6 particles lying at y = 0, with one more particle, not joined to it,
/// 20 cm above a point inside one of its triangles.
ClothBody patch_and_bead(Real bead_mass) {
  GridClothSpec spec;
  spec.nx = spec.ny = 6;
  spec.width = spec.height = 0.5;
  spec.plane = GridClothSpec::Plane::kXZ;
  ClothModel model = make_grid_cloth(spec);
  model.rest_positions.push_back(Vec3(0.013, 0.2, 0.021));
  model.uv.push_back(Vec2::Zero());
  model.mass.push_back(bead_mass);
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 400, 0.2};
  params.spring(SpringKind::kShear) = {true, 100, 0.05};
  params.thickness = 0.005;
  ClothBody body("patch", std::make_shared<const ClothModel>(std::move(model)), params,
                 make_integrator("velocity_verlet"));
  body.set_gravity(Vec3(0, -9.81, 0));
  return body;
}

TEST(ClothSelfCollision, ParticleFallingOnAPinnedPatchStopsAtTheThickness) {
  ClothBody body = patch_and_bead(0.01);
  const std::uint32_t bead = 36;
  for (std::uint32_t p = 0; p < bead; ++p) body.pin(p);
  ClothSelfCollision self;
  const Real h = 1e-3;
  for (int n = 0; n < 1500; ++n) {  // it lands after 0.2 s at 2 m/s, 2 mm a step
    step(body, self, {}, n * h, h);
    ASSERT_GE(body.state().x[bead].y(), body.params().thickness - 1e-12) << n;
  }
  EXPECT_NEAR(body.state().x[bead].y(), body.params().thickness, 1e-12);
  EXPECT_LT(body.state().v[bead].norm(), 1e-12);        // inelastic: it came to rest, no bounce
  EXPECT_NEAR(body.state().x[bead].x(), 0.013, 1e-12);  // straight down: nothing pushed it aside
  EXPECT_NEAR(body.state().x[bead].z(), 0.021, 1e-12);
}

TEST(ClothSelfCollision, ParticleFallingOnAHangingPatchRidesItDown) {
  // the patch hangs from its border; the heavy bead dents it and must stay on top
  ClothBody body = patch_and_bead(0.05);
  const std::uint32_t bead = 36;
  for (std::uint32_t p = 0; p < bead; ++p) {
    if (p % 6 == 0 || p % 6 == 5 || p / 6 == 0 || p / 6 == 5) body.pin(p);
  }
  ClothSelfCollision self;
  const Real h = 1e-3;
  Real lowest_clearance = std::numeric_limits<Real>::infinity();
  for (int n = 0; n < 2000; ++n) {
    step(body, self, {}, n * h, h);
    const std::span<const Vec3> x = body.state().x;
    const std::optional<Real> surface = surface_height_under(body.model().triangles, x, x[bead]);
    ASSERT_TRUE(surface.has_value()) << n;  // it fell straight onto the patch
    lowest_clearance = std::min(lowest_clearance, x[bead].y() - *surface);
  }
  EXPECT_GT(lowest_clearance, 0.9 * body.params().thickness);  // never through, nor much closer
  EXPECT_GT(closest_approach(body.model().triangles, body.state().x),
            0.9 * body.params().thickness);
  EXPECT_LT(body.state().x[bead].y(), -0.01);  // it did dent the patch
}

TEST(ClothSelfCollision, ConservesMomentumAndTheCentreOfMass) {
  // every push and impulse acts equally and oppositely on the particle and the triangle
  GridClothSpec spec;
  spec.nx = spec.ny = 10;
  const ClothModel model = make_grid_cloth(spec);
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> u(-1, 1);
  std::uniform_real_distribution<Real> mass(0.5, 2);
  ParticleState state;
  std::vector<Real> inv_mass;
  for (const Vec3& rest : model.rest_positions) {
    state.x.push_back(0.2 * rest + 0.03 * Vec3(u(rng), u(rng), u(rng)));
    state.v.push_back(Vec3(u(rng), u(rng), u(rng)));
    inv_mass.push_back(1 / mass(rng));
  }
  const auto momentum = [&] {
    Vec3 sum = Vec3::Zero();
    for (std::size_t p = 0; p < state.size(); ++p) sum += state.v[p] / inv_mass[p];
    return sum;
  };
  const auto moment = [&] {
    Vec3 sum = Vec3::Zero();
    for (std::size_t p = 0; p < state.size(); ++p) sum += state.x[p] / inv_mass[p];
    return sum;
  };
  const Vec3 momentum_before = momentum();
  const Vec3 moment_before = moment();
  ClothSelfCollision self;
  EXPECT_GT(self.resolve(model.triangles, inv_mass, 0.02, state), 20u);
  EXPECT_LT((momentum() - momentum_before).norm(), 1e-12);
  EXPECT_LT((moment() - moment_before).norm(), 1e-12);
}

TEST(ClothSelfCollision, FoldedSheetEndsWithItsHalvesApart) {
  // a sheet on the floor with its right half folded over the left one along a rounded crease,
  // 10 cm above it: the half falls onto the other and must end lying on it, not through it
  GridClothSpec spec;
  spec.nx = 21;
  spec.ny = 11;
  spec.width = 1;
  spec.height = 0.5;
  spec.plane = GridClothSpec::Plane::kXZ;
  spec.total_mass = 0.5;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 500, 0.1};
  params.spring(SpringKind::kShear) = {true, 100, 0.05};
  params.spring(SpringKind::kBend) = {true, 0.2, 0.005};
  params.drag = 0.02;
  params.thickness = 0.01;
  const ClothModel model = make_grid_cloth(spec);
  ClothBody body("sheet", std::make_shared<const ClothModel>(model), params,
                 make_integrator("symplectic_euler"));
  body.set_gravity(Vec3(0, -9.81, 0));
  // x > 0 is bent, length-preserving, round a half circle of radius R, then runs back flat
  const Real radius = 0.05;
  std::vector<std::uint32_t> top;
  for (std::uint32_t p = 0; p < model.particle_count(); ++p) {
    Vec3& x = body.state().x[p];
    const Real s = x.x();
    x.y() = params.thickness;
    if (s <= 0) continue;
    const Real angle = std::min(s / radius, M_PI);
    x.x() = radius * std::sin(angle) - std::max(Real{0}, s - M_PI * radius);
    x.y() += radius * (1 - std::cos(angle));
    if (s > M_PI * radius) top.push_back(p);
  }
  std::vector<Triangle> bottom;
  for (const Triangle& tri : model.triangles) {
    if (std::all_of(tri.begin(), tri.end(),
                    [&](std::uint32_t p) { return model.rest_positions[p].x() <= 0; })) {
      bottom.push_back(tri);
    }
  }
  const std::vector<Collider> floor(1);  // y = 0, normal +y
  ClothSelfCollision self;
  const Real h = 1e-3;
  Real lowest_clearance = std::numeric_limits<Real>::infinity();
  for (int n = 0; n < 3000; ++n) {
    step(body, self, floor, n * h, h);
    for (std::uint32_t p : top) {
      const std::span<const Vec3> x = body.state().x;
      const std::optional<Real> surface = surface_height_under(bottom, x, x[p]);
      if (surface) lowest_clearance = std::min(lowest_clearance, x[p].y() - *surface);
    }
  }
  // the top half lies on the bottom one, the thickness above it, and never went through
  EXPECT_GT(lowest_clearance, 0.9 * params.thickness);
  const std::span<const Vec3> x = body.state().x;
  for (std::uint32_t p : top) EXPECT_LT(x[p].y(), 3 * params.thickness) << p;  // it fell
  EXPECT_GT(closest_approach(body.model().triangles, x), 0.9 * params.thickness);
}

}  // namespace
}  // namespace felt
