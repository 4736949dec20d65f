// The god-object proxy against the invariant it exists for: a thin cloth, still or moving, and a
// fold of two sheets, are never popped through.

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "core/cloth/cloth_fixtures.hpp"
#include "core/geometry/procedural_surfaces.hpp"
#include "core/geometry/triangle_geometry.hpp"
#include "core/haptics/god_object.hpp"
#include "core/haptics/god_object_fixtures.hpp"

namespace felt {
namespace {

using namespace felt::test;  // the god-object fixtures and expect_vec_near

// ---- a thin cloth: never popped through

/// Height of a height-field grid surface at (x, y), from its triangles at `alpha`.
Real height_at(const Sheet& sheet, Real alpha, Real x, Real y) {
  for (const Triangle& t : sheet.triangles) {
    Vec3 c[3];
    for (int k = 0; k < 3; ++k) c[k] = (1 - alpha) * sheet.from()[t[k]] + alpha * sheet.to()[t[k]];
    const Vec2 p(x, y);
    const Vec2 a = c[0].head<2>(), b = c[1].head<2>(), cc = c[2].head<2>();
    const Real area = (b - a).x() * (cc - a).y() - (b - a).y() * (cc - a).x();
    const Real u = ((b - p).x() * (cc - p).y() - (b - p).y() * (cc - p).x()) / area;
    const Real v = ((cc - p).x() * (a - p).y() - (cc - p).y() * (a - p).x()) / area;
    const Real w = 1 - u - v;
    if (u >= -1e-12 && v >= -1e-12 && w >= -1e-12)
      return u * c[0].z() + v * c[1].z() + w * c[2].z();
  }
  ADD_FAILURE() << "(" << x << ", " << y << ") is off the cloth";
  return 0;
}

struct Crossing {
  Real radius;
  Vec3 lateral;  ///< the device's sideways velocity, m/s
};

class ThinCloth : public ::testing::TestWithParam<Crossing> {};

// The device goes straight through a still cloth at 1 m/s, sampled at 1 kHz.
TEST_P(ThinCloth, AStillClothIsNeverPoppedThrough) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, 0);
  const Sheet cloth(0, g.positions, g.triangles);
  const HapticSurface surface = surface_of({&cloth});
  const Vec3 start(0.05, 0.05, 0.06);  // above a vertex of the grid
  GodObject proxy(plain_settings(r), start);
  for (int i = 1; i <= 200; ++i) {
    const Vec3 device = start + 1e-3 * i * (Vec3(0, 0, -1) + lateral);
    const HapticContact c = proxy.update(surface, device, 1e-3);
    ASSERT_GE(c.proxy.z(), r - 1e-9) << "tick " << i;
    if (device.z() < r) {
      ASSERT_TRUE(c.in_contact) << "tick " << i;
    }
  }
}

// The cloth itself moves 1 cm per 10 ms physics step toward a still device; the haptic loop
// renders ten states between each pair of snapshots.
TEST_P(ThinCloth, AClothMovingOntoAStillDeviceCarriesTheProxy) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, 0.05);
  Sheet cloth(0, g.positions, g.triangles);
  const Vec3 device(0.05, 0.05, 0);
  GodObject proxy(plain_settings(r), Vec3(0.05, 0.05, -0.01));
  std::uint64_t step = 1;
  for (int physics = 0; physics < 15; ++physics, ++step) {
    cloth.advance(shifted(cloth.to(), Vec3(0, 0, -0.01) + 0.01 * lateral));
    for (int k = 1; k <= 10; ++k) {
      const HapticSurface surface = surface_of({&cloth}, step, 0.1 * k);
      const HapticContact c = proxy.update(surface, device, 1e-3);
      const Real below = height_at(cloth, 0.1 * k, c.proxy.x(), c.proxy.y()) - c.proxy.z();
      ASSERT_GE(below, r - 1e-9) << "physics step " << physics << " tick " << k;
    }
  }
  // pushed down by the cloth, the proxy pulls the device along
  EXPECT_LT(proxy.update(surface_of({&cloth}, step - 1, 1), device, 1e-3).force.z(), 0);
}

// The device moves up at 1 m/s while the cloth comes down at 1 m/s.
TEST_P(ThinCloth, ADeviceAgainstAnOncomingClothStaysOnItsSide) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, 0.05);
  Sheet cloth(0, g.positions, g.triangles);
  const Vec3 start(0.05, 0.05, -0.05);
  GodObject proxy(plain_settings(r), start);
  std::uint64_t step = 1;
  int tick = 0;
  for (int physics = 0; physics < 10; ++physics, ++step) {
    cloth.advance(shifted(cloth.to(), Vec3(0, 0, -0.01)));
    for (int k = 1; k <= 10; ++k) {
      ++tick;
      const Vec3 device = start + 1e-3 * tick * (Vec3(0, 0, 1) + lateral);
      const HapticContact c = proxy.update(surface_of({&cloth}, step, 0.1 * k), device, 1e-3);
      const Real below = height_at(cloth, 0.1 * k, c.proxy.x(), c.proxy.y()) - c.proxy.z();
      ASSERT_GE(below, r - 1e-9) << "tick " << tick;
    }
  }
}

