// Remote haptics in simulated time (issue 26): every case of docs/results/remote_haptics.md's
// deterministic section, each written as a `felt touch --log` CSV into OUT_DIR with a list of
// the cases (cases.tsv: scene, network, mode, remote_haptics.py's MODE, file) for
// scripts/study-remote-haptics to measure. --quick runs the cube at 100 ms only, --only BODY
// every case of one body (cube or curtain).
//
//   remote_haptics_study OUT_DIR [--quick | --only BODY]

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "remote_haptics_run.hpp"
#include "study_output.hpp"

namespace {

using felt::DevicePath;
using felt::study::RemoteCase;
using felt::study::Rendering;
using felt::study::SimulatedNetwork;

struct Body {
  const char* name;
  const char* scene;
  DevicePath path;
};

std::vector<Body> bodies(bool quick) {
  std::vector<Body> out;
  out.push_back({"cube", "pressed_cube.json", felt::study::cube_press_path()});
  if (quick) return out;
  out.push_back({"curtain", "default.json", felt::study::curtain_press_path()});
  return out;
}

struct Network {
  const char* label;
  SimulatedNetwork network;
};

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc == 3 && std::string(argv[2]) == "--quick";
  const bool only = argc == 4 && std::string(argv[2]) == "--only";
  if (argc != 2 && !quick && !only) {
    std::fprintf(stderr, "usage: remote_haptics_study OUT_DIR [--quick | --only BODY]\n");
    return 2;
  }
  const std::filesystem::path out_dir = argv[1];
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
  std::vector<Body> scenes = bodies(quick);
  if (only) {
    std::erase_if(scenes, [&](const Body& body) { return body.name != std::string(argv[3]); });
    if (scenes.empty()) {
      std::fprintf(stderr, "remote_haptics_study: no body %s (cube, curtain)\n", argv[3]);
      return 2;
    }
  }
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
