// A body's own "max_step" (issue 32: the panel's per-body time step): a world step longer than it
// is taken in equal substeps, which must be the very steps a world at the shorter step takes
// (the same integrator on the same forces: equal positions, to rounding), and a max_step that
// would take more substeps than the step budget is refused at load.

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/scene_loader.hpp"

namespace felt {
namespace {

using nlohmann::json;

json cloth_scene(double time_step) {
  json scene = json::parse(R"({"gravity": [0, -9.81, 0], "bodies": [{"type": "cloth",
      "grid": {"nx": 8, "ny": 8, "width": 0.5, "height": 0.5}, "pin": "top_corners",
      "springs": {"structural": {"stiffness": 400, "damping": 0.05}}}]})");
  scene["time_step"] = time_step;
  return scene;
}

json solid_scene(double time_step) {
  json scene = json::parse(R"({"gravity": [0, -9.81, 0], "bodies": [{"type": "solid",
      "lattice": {"size": [0.2, 0.2, 0.2], "cells": [2, 2, 2]},
      "transform": {"translate": [0, 0.15, 0]}, "node_mass": 1}],
      "colliders": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]}]})");
  scene["time_step"] = time_step;
  return scene;
}

Scene load(const json& document) {
  auto scene = load_scene(document);
  EXPECT_TRUE(scene) << scene.error().message;
  return std::move(*scene);
}

/// The largest distance between the same body's vertices in two worlds.
Real largest_gap(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  Real gap = 0;
  for (std::size_t i = 0; i < a.size(); ++i) gap = std::max(gap, (a[i] - b[i]).norm());
  return gap;
}

TEST(BodyMaxStep, AClothsMaxStepTakesTheStepsOfAWorldAtThatStep) {
  json document = cloth_scene(0.004);
  document["bodies"][0]["max_step"] = 0.001;
  Scene own = load(document);
  Scene fine = load(cloth_scene(0.001));
  for (int step = 0; step < 100; ++step) {
    own.world.step();
    for (int s = 0; s < 4; ++s) fine.world.step();
  }
  EXPECT_EQ(own.world.step_counts(0).substeps, 4);
  EXPECT_EQ(fine.world.step_counts(0).substeps, 1);
  const Real gap = largest_gap(own.world.cloths()[0].state().x, fine.world.cloths()[0].state().x);
  EXPECT_LT(gap, 1e-9);
  // and not the coarse world's: 0.4 s of swinging at 4 ms lands elsewhere
  Scene coarse = load(cloth_scene(0.004));
  for (int step = 0; step < 100; ++step) coarse.world.step();
  EXPECT_GT(largest_gap(coarse.world.cloths()[0].state().x, fine.world.cloths()[0].state().x),
            1e-4);
}

TEST(BodyMaxStep, ASolidsMaxStepTakesTheStepsOfAWorldAtThatStep) {
  // dropped onto the floor: its contacts are solved at every substep, as at every fine step
  json document = solid_scene(0.004);
  document["bodies"][0]["max_step"] = 0.001;
  Scene own = load(document);
  Scene fine = load(solid_scene(0.001));
  for (int step = 0; step < 100; ++step) {
    own.world.step();
    for (int s = 0; s < 4; ++s) fine.world.step();
  }
  EXPECT_EQ(own.world.step_counts(0).substeps, 4);
  EXPECT_EQ(fine.world.step_counts(0).substeps, 1);
  const Real gap = largest_gap(own.world.solids().bodies()[0].positions(),
                               fine.world.solids().bodies()[0].positions());
  EXPECT_LT(gap, 1e-9);
}

TEST(BodyMaxStep, AStepBeyondTheRangeOrTheBudgetIsRefusedWithTheReason) {
  for (const double bad : {0.0, -1e-3, 1e-7, 2.0}) {
    json document = cloth_scene(0.001);
    document["bodies"][0]["max_step"] = bad;
    const auto refused = load_scene(document);
    ASSERT_FALSE(refused) << bad;
    EXPECT_EQ(refused.error().path, "bodies[0].max_step");
    EXPECT_NE(refused.error().message.find("between 1e-06 and 1 s"), std::string::npos)
        << refused.error().message;
  }
  // 10 ms in steps of 2 µs: 5000 substeps, five times the default budget
  json document = solid_scene(0.01);
  document["bodies"][0]["max_step"] = 2e-6;
  const auto refused = load_scene(document);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().path, "bodies[0].max_step");
  EXPECT_NE(refused.error().message.find("5000 substeps"), std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("health.step_budget"), std::string::npos);
  document["health"] = {{"step_budget", 5000}};
  EXPECT_TRUE(load_scene(document));
}

TEST(BodyMaxStep, XpbdsSubstepsCountInTheBudgetWithTheBodysOwn) {
  // xpbd's substeps set its compliance, so the budget cannot cut them: a scene whose substeps
  // the budget cannot afford is refused
  json document = cloth_scene(0.001);
  document["health"] = {{"step_budget", 100}};
  document["bodies"][0]["integrator"] = {{"name", "xpbd"}, {"substeps", 200}};
  auto refused = load_scene(document);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().path, "bodies[0].integrator");
  EXPECT_NE(refused.error().message.find("takes 200 internal steps a step"), std::string::npos)
      << refused.error().message;
  // 10 substeps of the body's own, each of 20 xpbd substeps: 200
  document["bodies"][0]["integrator"]["substeps"] = 20;
  document["bodies"][0]["max_step"] = 1e-4;
  refused = load_scene(document);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().path, "bodies[0].max_step");
  EXPECT_NE(refused.error().message.find("10 substeps of the time step 0.001 s, each of 20 "
                                         "internal steps"),
            std::string::npos)
      << refused.error().message;
  document["bodies"][0]["integrator"]["substeps"] = 10;
  EXPECT_TRUE(load_scene(document));
}

}  // namespace
}  // namespace felt
