// Static colliders: signed distances against brute force, contacts against the signed distance
// of every particle, Coulomb friction against its analytic deceleration, and cloth that never
// sinks into what it rests on.

#include "core/collision/collider.hpp"

#include <random>

#include <gtest/gtest.h>

#include "core/cloth/cloth_grid.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

Collider sphere(Vec3 c, Real r) {
  Collider s;
  s.shape = Collider::Shape::kSphere;
  s.center = c;
  s.radius = r;
  return s;
}

Collider box(Vec3 c, Vec3 half) {
  Collider b;
  b.shape = Collider::Shape::kBox;
  b.center = c;
  b.half_extents = half;
  return b;
}

Collider capsule(Vec3 a, Vec3 b, Real r) {
  Collider c;
  c.shape = Collider::Shape::kCapsule;
  c.center = a;
  c.end = b;
  c.radius = r;
  return c;
}

/// Distance from p to a densely sampled box surface (the brute-force reference).
Real sampled_box_distance(const Vec3& p, const Vec3& c, const Vec3& h) {
  Real best = std::numeric_limits<Real>::infinity();
  const int n = 120;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side : {-1, 1}) {
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
          Vec3 q;
          q[axis] = side * h[axis];
          q[(axis + 1) % 3] = (2.0 * i / n - 1) * h[(axis + 1) % 3];
          q[(axis + 2) % 3] = (2.0 * j / n - 1) * h[(axis + 2) % 3];
          best = std::min(best, (p - c - q).norm());
        }
      }
    }
  }
  return best;
}

TEST(Collider, BoxDistanceMatchesASampledSurface) {
  const Vec3 c(0.1, -0.2, 0.3), h(0.5, 0.2, 0.8);
  const Collider b = box(c, h);
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> u(-1.5, 1.5);
  for (int k = 0; k < 60; ++k) {
    const Vec3 p = c + Vec3(u(rng), u(rng), u(rng));
    const SignedDistance sd = signed_distance(b, p);
    const Vec3 local = (p - c).cwiseAbs();
    const bool inside = (local.array() < h.array()).all();
    EXPECT_EQ(sd.distance < 0, inside) << p.transpose();
    // the sampling spacing bounds the reference's error
    EXPECT_NEAR(std::abs(sd.distance), sampled_box_distance(p, c, h), 0.02) << p.transpose();
  }
}

TEST(Collider, NormalsAreTheGradientOfTheDistance) {
  const Collider shapes[] = {sphere(Vec3(0, 1, 0), 0.4), box(Vec3::Zero(), Vec3(0.3, 0.2, 0.5)),
                             capsule(Vec3(-1, 0, 0), Vec3(1, 0.5, 0), 0.25)};
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> u(-1.2, 1.2);
  const Real eps = 1e-6;
  for (const Collider& shape : shapes) {
    for (int k = 0; k < 100; ++k) {
      const Vec3 p(u(rng), u(rng) + 0.5, u(rng));
      const SignedDistance sd = signed_distance(shape, p);
      Vec3 gradient;
      for (int a = 0; a < 3; ++a) {
        Vec3 d = Vec3::Zero();
        d[a] = eps;
        gradient[a] =
            (signed_distance(shape, p + d).distance - signed_distance(shape, p - d).distance) /
            (2 * eps);
      }
      // away from the box's medial planes the distance is smooth
      if (std::abs(gradient.norm() - 1) > 1e-3) continue;
      EXPECT_LT((gradient - sd.normal).norm(), 1e-4) << p.transpose();
    }
  }
  EXPECT_NEAR(signed_distance(sphere(Vec3::Zero(), 1), Vec3(0, 3, 4)).distance, 4, 1e-15);
  EXPECT_NEAR(signed_distance(capsule(Vec3::Zero(), Vec3(2, 0, 0), 0.5), Vec3(1, 2, 0)).distance,
              1.5, 1e-15);
}

