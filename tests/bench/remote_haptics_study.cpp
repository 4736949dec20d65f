// Remote haptics in simulated time (issue 26): every case of docs/results/remote_haptics.md's
// deterministic section, each written as a `felt touch --log` CSV into OUT_DIR with a list of
// the cases (cases.tsv: scene, network, mode, remote_haptics.py's MODE, file) for
// scripts/study-remote-haptics to measure. --quick runs the cube at 100 ms only.
//
//   remote_haptics_study OUT_DIR [--quick]

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "remote_haptics_run.hpp"
#include "study_output.hpp"

namespace {

using felt::DevicePath;
using felt::DeviceSample;
using felt::Vec3;
using felt::study::RemoteCase;
using felt::study::Rendering;
using felt::study::SimulatedNetwork;

DevicePath through(const std::vector<std::pair<double, Vec3>>& keys) {
  DevicePath path;
  path.shape = DevicePath::Shape::kSamples;
  for (const auto& [time, position] : keys) path.samples.push_back(DeviceSample{time, position, 0});
  return path;
}

struct Body {
  const char* name;
  const char* scene;
  DevicePath path;
};

/// 0.5 s to 1 cm above the surface (the 2 cm proxy touches 2 cm above it), 0.5 s pressing
/// `depth` below the surface's rest, 1 s sliding 10 or 20 cm across, 0.5 s pulling out, 0.5 s
/// away: the curtain's as scripts/bench-remote-haptics's, the cube's from above (its scene is
/// z-up, so "toward -z" is into both surfaces).
std::vector<Body> bodies(bool quick) {
  const std::string dir = FELT_SCENE_DIR;
  std::vector<Body> out;
  out.push_back({"cube", "pressed_cube.json",
                 through({{0, {-0.05, 0, 0.3}},
                          {0.5, {-0.05, 0, 0.23}},
                          {1.0, {-0.05, 0, 0.205}},
                          {2.0, {0.05, 0, 0.205}},
                          {2.5, {0.05, 0, 0.3}},
                          {3.0, {0.05, 0, 0.3}}})});
  if (quick) return out;
  out.push_back({"curtain", "default.json",
                 through({{0, {-0.1, 1.3, 0.08}},
                          {0.5, {-0.1, 1.3, 0.01}},
                          {1.0, {-0.1, 1.3, -0.03}},
                          {2.0, {0.1, 1.3, -0.03}},
                          {2.5, {0.1, 1.3, 0.08}},
                          {3.0, {0.1, 1.3, 0.08}}})});
  return out;
}

struct Network {
  const char* label;
  SimulatedNetwork network;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || (argc == 3 && std::string(argv[2]) != "--quick") || argc > 3) {
    std::fprintf(stderr, "usage: remote_haptics_study OUT_DIR [--quick]\n");
    return 2;
  }
  const std::filesystem::path out_dir = argv[1];
  const bool quick = argc == 3;
  std::filesystem::create_directories(out_dir);
  const std::vector<Network> networks =
      quick ? std::vector<Network>{{"100 ms", {0.1, 0, 0, 1}}}
            : std::vector<Network>{{"0 ms", {0, 0, 0, 1}},
                                   {"10 ms", {0.01, 0, 0, 1}},
                                   {"50 ms", {0.05, 0, 0, 1}},
                                   {"100 ms", {0.1, 0, 0, 1}},
                                   {"200 ms", {0.2, 0, 0, 1}},
                                   {"50 ms +-10 ms", {0.05, 0.01, 0, 1}},
                                   {"50 ms, 1 % loss", {0.05, 0, 0.01, 1}}};
  const std::vector<Body> scenes = bodies(quick);
  felt::study::Progress progress(static_cast<int>(scenes.size() * (1 + 2 * networks.size())));
  std::ofstream cases(out_dir / "cases.tsv");
  for (const Body& body : scenes) {
    RemoteCase c;
    c.scene = std::filesystem::path(FELT_SCENE_DIR) / body.scene;
    c.path = body.path;
    c.duration = 3;
    const auto run = [&](const std::string& network, const char* mode, const char* kind,
                         const std::string& file) {
      progress.begin(std::string(body.name) + ", " + network + ", " + mode);
      const auto samples = felt::study::run_remote_case(c);
      felt::study::write_remote_log(out_dir / file, samples);
      cases << body.name << "\t" << network << "\t" << mode << "\t" << kind << "\t" << file << "\n";
      progress.end(std::to_string(samples.size()) + " ticks");
    };
    c.rendering = Rendering::kRoundTrip;
    c.network = {};
    run("0 ms", "reference", "round-trip", std::string(body.name) + "-reference.csv");
    for (std::size_t i = 0; i < networks.size(); ++i) {
      c.network = networks[i].network;
      c.rendering = Rendering::kRoundTrip;
      run(networks[i].label, "round trip", "round-trip",
          std::string(body.name) + "-rt-" + std::to_string(i) + ".csv");
      c.rendering = Rendering::kLocalModel;
      run(networks[i].label, "local model", "local",
          std::string(body.name) + "-local-" + std::to_string(i) + ".csv");
    }
  }
  return cases ? 0 : 1;
}
