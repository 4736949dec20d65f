#include "scene/scene_overrides.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace felt {
namespace {

using nlohmann::json;

json document() {
  return json::parse(R"({"bodies": [{"integrator": "a", "springs": {}}]})");
}

TEST(SceneOverrides, SetsNestedValuesThroughArrayIndices) {
  json doc = document();
  ASSERT_TRUE(apply_override(doc, "bodies.0.integrator=explicit_euler"));
  EXPECT_EQ(doc["bodies"][0]["integrator"], "explicit_euler");  // not JSON: taken as a string
  ASSERT_TRUE(apply_override(doc, "bodies.0.springs.shear.stiffness=12.5"));
  EXPECT_EQ(doc["bodies"][0]["springs"]["shear"]["stiffness"], 12.5);  // created on the way
  ASSERT_TRUE(apply_override(doc, "gravity=[0,0,-9.81]"));
  EXPECT_EQ(doc["gravity"], json::parse("[0,0,-9.81]"));
  ASSERT_TRUE(apply_override(doc, "name=\"7\""));
  EXPECT_EQ(doc["name"], "7");
  ASSERT_TRUE(apply_override(doc, "bodies.0.pin=top_row"));
  EXPECT_EQ(doc["bodies"][0]["pin"], "top_row");
}

TEST(SceneOverrides, ReportsBadKeys) {
  json doc = document();
  EXPECT_EQ(apply_override(doc, "bodies.3.integrator=x").error(),
            "bodies.3: index out of range (size 1)");
  EXPECT_EQ(apply_override(doc, "bodies.first.integrator=x").error(),
            "bodies.first: an array needs a numeric index");
  EXPECT_EQ(apply_override(doc, "bodies.0.integrator.deeper=x").error(),
            "bodies.0.integrator.deeper: cannot descend into a string");
  EXPECT_FALSE(apply_override(doc, "bodies..integrator=x"));
  EXPECT_FALSE(apply_override(doc, "no_equals_sign"));
  EXPECT_FALSE(apply_override(doc, "=1"));
  EXPECT_EQ(doc, document());  // failed overrides change nothing they did not reach
}

}  // namespace
}  // namespace felt
