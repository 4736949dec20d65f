// The scene loader against mutated scenes: what a client can send as LoadScene JSON or AddBody
// JSON. Every scene file of scenes/ is mutated at random (numbers made extreme, values of the
// wrong type, keys and elements removed or repeated) and loaded with the server's limits.
// Whatever comes in, the loader returns a scene or an error and nothing else: no exception, no
// failed check, no crash, no allocation past the particle budget; and a scene it accepts steps
// without anything non-finite leaving the core.
//
// The seed and the number of cases are fixed so that CI runs the same cases every time;
// FELT_FUZZ_CASES and FELT_FUZZ_SEED run more, or others, by hand.

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "fuzz_settings.hpp"
#include "scene/scene_loader.hpp"

namespace felt {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// What the server allows a client's scene (ServerOptions::max_particles_per_scene).
constexpr std::size_t kClientParticleBudget = 250'000;

/// The scene files of scenes/ as JSON: the seeds the mutations start from.
std::vector<std::pair<std::string, json>> seed_scenes() {
  std::vector<std::pair<std::string, json>> seeds;
  for (const auto& entry : fs::recursive_directory_iterator(FELT_SCENE_DIR)) {
    if (entry.path().extension() != ".json" || entry.path().parent_path().filename() == "meshes") {
      continue;
    }
    auto document = read_scene_json(entry.path());
    if (document) seeds.emplace_back(entry.path().filename().string(), std::move(*document));
  }
  return seeds;
}

/// Every value in `node`'s tree, `node` first.
void collect(json& node, std::vector<json*>& into) {
  into.push_back(&node);
  if (node.is_structured()) {
    for (json& child : node) collect(child, into);
  }
}

json extreme_number(std::mt19937_64& rng) {
  const double values[] = {0,
                           -0.0,
                           -1,
                           1e-300,
                           -1e300,
                           1e300,
                           1e9,
                           4294967296.0,
                           9007199254740993.0,
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()};
  const int integers[] = {0, -1, 1, 2, 3, 1 << 20, std::numeric_limits<int>::max()};
  if (rng() % 2) return values[rng() % std::size(values)];
  return integers[rng() % std::size(integers)];
}

json other_type(std::mt19937_64& rng) {
  switch (rng() % 6) {
    case 0:
      return "text";
    case 1:
      return json::array();
    case 2:
      return json::object();
    case 3:
      return nullptr;
    case 4:
      return true;
    default:
      return json::array({1, 2});
  }
}

/// Changes one value of `document` at random.
void mutate(json& document, std::mt19937_64& rng) {
  std::vector<json*> nodes;
  collect(document, nodes);
  json& node = *nodes[rng() % nodes.size()];
  switch (rng() % 5) {
    case 0:  // a number made extreme (or a number where there was none)
      node = extreme_number(rng);
      break;
    case 1:
      node = other_type(rng);
      break;
    case 2:  // a key or an element removed
      if (node.is_object() && !node.empty()) {
        auto it = node.begin();
        std::advance(it, rng() % node.size());
        node.erase(it);
      } else if (node.is_array() && !node.empty()) {
        node.erase(node.begin() + static_cast<std::ptrdiff_t>(rng() % node.size()));
      }
      break;
    case 3:  // an element repeated
      if (node.is_array() && !node.empty() && node.size() < 64) {
        node.push_back(node[rng() % node.size()]);
      }
      break;
    default:  // a number scaled up, as a grid's or a lattice's size would be
      if (node.is_number()) node = node.get<double>() * 1000;
      break;
  }
}

bool finite(const std::vector<Vec3>& points) {
  for (const Vec3& p : points) {
    if (!p.allFinite()) return false;
  }
  return true;
}

/// What one case came to: refused, or loaded with this many particles.
struct Outcome {
  bool loaded = false;
  std::size_t particles = 0;
};

/// Loads `document` with a client's limits and, when it loads, steps it; fails the test when
/// anything but a scene or an error comes out.
Outcome load_and_step(const json& document) {
  SceneLoadOptions options;
  options.max_particles = kClientParticleBudget;
  options.asset_root = FELT_SCENE_DIR;
  auto scene = load_scene(document, options);
  if (!scene) {
    EXPECT_FALSE(std::string(scene.error().what()).empty());
    return {};
  }
  Outcome outcome{true, 0};
  for (const ClothBody& cloth : scene->world.cloths()) outcome.particles += cloth.state().size();
  for (const SolidBody& solid : scene->world.solids().bodies()) {
    outcome.particles += solid.positions().size();
  }
  EXPECT_LE(outcome.particles, kClientParticleBudget);
  for (int step = 0; step < 3; ++step) scene->world.step();
  for (const ClothBody& cloth : scene->world.cloths()) {
    EXPECT_TRUE(finite(cloth.state().x)) << cloth.name();
  }
  for (const SolidBody& solid : scene->world.solids().bodies()) {
    EXPECT_TRUE(finite(solid.positions())) << solid.name();
  }
  return outcome;
}

TEST(SceneJsonFuzz, AMutatedSceneLoadsOrIsRefusedAndNeverLeaksNonFiniteState) {
  const auto seeds = seed_scenes();
  ASSERT_GE(seeds.size(), 8u) << "the scenes directory moved?";
  const test::FuzzSettings settings = test::fuzz_settings(400);
  std::mt19937_64 rng(settings.seed);
  const std::uint64_t cases = settings.cases;

  std::uint64_t loaded = 0;
  double slowest_seconds = 0;
  std::string slowest;
  for (std::uint64_t c = 0; c < cases && !HasFailure(); ++c) {
    const auto& [name, seed] = seeds[rng() % seeds.size()];
    json document = seed;
    const int mutations = 1 + static_cast<int>(rng() % 3);
    for (int m = 0; m < mutations; ++m) mutate(document, rng);
    const std::string label = "case " + std::to_string(c) + " from " + name;
    SCOPED_TRACE(label + ": " + document.dump());
    const auto start = std::chrono::steady_clock::now();
    try {
      loaded += load_and_step(document).loaded ? 1 : 0;
    } catch (const std::exception& e) {  // a failed FELT_CHECK throws in tests
      ADD_FAILURE() << e.what();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (seconds > slowest_seconds) {  // named with its document, to run it again
      slowest_seconds = seconds;
      slowest = label + ": " + document.dump();
    }
  }
  // the mutations must leave enough scenes loadable for the stepping to be tested too
  if (!HasFailure()) {
    EXPECT_GT(loaded, cases / 10);
  }
  std::cout << loaded << " of " << cases << " mutated scenes loaded; the slowest took "
            << slowest_seconds << " s, " << slowest << "\n";
}

}  // namespace
}  // namespace felt