TEST(Collider, EveryParticleWithinTheThicknessIsResolvedAndNoOther) {
  // particles scattered around each shape, many in a thin shell about the thickness: those the
  // signed distance puts closer than the thickness move out to it, the others stay (the test
  // that skips far particles must never skip a near one)
  const Real thickness = 0.01;
  Collider floor;
  floor.normal = Vec3(1, 2, 2).normalized();
  floor.center = Vec3(0.1, -0.2, 0.3);
  const std::vector<Collider> shapes = {floor, sphere(Vec3(0.2, 0.1, 0), 0.3),
                                        box(Vec3(0, 0.1, 0.2), Vec3(0.3, 0.1, 0.2)),
                                        capsule(Vec3(-0.3, 0, 0), Vec3(0.4, 0.2, 0.1), 0.15)};
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> coordinate(-0.8, 0.8);
  for (const Collider& shape : shapes) {
    ParticleState state;
    while (state.size() < 4000) {
      // a point, then along the distance's gradient to a chosen distance from the surface
      const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
      const SignedDistance sd = signed_distance(shape, p);
      const Real wanted = std::uniform_real_distribution<Real>(-0.5, 3)(rng) * thickness;
      const Vec3 q = p + (wanted - sd.distance) * sd.normal;
      state.x.push_back(state.size() % 4 == 0 ? p : q);
      state.v.push_back(Vec3::Zero());
    }
    const ParticleState before = state;
    const std::vector<Real> inv_mass(state.size(), 1);
    std::size_t near = 0;
    for (const Vec3& p : before.x) near += signed_distance(shape, p).distance < thickness;
    ASSERT_GT(near, 1000u);
    EXPECT_EQ(resolve_collisions(std::span(&shape, 1), inv_mass, thickness, state), near);
    for (std::size_t p = 0; p < state.size(); ++p) {
      const Real distance = signed_distance(shape, before.x[p]).distance;
      if (distance < thickness) {
        EXPECT_NEAR(signed_distance(shape, state.x[p]).distance, thickness, 1e-9) << p;
      } else {
        EXPECT_EQ(state.x[p], before.x[p]) << p;
      }
    }
  }
}

TEST(Collider, CoulombFrictionDeceleratesAtMuG) {
  // a single particle sliding on the floor: v(t) = v0 − μ g t until it stops
  auto model = std::make_shared<ClothModel>();
  model->rest_positions = {Vec3(0, 0.005, 0)};
  model->uv = {Vec2::Zero()};
  model->mass = {0.1};
  const Real mu = 0.4, g = 9.81, v0 = 2, h = 1e-3;
  World world(WorldSettings{Vec3(0, -g, 0), h, 100, 6});
  world.add_collider([&] {
    Collider floor;
    floor.friction = mu;
    return floor;
  }());
  world.add_body(ClothBody("puck", model, ClothParams{}, make_integrator("symplectic_euler")));
  world.cloths()[0].state().v[0] = Vec3(v0, 0, 0);
  for (int n = 1; n <= 300; ++n) {
    world.step();
    ASSERT_NEAR(world.cloths()[0].state().v[0].x(), v0 - mu * g * n * h, 1e-9) << n;
    ASSERT_NEAR(world.cloths()[0].state().x[0].y(), 0.005, 1e-12);
  }
  for (int n = 0; n < 1000; ++n) world.step();
  EXPECT_EQ(world.cloths()[0].state().v[0], Vec3::Zero());  // static friction holds it
}

TEST(Collider, ClothDrapedOverABallNeverSinksIntoItOrTheFloor) {
  GridClothSpec spec;
  spec.nx = spec.ny = 16;
  spec.width = spec.height = 1.2;
  spec.total_mass = 0.3;
  spec.plane = GridClothSpec::Plane::kXZ;
  spec.center = Vec3(0.05, 0.8, 0.02);
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 300, 0.05};
  params.spring(SpringKind::kShear) = {true, 80, 0.02};
  params.spring(SpringKind::kBend) = {true, 3, 0.005};
  params.drag = 0.02;
  params.thickness = 0.01;
  World world(WorldSettings{Vec3(0, -9.81, 0), 1e-3, 100, 6});
  Collider floor;
  world.add_collider(floor);
  world.add_collider(sphere(Vec3(0, 0.3, 0), 0.3));
  world.add_body(ClothBody("sheet", std::make_shared<const ClothModel>(make_grid_cloth(spec)),
                           params, make_integrator("symplectic_euler")));
  const ClothBody& body = world.cloths()[0];
  for (int n = 0; n < 4000; ++n) {
    world.step();
    for (const Vec3& x : body.state().x) {
      for (const Collider& c : world.colliders()) {
        ASSERT_GE(signed_distance(c, x).distance, params.thickness - 1e-9) << "step " << n;
      }
    }
  }
  // it came to rest on the ball: the particle above the top is held at radius + thickness
  Real highest = -1;
  for (const Vec3& x : body.state().x) highest = std::max(highest, x.y());
  EXPECT_NEAR(highest, 0.6 + params.thickness, 0.01);
  EXPECT_LT(body.kinetic_energy(), 1e-3);
}

}  // namespace
}  // namespace felt
