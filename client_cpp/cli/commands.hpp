#pragma once
// The commands of the felt command-line client, one file per group; felt_cli.cpp parses the
// command line into these options and calls them. Each returns the process's exit status.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "async_client.hpp"
#include "felt_client.hpp"

namespace felt::cli {

/// What every command takes: where the server is, and which scene to be in.
struct Common {
  std::string server = "127.0.0.1:7450";
  std::string token;
  std::string scene;       ///< load this scene (by name) first
  std::uint64_t join = 0;  ///< or join this running scene first
};

/// Connects, says hello and loads --scene or joins --join if given.
felt::v1::Welcome connect(client::Client& client, const Common& common,
                          const std::string& name = "felt-cli");
/// The same for an asynchronous client.
felt::v1::Welcome connect(client::AsyncClient& client, const Common& common,
                          const std::string& name = "felt-cli");

// scene_commands.cpp
int hello(const Common& common);
int list_scenes(const Common& common);
struct LoadOptions {
  std::string name;
  std::string json_file;
  bool shared = false;
};
int load(const Common& common, const LoadOptions& options);
int stats(const Common& common);

// control_commands.cpp: each prints the scene's status after the request (destroy: its id)
int pause(const Common& common);
int resume(const Common& common);
int step(const Common& common, std::uint32_t steps);
int reset(const Common& common);
/// Saves the scene's state (SaveState with its data) to `file`, as protobuf's JSON mapping of
/// SceneState.
int save(const Common& common, const std::string& file);
/// Restores a state `save` wrote (RestoreState with its data).
int restore(const Common& common, const std::string& file);
/// Destroys a running scene by id (0: the one --scene or --join puts the client in).
int destroy(const Common& common, std::uint64_t scene);

// body_commands.cpp
struct ClothOptions {
  std::string name;
  std::vector<std::uint32_t> grid{20, 20};
  std::vector<double> size{1, 1};
  std::vector<double> center{0, 1.5, 0};
  std::string plane = "xy";
  double mass = 0.5;
  std::string integrator = "symplectic_euler";
  std::string pin = "top_corners";
};
int add_cloth(const Common& common, const ClothOptions& options, const std::string& json);
struct SolidOptions {
  std::string name;
  std::vector<std::uint32_t> cells{3, 3, 3};
  std::vector<double> size{0.3, 0.3, 0.3};
  std::vector<double> center{0, 1, 0};
  std::string model = "mass_spring";
  double node_mass = 0.01;
};
int add_solid(const Common& common, const SolidOptions& options, const std::string& json);
int remove_body(const Common& common, std::uint32_t body);
int set(const Common& common, const felt::v1::SetBodyParameters& parameters);
int pin(const Common& common, std::uint32_t body, const std::vector<std::uint32_t>& pins,
        const std::vector<std::uint32_t>& unpins);

// watch_command.cpp
struct WatchOptions {
  int frames = 10;
  std::string out_dir = "frames";
  std::string format = "obj";
  double rate = 0;
  bool normals = false;
  bool quantized = false;
  bool deltas = false;
  std::vector<std::uint32_t> bodies;
};
int watch(const Common& common, const WatchOptions& options);

// device_commands.cpp: the haptic device emulator
struct DeviceOptions {
  std::vector<double> at;  ///< a single update here (touch --at)
  std::string path;        ///< line, circle, press or csv
  std::vector<double> from, to, center, axis{0, 1, 0};
  double radius = 0.05;
  double period = 2;    ///< s
  double duration = 0;  ///< s; 0: one period (press: the period and a second held)
  double rate = 1000;   ///< Hz
  std::uint32_t buttons = 0;
  std::string csv;  ///< csv path: time, x, y, z[, buttons] per line
  std::string log;  ///< per update: CSV of force, contact and round trip
  std::uint32_t proxy = 0;
  /// render forces locally against the server's local models (docs/protocol.md 7.5)
  bool local_model = false;
  double model_radius = 0.1;   ///< m: the surface sent around the proxy
  double upstream_rate = 250;  ///< Hz: ProxyUpdates sent with --local-model
  double device_damping = 20;  ///< N·s/m the delay-adapted stiffness counts on
};
int touch(const Common& common, const DeviceOptions& options);
int grab(const Common& common, DeviceOptions options);
int record(const Common& common, const DeviceOptions& options, const std::string& out);
int replay(const Common& common, const std::string& file, double tolerance);

// bench_latency.cpp
struct BenchOptions {
  double seconds = 10;
  double rate = 1000;
  int clients = 1;
  double frame_rate = 60;  ///< 0: no frames
  bool quantized = false;
  bool deltas = false;
  std::vector<double> at{0, 1.2, 0.01};
  std::string csv;       ///< one line per round trip: client, send time, round trip and its legs
  int slow_readers = 0;  ///< more clients that subscribe at the highest rate and never read
  int busy_threads = 0;  ///< bench-floor: threads that spin meanwhile, as a physics thread steps
};
int bench_latency(const Common& common, const BenchOptions& options);
// bench_floor.cpp: the same round trip over raw loopback TCP (clients, rate, seconds and busy
// threads only)
int bench_floor(const BenchOptions& options);

}  // namespace felt::cli
