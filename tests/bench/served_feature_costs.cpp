// What each optional feature costs a served scene's physics thread per step (issue 27, item 6),
// on the 100 × 100 cloth of scenes/service_bench.json and the three cubes of
// scenes/thesis/three_cubes.json: the stepping thread's CPU milliseconds per step of each
// variant over a scene's first steps, the variants alternating round by round so that the
// machine's load falls on all of them alike. Each step is followed by what the scene runner
// does after it when it steps in real time: a snapshot for the other threads while someone
// reads them (with vertex normals only while haptics render) and, while a proxy renders, the
// haptic frame for it. The subscribers' frames are encoded on the frame encoder's thread, not
// this one (frame_stream_bench, docs/results/service.md).
//
// Usage: served_feature_costs ROUNDS RESULTS_DIR   (scripts/bench-features): rewrites the
// tables of RESULTS_DIR/feature_costs.md.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runtime/live_haptic_frames.hpp"
#include "runtime/live_scene.hpp"
#include "scene/scene_loader.hpp"
#include "scene/scene_overrides.hpp"
#include "scheduling/thread_cpu_time.hpp"
#include "study_output.hpp"

namespace felt {
namespace {

/// What runs after each step besides the world's step.
enum class Served {
  kNothing,      ///< a headless run (feltd run)
  kUnwatched,    ///< a served scene nobody subscribes to or touches
  kSubscribers,  ///< a served scene with subscribers: a snapshot a step
  kProxy,        ///< a served scene a proxy renders in: with normals, and a haptic frame
};

struct Variant {
  const char* scene;    ///< as the table names it
  const char* file;     ///< under scenes/
  int steps;            ///< measured from the scene's start
  const char* feature;  ///< as the table names it; the first of each scene is its bare run
  std::vector<std::string> overrides;
  Served served = Served::kNothing;
};

const char* const kCloth = "100 x 100 cloth (kang, h = 2 ms, first 0.4 s)";
const char* const kCubes = "three cubes (mass-spring, h = 10 ms, first 1 s)";
// the bare runs: no health check, and the cloth without its stretch limit
const std::vector<std::string> kBareCloth{"health.enabled=false",
                                          "bodies.0.stretch_limit.enabled=false"};
const std::vector<std::string> kBareCubes{"health.enabled=false"};

std::vector<std::string> with(std::vector<std::string> base, const std::vector<std::string>& more) {
  base.insert(base.end(), more.begin(), more.end());
  return base;
}

std::vector<Variant> variants() {
  const char* cloth = "service_bench.json";
  const char* cubes = "thesis/three_cubes.json";
  const std::vector<std::string> cubes_collide{"bodies.0.self_collision=true",
                                               "bodies.1.self_collision=true",
                                               "bodies.2.self_collision=true"};
  return {
      {kCloth, cloth, 200, "bare integrator (no health check, no stretch limit)", kBareCloth},
      {kCloth, cloth, 200, "health check", {"bodies.0.stretch_limit.enabled=false"}},
      {kCloth, cloth, 200, "stretch limiting (the scene's 10 %)", {"health.enabled=false"}},
      {kCloth, cloth, 200, "self-collision", with(kBareCloth, {"bodies.0.self_collision=true"})},
      {kCloth, cloth, 200, "served, nobody watching", kBareCloth, Served::kUnwatched},
      {kCloth, cloth, 200, "served, subscribers: a snapshot a step", kBareCloth,
       Served::kSubscribers},
      {kCloth, cloth, 200, "served, a proxy rendering: normals and a haptic frame a step",
       kBareCloth, Served::kProxy},
      {kCloth, cloth, 200, "everything on (health, limit, proxy)", {}, Served::kProxy},
      {kCubes, cubes, 100, "bare integrator (no health check; contact between the cubes)",
       kBareCubes},
      {kCubes, cubes, 100, "health check", {}},
      {kCubes, cubes, 100, "self-collision of each cube", with(kBareCubes, cubes_collide)},
      {kCubes, cubes, 100, "served, nobody watching", kBareCubes, Served::kUnwatched},
      {kCubes, cubes, 100, "served, subscribers: a snapshot a step", kBareCubes,
       Served::kSubscribers},
      {kCubes, cubes, 100, "served, a proxy rendering: normals and a haptic frame a step",
       kBareCubes, Served::kProxy},
  };
}

Scene load(const Variant& variant) {
  const std::filesystem::path file = std::filesystem::path(FELT_SCENE_DIR) / variant.file;
  auto document = read_scene_json(file);
  if (!document) throw std::runtime_error(document.error().what());
  for (const std::string& assignment : variant.overrides) {
    if (auto set = apply_override(*document, assignment); !set) {
      throw std::runtime_error(assignment + ": " + set.error());
    }
  }
  SceneLoadOptions options;
  options.asset_root = FELT_SCENE_DIR;
  auto scene = load_scene(*document, options);
  if (!scene) throw std::runtime_error(file.string() + ": " + scene.error().what());
  return std::move(*scene);
}

double one_minute_load() {
  double load = 0;
  return getloadavg(&load, 1) == 1 ? load : std::nan("");
}

/// CPU ms per step of `variant`'s scene over its first steps.
double cpu_ms_per_step(const Variant& variant) {
  LiveScene live(load(variant), 0, wall_clock());
  LiveHapticFrames frames(live, live.scene.haptic_structure);
  World& world = live.scene.world;
  const double start = thread_cpu_seconds();
  for (int n = 0; n < variant.steps; ++n) {
    world.step();
    if (variant.served == Served::kNothing) continue;
    // subscribers and proxies read on their own threads; their reads keep snapshots, frames
    // and normals coming
    if (variant.served == Served::kSubscribers) live.latest();
    if (variant.served == Served::kProxy) frames.current();
    const std::uint64_t published = live.published();
    live.publish_steps();  // as SceneRunner::run after a pass of steps
    if (live.published() != published) frames.publish(SteadyClock::now());
  }
  return 1e3 * (thread_cpu_seconds() - start) / variant.steps;
}

}  // namespace
}  // namespace felt

