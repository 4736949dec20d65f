#include "scene/thesis_scene_reader.hpp"

#include <numbers>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace felt {
namespace {

// The sample scene of the thesis's Appendix B.3, with a Felt mesh in place of the dog.
constexpr const char* kSample = R"(# Scene containing a dog.
DeformableModels
DeformableModel {
  Name Pes   Path meshes/bunny.obj   Immersed meshes/bunny.obj   Color 255   Mass 0.050
  Scale 1.0 1.0 1.0   Translate 0.0 8.0 0.0   Rotate -1.57 0.0 0.0
  Damping 2   DistancePreservation 60   VolumePreservation 20
}
)";

TEST(ThesisSceneReader, ReadsTheAppendixSample) {
  const auto scene = thesis_scene_to_json(kSample, "dog.cfg");
  ASSERT_TRUE(scene) << scene.error().what();
  const auto& body = (*scene)["bodies"][0];
  EXPECT_EQ(body["type"], "solid");
  EXPECT_EQ(body["name"], "Pes");
  EXPECT_EQ(body["mesh"]["file"], "meshes/bunny.obj");
  EXPECT_DOUBLE_EQ(body["node_mass"].get<double>(), 0.05);
  EXPECT_DOUBLE_EQ(body["mass_spring"]["damping"].get<double>(), 2);
  EXPECT_DOUBLE_EQ(body["mass_spring"]["distance_stiffness"].get<double>(), 60);
  EXPECT_DOUBLE_EQ(body["mass_spring"]["volume_stiffness"].get<double>(), 20);
  // radians in the file, degrees in Felt's transform
  EXPECT_NEAR(body["transform"]["rotate"][0].get<double>(), -1.57 * 180 / std::numbers::pi, 1e-12);
  EXPECT_EQ(body["transform"]["translate"], nlohmann::json({0.0, 8.0, 0.0}));
  // the thesis's floor, y = 0
  EXPECT_EQ((*scene)["colliders"][0]["type"], "plane");
}

TEST(ThesisSceneReader, TableB1Defaults) {
  const auto scene = thesis_scene_to_json(
      "DeformableModels\nDeformableModel { Path lattice:2x3x4 }\n", "defaults.cfg");
  ASSERT_TRUE(scene) << scene.error().what();
  const auto& body = (*scene)["bodies"][0];
  EXPECT_EQ(body["name"], "N/A");
  EXPECT_DOUBLE_EQ(body["node_mass"].get<double>(), 1);
  EXPECT_DOUBLE_EQ(body["mass_spring"]["damping"].get<double>(), 1);
  EXPECT_DOUBLE_EQ(body["mass_spring"]["distance_stiffness"].get<double>(), 20);
  EXPECT_DOUBLE_EQ(body["mass_spring"]["volume_stiffness"].get<double>(), 10);
  EXPECT_EQ(body["lattice"]["cells"], nlohmann::json({2, 3, 4}));
  EXPECT_EQ(body["transform"]["scale"], nlohmann::json({1, 1, 1}));
}

TEST(ThesisSceneReader, ErrorsNameTheLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"DeformableModel { Path lattice:1x1x1 }", "bad.cfg:1: expected DeformableModels"},
      {"DeformableModels\nDeformableModel {\n Mass heavy\n}", "bad.cfg:3: Mass: \"heavy\""},
      {"DeformableModels\nDeformableModel {\n Colour 1\n}", "bad.cfg:3: unknown parameter"},
      {"DeformableModels\nDeformableModel {\n Name x\n}",
       "bad.cfg:2: a DeformableModel needs a Path"},
      {"DeformableModels\nDeformableModel {\n Path dog.do\n}", "bad.cfg:3: Path \"dog.do\""},
      {"DeformableModels\nDeformableModel {\n Path lattice:1x1x1\n Scale 1 2", "expected a number"},
      {"DeformableModels\nDeformableModel {\n Path lattice:1x1x1\n", "expected a parameter or }"},
      {"DeformableModels\n", "bad.cfg:1: the file has no DeformableModel"},
      {"DeformableModels\nDeformableModel { Path lattice:99999999999x1x1 }", "too large"},
  };
  for (const auto& [text, expected] : cases) {
    const auto scene = thesis_scene_to_json(text, "bad.cfg");
    ASSERT_FALSE(scene) << text;
    EXPECT_NE(scene.error().what().find(expected), std::string::npos)
        << "expected \"" << expected << "\", got \"" << scene.error().what() << "\"";
  }
}

}  // namespace
}  // namespace felt
