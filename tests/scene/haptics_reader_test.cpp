#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/scene_loader.hpp"

namespace felt {
namespace {

using nlohmann::json;

std::string error_of(const json& document) {
  const auto scene = load_scene(document);
  return scene ? std::string("(loaded)") : scene.error().what();
}

TEST(HapticsReader, ReadsProxySettingsStructureAndDevices) {
  const auto scene = load_scene(json::parse(R"({
    "haptics": { "proxy_radius": 0, "stiffness": 800, "damping": 2, "max_force": 6,
                 "max_force_change": 0.5, "static_friction": 0.6, "dynamic_friction": 0.4,
                 "force_shading": false, "structure": "bvh_sphere_2", "servo_rate": 2000,
                 "devices": [
                   { "name": "stroke",
                     "path": { "shape": "line", "from": [0, 1, 0], "to": [1, 1, 0], "period": 2 } },
                   { "path": { "shape": "circle", "center": [0, 1, 0], "radius": 0.1,
                               "axis": [0, 0, 1], "period": 0.5, "buttons": 1 } },
                   { "path": { "shape": "samples",
                               "samples": [ { "t": 0, "position": [0, 0, 0] },
                                            { "t": 0.1, "position": [0, 1, 0], "buttons": 1 } ] } }
                 ] }
  })"));
  ASSERT_TRUE(scene) << scene.error().what();
  const ProxySettings& p = scene->haptics;
  EXPECT_EQ(p.radius, 0);
  EXPECT_EQ(p.stiffness, 800);
  EXPECT_EQ(p.damping, 2);
  EXPECT_EQ(p.max_force, 6);
  EXPECT_EQ(p.max_force_change, 0.5);
  EXPECT_EQ(p.static_friction, 0.6);
  EXPECT_EQ(p.dynamic_friction, 0.4);
  EXPECT_FALSE(p.force_shading);
  EXPECT_EQ(scene->haptic_structure, TriangleQueryKind::kBvhSphere2);
  EXPECT_EQ(scene->servo_rate, 2000);
  ASSERT_EQ(scene->devices.size(), 3u);
  EXPECT_EQ(scene->devices[0].name, "stroke");
  EXPECT_EQ(scene->devices[1].name, "device 1");
  EXPECT_EQ(scene->devices[0].path.at(1).position, Vec3(1, 1, 0));
  EXPECT_EQ(scene->devices[1].path.at(0).buttons, 1u);
  EXPECT_EQ(scene->devices[2].path.at(0.05).position, Vec3(0, 0.5, 0));
  EXPECT_EQ(scene->devices[2].path.at(0.2).buttons, 1u);
}

TEST(HapticsReader, DefaultsAreThoseOfProxySettings) {
  const auto scene = load_scene(json::parse(R"({ "haptics": { "static_friction": 0.3 } })"));
  ASSERT_TRUE(scene) << scene.error().what();
  // dynamic friction defaults to the static one
  EXPECT_EQ(scene->haptics.dynamic_friction, 0.3);
  EXPECT_EQ(scene->haptics.radius, ProxySettings{}.radius);
  EXPECT_TRUE(scene->devices.empty());
}

TEST(HapticsReader, BadValuesAreReportedWithTheirPath) {
  EXPECT_EQ(error_of(json::parse(R"({ "haptics": { "structure": "octree" } })")),
            "haptics.structure: must be brute_force, bvh_sphere_2, bvh_sphere_4, bvh_aabb_2, "
            "bvh_aabb_4 or spatial_hash");
  EXPECT_EQ(error_of(json::parse(R"({ "haptics": { "servo_rate": 100 } })")),
            "haptics.servo_rate: must be between 250 and 4000 Hz");
  EXPECT_EQ(error_of(json::parse(
                R"({ "haptics": { "static_friction": 0.2, "dynamic_friction": 0.5 } })")),
            "haptics.dynamic_friction: must be at most static_friction");
  EXPECT_EQ(error_of(json::parse(R"({ "haptics": { "proxy_radius": -1 } })")),
            "haptics.proxy_radius: must be >= 0");
  EXPECT_EQ(error_of(json::parse(R"({ "haptics": { "devices": [ { "name": "x" } ] } })")),
            "haptics.devices[0].path: is required");
  EXPECT_EQ(error_of(json::parse(
                R"({ "haptics": { "devices": [ { "path": { "shape": "spiral" } } ] } })")),
            "haptics.devices[0].path.shape: must be line, circle, press or samples");
  EXPECT_EQ(error_of(json::parse(R"({ "haptics": { "devices": [ { "path": {
              "shape": "samples", "samples": [ { "t": 1, "position": [0, 0, 0] },
                                               { "t": 1, "position": [0, 0, 0] } ] } } ] } })")),
            "haptics.devices[0].path.samples[1].t: must be later than the sample before");
  // a JSON exception escaped the loader here once (the scene-JSON fuzz test found it)
  EXPECT_EQ(error_of(json::parse(
                R"({ "haptics": { "devices": [ { "path": { "shape": "samples" } } ] } })")),
            "haptics.devices[0].path.samples: is required");
  EXPECT_EQ(error_of(json::parse(R"({ "haptics": { "devices": [ { "path": {
              "shape": "circle", "axis": [0, 0, 0] } } ] } })")),
            "haptics.devices[0].path.axis: must not be zero");
}

}  // namespace
}  // namespace felt
