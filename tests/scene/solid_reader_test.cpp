#include <array>
#include <numbers>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/scene_loader.hpp"

namespace felt {
namespace {

using nlohmann::json;

json cube_scene() {
  return json::parse(R"({
    "bodies": [{ "type": "solid", "name": "cube",
                 "lattice": { "cells": [5, 5, 5], "size": [1, 1, 1] },
                 "transform": { "translate": [0, 0.6, 0] },
                 "node_mass": 0.05,
                 "mass_spring": { "distance_stiffness": 60, "volume_stiffness": 20, "damping": 2 } }]
  })");
}

std::string error_of(const json& document) {
  const auto scene = load_scene(document);
  return scene ? std::string("(loaded)") : scene.error().what();
}

TEST(SolidReader, LatticeCubeWithTheThesisParameters) {
  const auto scene = load_scene(cube_scene());
  ASSERT_TRUE(scene) << scene.error().what();
  ASSERT_EQ(scene->world.body_count(), 1u);
  EXPECT_EQ(scene->world.body_ref(0).kind, BodyRef::Kind::kSolid);
  const SolidBody& cube = scene->world.solids().bodies()[0];
  EXPECT_EQ(cube.name(), "cube");
  EXPECT_EQ(cube.node_count(), 216u);
  EXPECT_EQ(cube.rest().tets.size(), 625u);
  EXPECT_NEAR(cube.rest_volume(), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(cube.material().mass_spring.distance_stiffness, 60);
  EXPECT_DOUBLE_EQ(cube.material().mass_spring.volume_stiffness, 20);
  EXPECT_DOUBLE_EQ(cube.material().mass_spring.damping, 2);
  EXPECT_DOUBLE_EQ(cube.mass(0), 0.05);
  // centred on the origin, then translated
  Vec3 low = Vec3::Constant(1e9);
  for (const Vec3& x : cube.positions()) low = low.cwiseMin(x);
  EXPECT_LT((low - Vec3(-0.5, 0.1, -0.5)).norm(), 1e-12);
}

TEST(SolidReader, BodyIdsFollowTheSceneOrderAcrossKinds) {
  json doc = cube_scene();
  doc["bodies"].insert(doc["bodies"].begin(),
                       json{{"type", "cloth"}, {"grid", {{"nx", 3}, {"ny", 3}}}});
  const auto scene = load_scene(doc);
  ASSERT_TRUE(scene) << scene.error().what();
  EXPECT_EQ(scene->world.body_ref(0).kind, BodyRef::Kind::kCloth);
  EXPECT_EQ(scene->world.body_ref(1).kind, BodyRef::Kind::kSolid);
  EXPECT_EQ(scene->world.cloth(1), nullptr);
  EXPECT_NE(scene->world.cloth(0), nullptr);
}

TEST(SolidReader, FineBoxSurfaceIsEmbedded) {
  json doc = cube_scene();
  doc["bodies"][0]["lattice"]["fine_divisions"] = 20;
  const auto scene = load_scene(doc);
  ASSERT_TRUE(scene) << scene.error().what();
  const EmbeddedSurface* fine = scene->world.solids().bodies()[0].embedded_surface();
  ASSERT_NE(fine, nullptr);
  // Table 7.1: the fine cube has 2402 vertices and 4800 triangles
  EXPECT_EQ(fine->vertex_count(), 2402u);
  EXPECT_EQ(fine->triangles.size(), 4800u);
}

TEST(SolidReader, ModelsAndTheirParameters) {
  json doc = cube_scene();
  doc["bodies"][0]["model"] = "shape_matching";
  doc["bodies"][0]["shape_matching"] = {
      {"mode", "quadratic"},
      {"beta", 0.3},
      {"time_constant", 0.02},
      {"clusters", true},
      {"plasticity", {{"yield", 0.05}, {"creep", 2}, {"max", 0.5}}}};
  auto scene = load_scene(doc);
  ASSERT_TRUE(scene) << scene.error().what();
  const ShapeMatchingMaterial& sm = scene->world.solids().bodies()[0].material().shape_matching;
  EXPECT_EQ(scene->world.solids().bodies()[0].material().model, SolidModel::kShapeMatching);
  EXPECT_EQ(sm.mode, ShapeMatchingMaterial::Mode::kQuadratic);
  EXPECT_DOUBLE_EQ(sm.beta, 0.3);
  EXPECT_TRUE(sm.clusters);
  EXPECT_DOUBLE_EQ(sm.plastic_yield, 0.05);

  doc["bodies"][0]["model"] = "corotated_fem";
  doc["bodies"][0]["fem"] = {{"young_modulus", 5e4}, {"poisson_ratio", 0.45}};
  scene = load_scene(doc);
  ASSERT_TRUE(scene) << scene.error().what();
  EXPECT_DOUBLE_EQ(scene->world.solids().bodies()[0].material().fem.young_modulus, 5e4);
}

TEST(SolidReader, NamesThePathOfTheBadValue) {
  const std::pair<std::function<void(json&)>, std::string> cases[] = {
      {[](json& b) {
         b["lattice"]["cells"] = {5, 0, 5};
       },
       "bodies[0].lattice.cells[1]: must be"},
      {[](json& b) {
         b["lattice"]["size"] = {1, -1, 1};
       },
       "bodies[0].lattice.size: must be at least 1e-6 in each axis"},
      // geometry the core cannot tell apart: nodes 1e-301 m apart, or 0.1 m apart at 9e15 m
      {[](json& b) {
         b["lattice"]["size"] = {10, 10, 1e-300};
       },
       "bodies[0].lattice.size: must be at least 1e-6 in each axis"},
      {[](json& b) {
         b["transform"] = {{"translate", {0, 0, 9.007199254740992e15}}};
       },
       "bodies[0].transform.translate[2]: must be a number between -1e6 and 1e6"},
      {[](json& b) {
         b.erase("lattice"), b["torus"] = {{"major_radius", 1e300}};
       },
       "bodies[0].torus.major_radius: must be between 1e-6 and 1e6 m"},
      {[](json& b) { b["node_mass"] = 0; }, "bodies[0].node_mass: must be > 0"},
      {[](json& b) { b["mass_spring"]["damping"] = -1; },
       "bodies[0].mass_spring.damping: must be >= 0"},
      {[](json& b) { b["model"] = "rubber"; }, "bodies[0].model: must be mass_spring"},
      {[](json& b) {
         b["fem"] = {{"poisson_ratio", 0.5}};
       },
       "bodies[0].fem.poisson_ratio: must be in [0, 0.5)"},
      {[](json& b) { b["grid"] = json::object(); }, "bodies[0].grid: unknown key"},
      {[](json& b) {
         b["sphere"] = {{"radius", 1}};
       },
       "bodies[0].sphere: a solid takes one shape"},
      {[](json& b) { b.erase("lattice"); }, "bodies[0]: a solid needs one of"},
      {[](json& b) { b["pin"] = {216}; }, "bodies[0].pin[0]: must be a node index below 216"},
      {[](json& b) {
         b["mesh"] = {{"file", "meshes/bunny.obj"}}, b.erase("lattice");
       },
       "bodies[0].mesh.file: files can only be loaded"},
  };
  for (const auto& [edit, expected] : cases) {
    json doc = cube_scene();
    edit(doc["bodies"][0]);
    EXPECT_NE(error_of(doc).find(expected), std::string::npos)
        << "expected \"" << expected << "\", got \"" << error_of(doc) << "\"";
  }
}

// Cloth integrators apply to the solids' force models; the ones that do not say why.
TEST(SolidReader, IntegratorsThatApplyToTheModelAndWhyTheOthersDoNot) {
  const auto integrator_of = [](const char* model, const char* integrator) {
    json doc = cube_scene();
    doc["bodies"][0]["model"] = model;
    doc["bodies"][0]["integrator"] = integrator;
    const auto scene = load_scene(doc);
    if (!scene) return std::string("refused: ") + scene.error().what();
    const Integrator* chosen = scene->world.solids().bodies()[0].integrator();
    return chosen ? std::string(chosen->name()) : std::string("time_corrected_verlet");
  };
  EXPECT_EQ(integrator_of("mass_spring", "rk4"), "rk4");
  EXPECT_EQ(integrator_of("mass_spring", "kang"), "kang");
  EXPECT_EQ(integrator_of("corotated_fem", "symplectic_euler"), "symplectic_euler");
  EXPECT_EQ(integrator_of("mass_spring", "time_corrected_verlet"), "time_corrected_verlet");
  const std::pair<std::array<const char*, 2>, const char*> refused[] = {
      {{"shape_matching", "rk4"}, "shape matching moves its nodes by its own update"},
      {{"mass_spring", "implicit_euler"}, "implicit_euler needs a force Jacobian"},
      {{"corotated_fem", "imex"}, "imex takes springs implicitly and corotated_fem has none"},
      {{"mass_spring", "warp"}, "unknown integrator \"warp\" (known: time_corrected_verlet,"},
  };
  for (const auto& [given, expected] : refused) {
    const std::string got = integrator_of(given[0], given[1]);
    EXPECT_NE(got.find("bodies[0].integrator: "), std::string::npos) << got;
    EXPECT_NE(got.find(expected), std::string::npos) << got;
  }
}

// Explicit Euler and the midpoint rule grow an undamped mode at every step (their stability
// polynomials leave the unit circle on the imaginary axis): no substeps help, so the scene is
// refused. With Rayleigh damping β explicit Euler keeps a mode stable while h ≤ c/ω² = β,
// which the body's stable step follows (0.7 of it) instead of position Verlet's far longer one.
TEST(SolidReader, RefusesAnIntegratorNoStepKeepsStableWithoutDamping) {
  const auto load_fem = [](const char* integrator, Real damping) {
    json doc = cube_scene();
    doc["bodies"][0]["model"] = "corotated_fem";
    doc["bodies"][0]["fem"] = {{"young_modulus", 1e4}, {"damping", damping}};
    doc["bodies"][0]["integrator"] = integrator;
    return load_scene(doc);
  };
  for (const char* integrator : {"explicit_euler", "midpoint"}) {
    const auto refused = load_fem(integrator, 0);
    ASSERT_FALSE(refused) << integrator;
    EXPECT_NE(std::string(refused.error().what())
                  .find(std::string("bodies[0].integrator: ") + integrator +
                        " gains energy at every step on a body without damping"),
              std::string::npos)
        << refused.error().what();
  }
  EXPECT_TRUE(load_fem("rk4", 0));
  constexpr Real kBeta = 2e-4;
  const auto damped = load_fem("explicit_euler", kBeta);
  ASSERT_TRUE(damped) << damped.error().what();
  const Real stable = damped->world.solids().bodies()[0].stable_time_step();
  EXPECT_GT(stable, 0);
  EXPECT_LE(stable, 0.7 * kBeta * (1 + 1e-9));
  const auto verlet = load_fem("symplectic_euler", kBeta);
  EXPECT_GT(verlet->world.solids().bodies()[0].stable_time_step(), 2 * stable);
}

// A material whose stable step is thousands of times below the scene's step would stall the
// physics thread in substeps: it is refused when the scene loads.
TEST(SolidReader, RefusesAMaterialTooStiffForItsMass) {
  json doc = cube_scene();
  doc["time_step"] = 0.01;
  doc["bodies"][0]["node_mass"] = 1e-9;
  doc["bodies"][0]["mass_spring"]["distance_stiffness"] = 1e9;
  EXPECT_NE(error_of(doc).find("bodies[0]: too stiff for its node mass"), std::string::npos)
      << error_of(doc);
}

TEST(SolidReader, ParticleLimitCoversTheLattice) {
  json doc = cube_scene();
  doc["bodies"][0]["lattice"]["cells"] = {64, 64, 64};
  SceneLoadOptions options;
  options.max_particles = 10'000;
  const auto scene = load_scene(doc, options);
  ASSERT_FALSE(scene);
  EXPECT_NE(scene.error().what().find("particle limit"), std::string::npos);
}

TEST(SolidReader, SolidSettings) {
  json doc = cube_scene();
  doc["solids"] = {{"max_step", 0.005}, {"contact_iterations", 4}, {"friction", "thesis"}};
  const auto scene = load_scene(doc);
  ASSERT_TRUE(scene) << scene.error().what();
  EXPECT_DOUBLE_EQ(scene->world.solids().settings().max_step, 0.005);
  EXPECT_EQ(scene->world.solids().settings().contact_iterations, 4);
  EXPECT_EQ(scene->world.solids().settings().friction, SolidFriction::kThesis);
  doc["solids"]["max_step"] = 0.02;
  EXPECT_NE(error_of(doc).find("solids.max_step: must be at most 0.015 s"), std::string::npos);
  // a million substeps a step stalled the server: at most 2000, like a too stiff body
  doc["solids"]["max_step"] = 1e-9;
  EXPECT_NE(error_of(doc).find("solids.max_step: must be at least the time step / 2000 = 5e-07 s"),
            std::string::npos)
      << error_of(doc);
}

// A box lattice's edges are sharp (60°) by default, a voxelized shape's staircase is smooth
// (180°); either can be given.
TEST(SolidReader, CreaseAngleDependsOnTheShape) {
  json doc = cube_scene();
  doc["bodies"].push_back({{"type", "solid"}, {"sphere", {{"radius", 0.5}, {"resolution", 3}}}});
  const auto scene = load_scene(doc);
  ASSERT_TRUE(scene) << scene.error().what();
  const auto& solids = scene->world.solids().bodies();
  EXPECT_DOUBLE_EQ(solids[0].material().crease_angle, std::numbers::pi / 3);
  EXPECT_DOUBLE_EQ(solids[1].material().crease_angle, std::numbers::pi);
  doc["bodies"][0]["crease_angle"] = 90;
  const auto given = load_scene(doc);
  ASSERT_TRUE(given) << given.error().what();
  EXPECT_DOUBLE_EQ(given->world.solids().bodies()[0].material().crease_angle, std::numbers::pi / 2);
  doc["bodies"][0]["crease_angle"] = 200;
  EXPECT_NE(error_of(doc).find("bodies[0].crease_angle: must be 0 to 180"), std::string::npos);
}

// Table 7.2 of the second thesis: three stacked 5×5×5 cubes, in JSON and in its own format.
TEST(SolidReader, ThreeCubesSceneHasTheThesisCounts) {
  SceneLoadOptions options;
  options.asset_root = FELT_SCENE_DIR;
  for (const char* file : {"/thesis/three_cubes.json", "/thesis/three_cubes.cfg"}) {
    const auto scene = load_scene_file(std::string(FELT_SCENE_DIR) + file, options);
    ASSERT_TRUE(scene) << file << ": " << scene.error().what();
    std::size_t nodes = 0, edges = 0, triangles = 0, tets = 0;
    for (const SolidBody& body : scene->world.solids().bodies()) {
      nodes += body.node_count();
      edges += body.topology().edges.size();
      triangles += body.topology().surface.size();
      tets += body.rest().tets.size();
    }
    EXPECT_EQ(nodes, 648u) << file;
    EXPECT_EQ(edges, 2970u) << file;
    EXPECT_EQ(triangles, 900u) << file;
    EXPECT_EQ(tets, 1875u) << file;
  }
}

}  // namespace
}  // namespace felt