int main(int argc, char** argv) {
  using namespace felt;
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s ROUNDS RESULTS_DIR\n", argv[0]);
    return 2;
  }
  const int rounds = std::max(1, std::atoi(argv[1]));
  const std::vector<Variant> all = variants();
  std::vector<std::vector<double>> cpu(all.size());
  std::vector<double> load{one_minute_load()};
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < rounds; ++r) {
    for (std::size_t i = 0; i < all.size(); ++i) cpu[i].push_back(cpu_ms_per_step(all[i]));
    load.push_back(one_minute_load());
    std::fprintf(stderr, "round %d of %d\n", r + 1, rounds);
  }
  std::string tables =
      study::generated_by("served_feature_costs", study::seconds_since(start)) +
      study::format(
          " %d rounds, the variants alternating within each round; one-minute load "
          "average %.1f–%.1f on 2 cores.\n\n",
          rounds, *std::min_element(load.begin(), load.end()),
          *std::max_element(load.begin(), load.end())) +
      "| scene | feature | CPU ms per step, median (min–max) | against bare |\n"
      "|---|---|---:|---:|\n";
  double bare = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    std::vector<double> sorted = cpu[i];
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2];
    if (i == 0 || all[i].scene != all[i - 1].scene) bare = median;
    tables += study::format("| %s | %s | %.3f (%.3f–%.3f) | %.2f |\n", all[i].scene, all[i].feature,
                            median, sorted.front(), sorted.back(), median / bare);
  }
  study::write_tables(argv[2], "feature_costs.md", "What the optional features cost",
                      "feature_costs_tables.md", "served_feature_costs", tables);
  return 0;
}
