// The client's local renderer (client_cpp/local_renderer.hpp) on a surface that gives: a flat
// patch mounted on a spring k_o, pressed by the proxy's spring k_p. In series the device feels
// k_eff = k_p k_o / (k_p + k_o) times its depth below the unpushed surface, whatever push the
// model in hand was cut under (a fresh one, a stale one, none); without the surface's stiffness
// the renderer takes the copy as rigid and feels k_p times the depth below the copy. A late tick
// catches up with the ticks it missed.

#include "local_renderer.hpp"

#include <gtest/gtest.h>

namespace felt::client {
namespace {

constexpr double kProxyStiffness = 400;  // N/m
constexpr double kRadius = 0.02;         // m

felt::v1::ProxySettings settings() {
  felt::v1::ProxySettings s;
  s.set_radius(kRadius);
  s.set_stiffness(kProxyStiffness);
  s.set_damping(0);
  s.set_max_force(100);
  s.set_max_force_change(0);
  s.set_static_friction(0);
  s.set_dynamic_friction(0);
  s.set_force_shading(true);
  return s;
}

/// A 1 m square patch in the plane z = `height`, still, cut under `push` (N, on the device),
/// with the surface stiffness `stiffness`.
felt::LocalModel patch(double height, double push, double stiffness) {
  felt::LocalModel model;
  model.push = {0, 0, push};
  felt::LocalModelBody& body = model.bodies.emplace_back();
  body.body_id = 3;
  body.vertex_count = 4;
  body.triangle_count = 2;
  body.triangle_ids = {0, 1};
  body.corners = {{0, 1, 2}, {0, 2, 3}};
  body.vertex_ids = {0, 1, 2, 3};
  body.positions = {
      {-0.5, -0.5, height}, {0.5, -0.5, height}, {0.5, 0.5, height}, {-0.5, 0.5, height}};
  body.velocities.assign(4, felt::Vec3::Zero());
  body.normals.assign(4, felt::Vec3(0, 0, 1));
  body.stiffness = stiffness;
  return model;
}

/// The force after pressing from above to `depth` below the unpushed surface z = 0 (the
/// proxy's sphere touching at z = kRadius), against `model`.
felt::Vec3 pressed(const felt::LocalModel& model, double depth) {
  LocalRenderer renderer(settings(), {20, 1e-3});
  renderer.take(model, 0, 0);
  felt::Vec3 force = felt::Vec3::Zero();
  for (int k = 0; k <= 100; ++k) {
    const double z = kRadius + 0.01 - (0.01 + depth) * k / 100.0;
    force = renderer.tick({0, 0, z}, k * 1e-3).contact.force;
  }
  return force;
}

TEST(LocalRenderer, AGivingSurfaceIsFeltAsTheSeriesSpringWhateverPushItsModelShows) {
  const double k_o = 1500;
  const double k_eff = kProxyStiffness * k_o / (kProxyStiffness + k_o);
  const double depth = 0.01;
  // the model cut under the push the contact holds now, under a smaller one (stale), under none
  for (const double push : {k_eff * depth, 0.3 * k_eff * depth, 0.0}) {
    SCOPED_TRACE(push);
    const felt::Vec3 force = pressed(patch(-push / k_o, push, k_o), depth);
    EXPECT_NEAR(force.z(), k_eff * depth, 1e-9);
    EXPECT_NEAR(force.x(), 0, 1e-12);
    EXPECT_NEAR(force.y(), 0, 1e-12);
  }
}

TEST(LocalRenderer, ASurfaceOfUnknownStiffnessIsARigidCopy) {
  const double k_o = 1500;
  const double push = 2;
  const felt::Vec3 force = pressed(patch(-push / k_o, push, 0), 0.01);
  EXPECT_NEAR(force.z(), kProxyStiffness * (0.01 - push / k_o), 1e-9);
}

TEST(LocalRenderer, UpstreamCarriesTheProxyWhereTheSurfaceGaveTo) {
  const double k_o = 1500;
  const double k_eff = kProxyStiffness * k_o / (kProxyStiffness + k_o);
  LocalRenderer renderer(settings(), {20, 1e-3});
  renderer.take(patch(0, 0, k_o), 0, 0);
  const felt::Vec3 device(0, 0, kRadius - 0.01);
  for (int k = 0; k <= 50; ++k) {
    renderer.tick(felt::Vec3(0, 0, kRadius + 0.01 - 0.02 * k / 50.0), k * 1e-3);
  }
  const felt::v1::LocalContact up = renderer.upstream();
  ASSERT_TRUE(up.in_contact());
  // the server pushes the body with stiffness (proxy - device): the force the device felt
  EXPECT_NEAR(up.stiffness() * (up.proxy().z() - device.z()), k_eff * 0.01, 1e-9);
}

TEST(LocalRenderer, ALateTickRendersTheTicksItMissedFirst) {
  // the patch rises at 0.5 m/s into a device sliding down and sideways; one renderer ticks every
  // millisecond, the other misses four ticks: its late tick is the first one's, to rounding
  felt::LocalModel rising = patch(0, 0, 0);
  rising.bodies[0].velocities.assign(4, felt::Vec3(0, 0, 0.5));
  const auto device_at = [](int k) { return felt::Vec3(0.002 * k, 0, kRadius + 0.02 - 0.001 * k); };
  // the force follows the depth at most 0.3 N per tick (0.6 N of depth a tick here), and a
  // sliding proxy's friction depends on the path it took: a late tick taken as one tick would
  // render neither
  felt::v1::ProxySettings ramped = settings();
  ramped.set_max_force_change(0.3);
  ramped.set_static_friction(0.4);
  ramped.set_dynamic_friction(0.3);
  LocalRenderer every(ramped, {20, 1e-3});
  LocalRenderer late(ramped, {20, 1e-3});
  every.take(rising, 0, 0);
  late.take(rising, 0, 0);
  int touching = 0;
  for (int k = 0; k <= 30; ++k) {
    const LocalForce expected = every.tick(device_at(k), k * 1e-3);
    if (k > 10 && k < 15) continue;  // the late renderer's loop stalled
    const LocalForce got = late.tick(device_at(k), k * 1e-3);
    EXPECT_LT((got.contact.force - expected.contact.force).norm(), 1e-9) << "tick " << k;
    EXPECT_LT((got.contact.proxy - expected.contact.proxy).norm(), 1e-12) << "tick " << k;
    touching += expected.contact.in_contact ? 1 : 0;
  }
  EXPECT_GT(touching, 10);
}

}  // namespace
}  // namespace felt::client
