// The local model (issue 26): what the server cuts near a proxy, and the client's surface made
// from it, against the server's own rendering of the same moving sheet. A fresh model gives the
// same forces as the server; a sheet moving at constant velocity is extrapolated exactly, so
// one model renders what the server renders long after; a model that differs from the surface
// shown takes over by a blend; the passivity rule's stiffness.

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "core/collision/triangle_query.hpp"
#include "core/geometry/triangle_geometry.hpp"
#include "core/haptics/extrapolated_surface.hpp"
#include "core/haptics/god_object.hpp"
#include "core/haptics/local_model.hpp"
#include "core/haptics/passive_stiffness.hpp"
#include "core/math/aabb.hpp"

namespace felt {
namespace {

constexpr int kSide = 13;        // vertices along a side of the sheet
constexpr Real kSpacing = 0.05;  // m between them: a 0.6 m square around the origin

/// A square sheet in the plane z = 0 at time 0 moving at `velocity`; the server's surfaces
/// of it, each from one state to the next, as the runtime's haptic frames show it.
struct MovingSheet {
  Vec3 velocity;
  std::vector<Triangle> triangles;
  std::vector<Vec3> normals;
  std::unique_ptr<TriangleQuery> query;
  SurfaceMotion motion{0, 0, 1};

  explicit MovingSheet(const Vec3& v) : velocity(v) {
    for (int j = 0; j + 1 < kSide; ++j) {
      for (int i = 0; i + 1 < kSide; ++i) {
        const auto at = [](int x, int y) { return static_cast<std::uint32_t>(y * kSide + x); };
        triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
    normals.assign(kSide * kSide, Vec3(0, 0, 1));
    query = make_triangle_query(TriangleQueryKind::kBruteForce, triangles, positions(0));
  }

  std::vector<Vec3> positions(Real t) const {
    std::vector<Vec3> out;
    for (int j = 0; j < kSide; ++j) {
      for (int i = 0; i < kSide; ++i) {
        out.emplace_back(kSpacing * (i - kSide / 2), kSpacing * (j - kSide / 2), 0);
        out.back() += t * velocity;
      }
    }
    return out;
  }

  /// The server's surface at `t`: the sheet from `t - dt` to `t`, rendered at its end.
  HapticSurface surface(Real t, Real dt) {
    auto states = std::make_shared<std::array<std::vector<Vec3>, 2>>(
        std::array{positions(t - dt), positions(t)});
    motion = motion.then((*states)[0], (*states)[1]);
    HapticSurface s;
    s.bodies.push_back(HapticBody{7, triangles, (*states)[0], (*states)[1], normals, normals,
                                  query.get(), motion});
    s.step = static_cast<std::uint64_t>(std::llround(t / dt)) + 1;
    s.alpha = 1;
    s.storage = states;
    return s;
  }
};

ProxySettings settings() {
  ProxySettings s;
  s.radius = 0.01;
  s.stiffness = 400;
  s.max_force = 20;
  return s;
}

/// The device presses into the sheet from 3 cm in front, sliding sideways.
Vec3 device_at(Real t) {
  return {0.01 + 0.1 * t, -0.02, 0.03 - 0.3 * t};
}

TEST(LocalModel, HoldsTheTrianglesNearThePointWithTheirVelocities) {
  MovingSheet sheet(Vec3(0.02, 0, -0.05));
  const Real dt = 0.01;
  const LocalModel model =
      cut_local_model(sheet.surface(0, dt), dt, Vec3(0, 0, 0.02), 0.06, 10'000);
  ASSERT_EQ(model.bodies.size(), 1u);
  const LocalModelBody& body = model.bodies[0];
  EXPECT_EQ(body.body_id, 7u);
  EXPECT_EQ(body.vertex_count, static_cast<std::uint32_t>(kSide * kSide));
  EXPECT_EQ(body.triangle_count, sheet.triangles.size());
  EXPECT_FALSE(model.truncated);
  EXPECT_TRUE(well_formed(model));
  // every triangle with a point within 6 cm of (0, 0, 2 cm): its foot within sqrt(6² - 2²) cm
  // of the origin in the plane; by brute force
  const std::vector<Vec3> now = sheet.positions(0);
  std::size_t expected = 0;
  for (std::size_t t = 0; t < sheet.triangles.size(); ++t) {
    const ClosestPoint nearest =
        closest_point_on_triangle(Vec3(0, 0, 0.02), now[sheet.triangles[t][0]],
                                  now[sheet.triangles[t][1]], now[sheet.triangles[t][2]]);
    if ((nearest.point - Vec3(0, 0, 0.02)).norm() <= 0.06) ++expected;
  }
  EXPECT_GT(expected, 10u);
  EXPECT_EQ(body.triangle_ids.size(), expected);
  for (std::size_t i = 0; i < body.vertex_ids.size(); ++i) {
    EXPECT_LT((body.positions[i] - now[body.vertex_ids[i]]).norm(), 1e-15);
    EXPECT_LT((body.velocities[i] - sheet.velocity).norm(), 1e-12);
  }
  const LocalModel few = cut_local_model(sheet.surface(0, dt), dt, Vec3(0, 0, 0.02), 0.06, 4);
  EXPECT_TRUE(few.truncated);
  EXPECT_EQ(few.bodies[0].triangle_ids.size(), 4u);
}

TEST(LocalModel, ABodyWithoutNormalsIsLeftOut) {
  // a served scene's first frame after a quiet spell: its snapshot was made without them
  MovingSheet sheet(Vec3::Zero());
  HapticSurface surface = sheet.surface(0, 0.01);
  ASSERT_EQ(cut_local_model(surface, 0.01, Vec3::Zero(), 0.1, 100).bodies.size(), 1u);
  surface.bodies[0].normals_to = {};
  EXPECT_TRUE(cut_local_model(surface, 0.01, Vec3::Zero(), 0.1, 100).bodies.empty());
}

TEST(LocalModel, AModelWithABadIdOrNumberIsNotWellFormed) {
  MovingSheet sheet(Vec3::Zero());
  const LocalModel good = cut_local_model(sheet.surface(0, 0.01), 0.01, Vec3::Zero(), 0.1, 100);
  ASSERT_TRUE(well_formed(good));
  LocalModel bad = good;
  bad.bodies[0].corners[0][1] = bad.bodies[0].vertex_count;
  EXPECT_FALSE(well_formed(bad));
  bad = good;
  bad.bodies[0].velocities[0].x() = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_FALSE(well_formed(bad));
  bad = good;
  bad.bodies[0].triangle_ids.pop_back();
  EXPECT_FALSE(well_formed(bad));
  // how the surface gives: a stiffness that is negative or not finite, a push that is not
  bad = good;
  bad.bodies[0].stiffness = -1;
  EXPECT_FALSE(well_formed(bad));
  bad.bodies[0].stiffness = std::numeric_limits<Real>::infinity();
  EXPECT_FALSE(well_formed(bad));
  bad = good;
  bad.push.z() = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_FALSE(well_formed(bad));
  bad.push.z() = 2;  // a push and a stiffness in range are fine
  bad.bodies[0].stiffness = 1500;
  EXPECT_TRUE(well_formed(bad));
}

TEST(ExtrapolatedSurface, ASheetMovingAtConstantVelocityIsWhereItsVelocitiesPutIt) {
  MovingSheet sheet(Vec3(0.02, -0.01, -0.05));
  const Real dt = 0.004;
  ExtrapolatedSurface local;
  local.take(cut_local_model(sheet.surface(0, dt), dt, Vec3::Zero(), 0.2, 10'000), 1.5);
  for (const Real t : {0.0, 0.05, 0.2}) {
    const HapticSurface at = local.advance(1.5 + t);
    const std::vector<Vec3> truth = sheet.positions(t);
    std::size_t seen = 0;
    for (std::uint32_t v = 0; v < truth.size(); ++v) {
      const Vec3 p = at.vertex(at.bodies[0], v);
      if (!p.allFinite()) continue;  // not in the model
      EXPECT_LT((p - truth[v]).norm(), 1e-12) << "vertex " << v << " at " << t << " s";
      ++seen;
    }
    EXPECT_GT(seen, 20u);
  }
}

TEST(ExtrapolatedSurface, AFreshModelEveryTickRendersTheServersForces) {
  MovingSheet sheet(Vec3(0.01, 0, 0.04));  // toward the device
  const Real dt = 0.001;
  GodObject server(settings(), device_at(0));
  GodObject client(settings(), device_at(0));
  ExtrapolatedSurface local;
  int touching = 0;
  for (int k = 1; k <= 150; ++k) {
    const Real t = k * dt;
    const HapticSurface truth = sheet.surface(t, dt);
    local.take(cut_local_model(truth, dt, device_at(t), 0.1, 10'000), t);
    const HapticContact expected = server.update(truth, device_at(t), dt);
    const HapticContact got = client.update(local.advance(t), device_at(t), dt);
    ASSERT_EQ(got.in_contact, expected.in_contact) << "tick " << k;
    EXPECT_LT((got.force - expected.force).norm(), 1e-9) << "tick " << k;
    EXPECT_LT((got.proxy - expected.proxy).norm(), 1e-12) << "tick " << k;
    touching += expected.in_contact ? 1 : 0;
  }
  EXPECT_GT(touching, 50);
}

TEST(ExtrapolatedSurface, OneModelOfASheetAtConstantVelocityRendersTheServersForcesLater) {
  MovingSheet sheet(Vec3(0.02, 0, 0.05));
  const Real dt = 0.001;
  GodObject server(settings(), device_at(0));
  GodObject client(settings(), device_at(0));
  ExtrapolatedSurface local;
  local.take(cut_local_model(sheet.surface(0, dt), dt, device_at(0), 0.2, 10'000), 0);
  Real largest = 0;
  int touching = 0;
  for (int k = 1; k <= 200; ++k) {  // 0.2 s on one model
    const Real t = k * dt;
    const HapticContact expected = server.update(sheet.surface(t, dt), device_at(t), dt);
    const HapticContact got = client.update(local.advance(t), device_at(t), dt);
    ASSERT_EQ(got.in_contact, expected.in_contact) << "tick " << k;
    EXPECT_LT((got.force - expected.force).norm(), 1e-9) << "tick " << k;
    largest = std::max(largest, expected.force.norm());
    touching += expected.in_contact ? 1 : 0;
  }
  EXPECT_GT(touching, 50);
  EXPECT_GT(largest, 5.0);  // pressed well in: the comparison is of real forces
}

TEST(ExtrapolatedSurface, TrianglesLeftOutOfANewModelAreNotThere) {
  MovingSheet sheet(Vec3::Zero());
  ExtrapolatedSurface local;
  local.take(cut_local_model(sheet.surface(0, 0.01), 0.01, Vec3(0.2, 0, 0), 0.05, 10'000), 0);
  local.advance(0);
  // the proxy moved to the other side: the first model's vertices are gone from the surface
  local.take(cut_local_model(sheet.surface(0, 0.01), 0.01, Vec3(-0.2, 0, 0), 0.05, 10'000), 0);
  const std::vector<Vec3> truth = sheet.positions(0);
  // each of the three states the surface cycles through, once rewritten
  for (int tick = 1; tick <= 3; ++tick) {
    const HapticSurface at = local.advance(0.001 * tick);
    for (std::uint32_t v = 0; v < truth.size(); ++v) {
      const Vec3 p = at.vertex(at.bodies[0], v);
      if (truth[v].x() > 0.1) {
        EXPECT_FALSE(p.allFinite()) << "vertex " << v;
      }
      if (std::abs(truth[v].x() + 0.2) < 1e-9 && std::abs(truth[v].y()) < 1e-9) {
        EXPECT_TRUE(p.allFinite()) << "vertex " << v;
      }
    }
    std::vector<std::uint32_t> listed;
    at.bodies[0].query->collect(Aabb{Vec3::Constant(-1), Vec3::Constant(1)}, listed);
    EXPECT_FALSE(listed.empty());
    for (const std::uint32_t t : listed) {
      for (const std::uint32_t v : sheet.triangles[t]) EXPECT_LT(truth[v].x(), 0);
    }
  }
}

TEST(ExtrapolatedSurface, ANewModelTakesOverFromTheSurfaceShownByEqualSharesOverTheBlend) {
  // a still sheet at z = 0 shown for 5 ticks, then a model of it 3 cm back: the surface does not
  // jump there but goes by equal steps of 3 cm × 1 ms / kModelBlend, and stays there after
  MovingSheet sheet(Vec3::Zero());
  const Real tick = 0.001;
  ExtrapolatedSurface local;
  local.take(cut_local_model(sheet.surface(0, 0.01), 0.01, Vec3::Zero(), 0.1, 10'000), 0);
  for (int k = 0; k <= 5; ++k) local.advance(k * tick);
  LocalModel back = cut_local_model(sheet.surface(0, 0.01), 0.01, Vec3::Zero(), 0.1, 10'000);
  for (Vec3& p : back.bodies[0].positions) p.z() -= 0.03;
  local.take(back, 5 * tick);
  const int blend_ticks = static_cast<int>(std::lround(kModelBlend / tick));
  for (int k = 6; k <= 5 + blend_ticks + 5; ++k) {
    const HapticSurface at = local.advance(k * tick);
    const Real gone = std::min(1.0, (k - 5) * tick / kModelBlend);  // of the difference
    for (const std::uint32_t v : back.bodies[0].vertex_ids) {
      const Vec3 p = at.vertex(at.bodies[0], v);
      EXPECT_NEAR(p.z(), -0.03 * gone, 1e-12) << "vertex " << v << " at tick " << k;
      EXPECT_NEAR(p.x(), sheet.positions(0)[v].x(), 1e-12);
    }
  }
}

TEST(PassiveStiffness, FollowsTheDelayedWallsBoundBelowTheProxysStiffness) {
  // b > K (T/2 + d): with b = 20 N·s/m and T = 1 ms, 400 N/m holds to d = 49.5 ms
  EXPECT_DOUBLE_EQ(passive_stiffness(400, 20, 1e-3, 0), 400);
  EXPECT_NEAR(passive_stiffness(400, 20, 1e-3, 0.0495), 400, 1e-9);
  EXPECT_NEAR(passive_stiffness(400, 20, 1e-3, 0.0995), 200, 1e-9);
  EXPECT_NEAR(passive_stiffness(400, 20, 1e-3, 0.1995), 100, 1e-9);
  Real previous = 400;
  for (Real d = 0; d < 1; d += 0.01) {
    const Real k = passive_stiffness(400, 20, 1e-3, d);
    EXPECT_LE(k, previous);
    EXPECT_GE(k, 0);
    previous = k;
  }
  EXPECT_DOUBLE_EQ(passive_stiffness(400, 20, 1e-3, std::numeric_limits<Real>::quiet_NaN()), 400);
  EXPECT_DOUBLE_EQ(passive_stiffness(400, 20, 1e-3, -1), 400);
  EXPECT_DOUBLE_EQ(passive_stiffness(400, 0, 1e-3, 0.1), 0);
}

/// The largest K in [0, cap] with b >= K T/2 + K K / (K + k_o) d, by bisection on the rule
/// itself (k_o = 0: the whole K late).
Real largest_passing(Real cap, Real b, Real T, Real d, Real k_o) {
  const auto passes = [&](Real k) {
    const Real late_share = k_o > 0 ? k / (k + k_o) : 1;
    return k * T / 2 + k * late_share * d <= b;
  };
  if (passes(cap)) return cap;
  Real lo = 0, hi = cap;
  for (int i = 0; i < 200; ++i) {
    const Real mid = (lo + hi) / 2;
    (passes(mid) ? lo : hi) = mid;
  }
  return lo;
}

TEST(PassiveStiffness, OnlyTheLateShareOfAYieldingSurfaceCountsTheDelay) {
  // against a surface of known stiffness only K K / (K + k_o) comes a round trip late: the
  // rule's bound, found by bisection, for surfaces from soft to rigid
  for (const Real k_o : {10.0, 100.0, 400.0, 2000.0, 1e4, 1e6, 1e9}) {
    for (const Real d : {0.0, 0.01, 0.05, 0.1, 0.2}) {
      SCOPED_TRACE(k_o);
      SCOPED_TRACE(d);
      const Real k = passive_stiffness(400, 20, 1e-3, d, k_o);
      EXPECT_NEAR(k, largest_passing(400, 20, 1e-3, d, k_o), 1e-9 * 400);
      EXPECT_GE(k, passive_stiffness(400, 20, 1e-3, d));  // never below the whole-K rule
    }
  }
  // the cube of the remote-haptics study (k_o about 2 kN/m) keeps the proxy's 400 N/m at 100 ms;
  // a soft surface is held near the whole-K rule
  EXPECT_DOUBLE_EQ(passive_stiffness(400, 20, 1e-3, 0.1, 2000), 400);
  EXPECT_NEAR(passive_stiffness(400, 20, 1e-3, 0.1, 1), passive_stiffness(400, 20, 1e-3, 0.1), 2);
  // a rigid surface leaves the sampling's bound, K <= 2 b / T
  EXPECT_NEAR(passive_stiffness(1e6, 20, 1e-3, 0.1, 1e12), 4e4, 1);
  // unknown, negative or non-finite: the whole K late
  EXPECT_DOUBLE_EQ(passive_stiffness(400, 20, 1e-3, 0.1, 0), passive_stiffness(400, 20, 1e-3, 0.1));
  EXPECT_DOUBLE_EQ(passive_stiffness(400, 20, 1e-3, 0.1, -5),
                   passive_stiffness(400, 20, 1e-3, 0.1));
  EXPECT_DOUBLE_EQ(passive_stiffness(400, 20, 1e-3, 0.1, std::numeric_limits<Real>::infinity()),
                   passive_stiffness(400, 20, 1e-3, 0.1));
}

}  // namespace
}  // namespace felt
