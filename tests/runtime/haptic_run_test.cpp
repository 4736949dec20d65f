// Haptic devices ticked in simulated time by `run_batch`: reproducible, so these check what a
// user feels on a live server without depending on the machine's speed.

#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "runtime/batch_run.hpp"
#include "scene/scene_loader.hpp"

namespace felt {
namespace {

using nlohmann::json;

/// The default curtain (1 m, 20 × 20, 0.5 kg) hanging from its top corners in the plane z = 0,
/// with physics at `time_step` and one device pressing 1 cm behind its plane from +z.
json pressed_curtain(double time_step) {
  json scene = json::parse(R"({
    "gravity": [0, -9.81, 0],
    "haptics": { "proxy_radius": 0.02, "stiffness": 400, "max_force": 8,
                 "devices": [ { "name": "finger",
                   "path": { "shape": "press", "from": [0.02, 1.5, 0.2], "to": [0.02, 1.5, -0.01],
                             "period": 0.5 } } ] },
    "bodies": [ { "type": "cloth", "name": "curtain",
      "grid": { "width": 1.0, "height": 1.0, "nx": 20, "ny": 20, "center": [0, 1.5, 0] },
      "mass": 0.5,
      "springs": { "structural": { "stiffness": 200, "damping": 0.05 },
                   "shear": { "stiffness": 50, "damping": 0.02 },
                   "bend": { "stiffness": 5, "damping": 0.005 } },
      "drag": 0.005, "integrator": "symplectic_euler", "pin": "top_corners" } ]
  })");
  scene["time_step"] = time_step;
  return scene;
}

/// The same cloth held at its four corners, sagging, stepped by implicit Euler at 100 Hz; a
/// finger presses down into the middle of the sag and stays there.
json pressed_hammock() {
  json scene = pressed_curtain(0.01);
  scene["bodies"][0]["grid"]["plane"] = "xz";
  scene["bodies"][0]["grid"]["center"] = {0, 1, 0};
  scene["bodies"][0]["pin"] = "four_corners";
  scene["bodies"][0]["integrator"] = "implicit_euler";
  scene["haptics"]["devices"][0]["path"] = json::parse(
      R"({ "shape": "press", "from": [0.02, 1.2, 0.02], "to": [0.02, 0.7, 0.02], "period": 1 })");
  return scene;
}

std::vector<HapticRecord> run_recorded(Scene& scene, std::uint64_t steps,
                                       BatchRunStats* stats_out = nullptr) {
  std::stringstream csv;
  BatchHaptics haptics;
  haptics.record = &csv;
  const BatchRunStats stats = run_batch(scene, steps, haptics);
  EXPECT_FALSE(stats.nonfinite);
  if (stats_out) *stats_out = stats;
  auto records = read_recording(csv);
  EXPECT_TRUE(records) << records.error();
  return records ? *records : std::vector<HapticRecord>{};
}

/// A finger pressed into the sag of the scene `doc`: in contact throughout its second half,
/// pushing, and the force never jumping by 1 % of its mean from one update to the next.
void expect_a_steady_press(const json& doc) {
  auto scene = load_scene(doc);
  ASSERT_TRUE(scene) << scene.error().what();
  const auto records = run_recorded(*scene, 300);  // 3 s
  ASSERT_EQ(records.size(), 3000u);
  double largest_step = 0, mean_force = 0;
  int held = 0;
  for (std::size_t i = 1; i < records.size(); ++i) {
    if (records[i].time < 1.5) continue;  // pressed in, settled
    ASSERT_TRUE(records[i].in_contact) << "at t = " << records[i].time;
    largest_step = std::max(largest_step, (records[i].force - records[i - 1].force).norm());
    mean_force += records[i].force.norm();
    ++held;
  }
  mean_force /= held;
  EXPECT_GT(mean_force, 0.5);  // the finger really pushes the curtain
  EXPECT_LT(largest_step, 0.01 * mean_force);
}

TEST(HapticRun, RestingOnAHangingClothTheForceDoesNotVibrate) {
  // physics at 100 Hz under a 1 kHz servo: without interpolation the force would jump at every
  // physics step, and applying it back to the cloth would shake it (thesis 1's vibration); with
  // implicit Euler, and with projective dynamics
  for (const char* integrator : {"implicit_euler", "projective_dynamics"}) {
    SCOPED_TRACE(integrator);
    json doc = pressed_hammock();
    doc["bodies"][0]["integrator"] = integrator;
    expect_a_steady_press(doc);
  }
}

TEST(HapticRun, ARunWithDevicesIsReproducible) {
  auto first = load_scene(pressed_curtain(0.001));
  auto second = load_scene(pressed_curtain(0.001));
  const auto a = run_recorded(*first, 400);
  const auto b = run_recorded(*second, 400);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].force, b[i].force) << i;
    ASSERT_EQ(a[i].proxy, b[i].proxy) << i;
  }
}