// A cloth that waves (each vertex on its own vertical path) while the device pushes through.
TEST_P(ThinCloth, AWavingClothIsNeverPoppedThrough) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, 0);
  Sheet cloth(0, g.positions, g.triangles);
  const auto wave = [&](Real time) {
    std::vector<Vec3> x = g.positions;
    for (Vec3& p : x) p.z() = 0.02 * std::sin(8 * p.x() + 5 * p.y() - 30 * time);
    return x;
  };
  cloth.advance(wave(0));
  const Vec3 start(0.05, 0.05, 0.06);
  GodObject proxy(plain_settings(r), start);
  std::uint64_t step = 1;
  int tick = 0;
  for (int physics = 1; physics <= 20; ++physics, ++step) {
    cloth.advance(wave(0.01 * physics));
    for (int k = 1; k <= 10; ++k) {
      ++tick;
      const Vec3 device = start + 1e-3 * tick * (Vec3(0, 0, -1) + lateral);
      const HapticContact c = proxy.update(surface_of({&cloth}, step, 0.1 * k), device, 1e-3);
      const Real below = c.proxy.z() - height_at(cloth, 0.1 * k, c.proxy.x(), c.proxy.y());
      ASSERT_GT(below, -1e-9) << "tick " << tick;
    }
  }
}

// A cloth at rest 5 mm from the proxy (too far for the proxy to hold on to it) whose next
// snapshot is 10 cm away: it sweeps past the proxy between two updates. The proxy is tested
// against that motion and keeps its side.
TEST_P(ThinCloth, AClothFasterThanItsLastStepStillPushes) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, r + 0.005);
  Sheet cloth(0, g.positions, g.triangles);
  const Vec3 device(0.05, 0.05, 0);
  GodObject proxy(plain_settings(r), device);
  EXPECT_FALSE(proxy.update(surface_of({&cloth}, 1, 1), device, 1e-3).in_contact);
  cloth.advance(shifted(cloth.to(), Vec3(0, 0, -0.1) + 0.1 * lateral));
  for (int k = 1; k <= 10; ++k) {
    const HapticContact c = proxy.update(surface_of({&cloth}, 2, 0.1 * k), device, 1e-3);
    const Real below = height_at(cloth, 0.1 * k, c.proxy.x(), c.proxy.y()) - c.proxy.z();
    ASSERT_GE(below, r - 1e-9) << "tick " << k;
  }
}

// A remote client that updates its proxy at 20 Hz while the cloth, stepped at 100 Hz, comes
// down 1 cm per step through its still device: several snapshots go by between two updates,
// and the cloth is on the device's other side at the next. The proxy is tested against all the
// motion since its previous update and is carried down with the cloth.
TEST_P(ThinCloth, AProxyUpdatedRarelyIsCarriedThroughEverySnapshotBetweenItsUpdates) {
  const auto [r, lateral] = GetParam();
  const Grid g = grid(21, 1, r + 0.025);
  Sheet cloth(0, g.positions, g.triangles);
  const Vec3 device(0.05, 0.05, 0);
  GodObject proxy(plain_settings(r), device);
  EXPECT_FALSE(proxy.update(surface_of({&cloth}, 1, 1), device, 1e-3).in_contact);
  std::uint64_t step = 1;
  for (int update = 1; update <= 3; ++update) {
    for (int physics = 0; physics < 5; ++physics) {
      cloth.advance(shifted(cloth.to(), Vec3(0, 0, -0.01) + 0.01 * lateral));
      ++step;
    }
    const Real alpha = update == 2 ? 0.5 : 1;  // anywhere in the newest pair
    const HapticContact c = proxy.update(surface_of({&cloth}, step, alpha), device, 0.05);
    const Real below = height_at(cloth, alpha, c.proxy.x(), c.proxy.y()) - c.proxy.z();
    ASSERT_GE(below, r - 1e-9) << "update " << update;
    if (update > 1) {  // the cloth has passed the device: it pushes the device down
      EXPECT_TRUE(c.in_contact) << "update " << update;
      EXPECT_LT(c.force.z(), 0) << "update " << update;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Paths, ThinCloth,
                         ::testing::Values(Crossing{0, Vec3::Zero()}, Crossing{0.01, Vec3::Zero()},
                                           Crossing{0, Vec3(0.3, 0.1, 0)},
                                           Crossing{0.01, Vec3(0.3, 0.1, 0)}));

// Two sheets 4 mm apart: the device goes through both, the proxy stays above the upper one,
// still and while the fold moves up into the device.
TEST(GodObjectFold, TheProxyStaysAboveTheUpperSheet) {
  for (const Real r : {0.0, 0.01}) {
    const Grid upper = grid(21, 1, 0);
    const Grid lower = grid(21, 1, -0.004);
    Sheet a(0, upper.positions, upper.triangles);
    Sheet b(1, lower.positions, lower.triangles);
    const Vec3 start(0.02, 0.03, 0.05);
    GodObject proxy(plain_settings(r), start);
    for (int i = 1; i <= 120; ++i) {
      const Vec3 device = start + 1e-3 * i * Vec3(0.2, 0, -1);
      const HapticContact c = proxy.update(surface_of({&a, &b}), device, 1e-3);
      ASSERT_GE(c.proxy.z(), r - 1e-9) << "tick " << i;
    }
    // now both sheets rise 5 mm per physics step against the device
    std::uint64_t step = 2;
    const Vec3 device = proxy.proxy() + Vec3(0, 0, -0.02);
    for (int physics = 0; physics < 6; ++physics, ++step) {
      a.advance(shifted(a.to(), Vec3(0, 0, 0.005)));
      b.advance(shifted(b.to(), Vec3(0, 0, 0.005)));
      for (int k = 1; k <= 10; ++k) {
        const HapticContact c = proxy.update(surface_of({&a, &b}, step, 0.1 * k), device, 1e-3);
        ASSERT_GE(c.proxy.z() - height_at(a, 0.1 * k, c.proxy.x(), c.proxy.y()), r - 1e-9)
            << "physics " << physics << " tick " << k;
      }
    }
  }
}

}  // namespace
}  // namespace felt