TEST(HapticRun, EveryStructureReplaysTheBruteForceRecordingEquivalently) {
  // a stroke across the curtain in contact, recorded with the reference, then replayed with
  // each structure: same contacts, same triangles, same proxy positions (De Boeck's method)
  json doc = pressed_hammock();
  doc["haptics"]["structure"] = "brute_force";
  doc["haptics"]["devices"][0]["path"] = json::parse(R"({ "shape": "samples", "samples": [
      { "t": 0, "position": [-0.3, 1.1, 0.05] }, { "t": 0.2, "position": [-0.3, 0.8, 0.05] },
      { "t": 0.8, "position": [0.3, 0.8, -0.05] }, { "t": 1.0, "position": [0.3, 1.1, -0.05] } ] })");
  auto reference = load_scene(doc);
  ASSERT_TRUE(reference) << reference.error().what();
  const auto recorded = run_recorded(*reference, 100);
  const auto touching = std::count_if(recorded.begin(), recorded.end(),
                                      [](const HapticRecord& r) { return r.in_contact; });
  EXPECT_GT(touching, 200);  // of 1000 updates
  for (const char* kind :
       {"bvh_sphere_2", "bvh_sphere_4", "bvh_aabb_2", "bvh_aabb_4", "spatial_hash"}) {
    doc["haptics"]["structure"] = kind;
    auto scene = load_scene(doc);
    BatchHaptics replay;
    replay.replay = &recorded;
    replay.tolerance = 1e-9;
    const BatchRunStats stats = run_batch(*scene, 100, replay);
    EXPECT_EQ(stats.haptics.compared, recorded.size()) << kind;
    EXPECT_EQ(stats.haptics.equivalent, recorded.size()) << kind;
  }
}

/// A 2 × 2 cloth with three corners pinned and springs too weak to hold anything: the fourth
/// corner, at (0.5, 0, 0.5), hangs from whatever holds it. One device of radius 1 cm follows
/// `path`.
json loose_corner(const json& path) {
  json scene = json::parse(R"({
    "time_step": 0.001, "gravity": [0, -9.81, 0],
    "haptics": { "proxy_radius": 0.01, "stiffness": 400, "max_force": 8 },
    "bodies": [ { "type": "cloth",
      "grid": { "width": 1, "height": 1, "nx": 2, "ny": 2, "center": [0, 0, 0], "plane": "xz" },
      "mass": 0.4,
      "springs": { "structural": { "stiffness": 1e-4, "damping": 0 },
                   "shear": { "stiffness": 1e-4, "damping": 0 },
                   "bend": { "enabled": false } },
      "drag": 0.05, "integrator": "symplectic_euler", "pin": [0, 1, 2] } ]
  })");
  scene["haptics"]["devices"] = json::array({{{"path", path}}});
  return scene;
}

TEST(HapticRun, GrabCarriesTheWeightOfTheGrabbedVertex) {
  // the corner hangs from the device by the grab spring alone: the device feels its weight
  auto scene = load_scene(loose_corner(json::parse(
      R"({ "shape": "press", "from": [0.5, 0.005, 0.5], "to": [0.5, 0.005, 0.5], "buttons": 1 })")));
  ASSERT_TRUE(scene) << scene.error().what();
  const auto records = run_recorded(*scene, 3000);
  // the free corner (index 3) is at (0.5, 0, 0.5), inside the proxy's sphere: grabbed at
  // once, then carried
  Vec3 mean_force = Vec3::Zero();
  int samples = 0;
  for (const HapticRecord& r : records) {
    if (r.time < 2) continue;
    mean_force += r.force;
    ++samples;
  }
  mean_force /= samples;
  const double weight = 0.1 * 9.81;  // a quarter of the cloth's mass
  EXPECT_NEAR(mean_force.y(), -weight, 0.02 * weight);
  EXPECT_NEAR(mean_force.x(), 0, 0.02 * weight);
  // hanging below the device by weight / stiffness
  const Vec3 corner = scene->world.cloths()[0].state().x[3];
  EXPECT_NEAR(corner.y(), 0.005 - weight / 400, 0.2 * weight / 400);
}

TEST(HapticRun, ReleasingTheButtonLetsGo) {
  auto scene = load_scene(loose_corner(json::parse(R"({ "shape": "samples", "samples": [
      { "t": 0, "position": [0.5, 0.005, 0.5], "buttons": 1 },
      { "t": 0.5, "position": [0.5, 0.3, 0.5], "buttons": 1 },
      { "t": 0.8, "position": [0.5, 0.3, 0.5], "buttons": 0 },
      { "t": 1.0, "position": [0.5, 0.3, 0.5], "buttons": 0 } ] })")));
  ASSERT_TRUE(scene) << scene.error().what();
  const auto records = run_recorded(*scene, 1000);
  double held_force = 0;
  int held = 0;
  for (const HapticRecord& r : records) {
    if (r.time > 0.6 && r.time < 0.8) {
      EXPECT_NE(r.force, Vec3::Zero()) << "at t = " << r.time;
      held_force += r.force.y();
      ++held;
    } else if (r.time > 0.81) {
      // let go: nothing pulls the device down any more (the corner may bounce into the proxy)
      EXPECT_GE(r.force.y(), 0) << "at t = " << r.time;
    }
  }
  // lifted 30 cm with the device and bouncing on the grab spring: on average it feels the
  // corner's weight
  EXPECT_NEAR(held_force / held, -0.1 * 9.81, 0.1);
  // let go at about 0.3 m (bouncing on the spring), it has fallen for 0.2 s
  EXPECT_LT(scene->world.cloths()[0].state().x[3].y(), 0.3 - 0.5 * 9.81 * 0.2 * 0.2 + 0.03);
}

}  // namespace
}  // namespace felt
