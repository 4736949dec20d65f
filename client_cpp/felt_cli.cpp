// felt: the command-line client of feltd. The commands live in cli/.

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "command_line/usage_status.hpp"
#include "scheduling/latency_options.hpp"

namespace {

using namespace felt::cli;
namespace v1 = felt::v1;

void scene_options(CLI::App* command, Common& common) {
  command->add_option("--scene", common.scene, "Load this scene (by name) first");
  command->add_option("--join", common.join, "Join this running scene (an id from 'felt scenes')");
}

void path_options(CLI::App* command, DeviceOptions& d) {
  command->add_option("--path", d.path, "line, circle, press or csv");
  command->add_option("--from", d.from, "Start X,Y,Z (line, press)")->delimiter(',')->expected(3);
  command->add_option("--to", d.to, "End X,Y,Z (line, press)")->delimiter(',')->expected(3);
  command->add_option("--center", d.center, "Centre X,Y,Z (circle)")->delimiter(',')->expected(3);
  command->add_option("--axis", d.axis, "Circle axis X,Y,Z")->delimiter(',')->expected(3);
  command->add_option("--radius", d.radius, "Circle radius, m")->capture_default_str();
  command->add_option("--period", d.period, "Seconds per round trip, turn or press")
      ->capture_default_str();
  command->add_option("--duration", d.duration, "Seconds to run (default: one period)");
  command->add_option("--rate", d.rate, "Updates per second")->capture_default_str();
  command->add_option("--csv", d.csv, "Samples 'time, x, y, z[, buttons]' (--path csv)");
  command->add_option("--buttons", d.buttons, "Buttons held (bit 0 grabs)");
  command->add_option("--proxy", d.proxy, "Proxy id")->capture_default_str();
}

void local_model_options(CLI::App* command, DeviceOptions& d) {
  command->add_flag("--local-model", d.local_model,
                    "Render forces here at --rate against the server's local model of the "
                    "surface near the proxy, sending updates upstream at --upstream-rate");
  command->add_option("--model-radius", d.model_radius, "Local model radius, m")
      ->capture_default_str();
  command->add_option("--upstream-rate", d.upstream_rate, "Updates per second with --local-model")
      ->capture_default_str();
  command
      ->add_option("--device-damping", d.device_damping,
                   "N*s/m of the device and hand the delay-adapted stiffness counts on")
      ->capture_default_str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"felt " FELT_VERSION " - command-line client of the Felt simulation service"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "felt " FELT_VERSION);
  // the options below are taken after the command's name too (felt stats --server HOST:PORT):
  // every command inherits the fallthrough to them
  app.fallthrough();
  Common common;
  if (const char* token = std::getenv("FELT_TOKEN")) common.token = token;
  app.add_option("--server", common.server, "feltd address HOST:PORT (default: $FELT_SERVER)")
      ->envname("FELT_SERVER")
      ->capture_default_str();
  app.add_option("--token", common.token, "Token the server requires (default: $FELT_TOKEN)");
  // every thread of felt is on its haptic path (device loops, the replies' reader), and on a
  // machine shared with feltd a device loop must preempt the physics thread as soon as it wakes
  int slice_us = 100;
  app.add_option("--slice-us", slice_us,
                 "Time slice felt's threads ask the kernel for (Linux 6.12+; 0: the kernel's)")
      ->check(CLI::Range(0, 0) | CLI::Range(static_cast<int>(felt::kMinTimeSlice.count()),
                                            static_cast<int>(felt::kMaxTimeSlice.count())))
      ->capture_default_str();
  // the device's host wakes for every ForceUpdate: with halting idle cores (a VM) that wake-up
  // is the outbound leg's tail
  int wakeup_latency_us = -1;
  app.add_option("--cpu-wakeup-latency-us", wakeup_latency_us,
                 "Hold every idle core's wake-up latency at most this while felt runs "
                 "(system-wide, root; 0: idle cores poll; -1: the system's)")
      ->check(CLI::Range(-1, static_cast<int>(felt::kMaxCpuWakeupLatency.count())))
      ->capture_default_str();
  // the same without root; feltd does it while updates arrive, which covers a device on its host
  bool spin_idle_cores = false;
  app.add_flag("--spin-idle-cores", spin_idle_cores,
               "Keep this host's idle cores awake while felt runs, with a spinning thread per "
               "core that yields to any other (no privilege; for a device on another host than "
               "feltd)");

  CLI::App* hello_cmd =
      app.add_subcommand("hello", "Print the server's version, capabilities and limits");
  CLI::App* scenes_cmd = app.add_subcommand("scenes", "List scene files and running scenes");
  CLI::App* stats_cmd =
      app.add_subcommand("stats", "Print the statistics of a scene and the server");
  scene_options(stats_cmd, common);

  LoadOptions load_options;
  CLI::App* load_cmd = app.add_subcommand("load", "Load a scene that stays for others to join");
  load_cmd->add_option("name", load_options.name,
                       "Scene name (a file in the server's scene directory)");
  load_cmd->add_option("--json", load_options.json_file, "Send this scene file instead");
  load_cmd->add_flag("--shared", load_options.shared, "Let every client change every body");

  ClothOptions cloth;
  std::string body_json;
  CLI::App* cloth_cmd = app.add_subcommand("add-cloth", "Add a cloth to a scene");
  cloth_cmd->add_option("--name", cloth.name, "Body name");
  cloth_cmd->add_option("--grid", cloth.grid, "Particles NX,NY")->delimiter(',')->expected(2);
  cloth_cmd->add_option("--size", cloth.size, "Width,height in m")->delimiter(',')->expected(2);
  cloth_cmd->add_option("--center", cloth.center, "Centre X,Y,Z")->delimiter(',')->expected(3);
  cloth_cmd->add_option("--plane", cloth.plane, "xy (hanging) or xz (lying)")
      ->capture_default_str();
  cloth_cmd->add_option("--mass", cloth.mass, "Total mass, kg")->capture_default_str();
  cloth_cmd->add_option("--integrator", cloth.integrator, "Integrator")->capture_default_str();
  cloth_cmd->add_option("--pin", cloth.pin, "Pin preset (top_corners, four_corners, top_row, none)")
      ->capture_default_str();
  cloth_cmd->add_option("--json", body_json, "The body's scene JSON (or @FILE) instead");
  scene_options(cloth_cmd, common);

  SolidOptions solid;
  CLI::App* solid_cmd =
      app.add_subcommand("add-solid", "Add a soft solid (a lattice box) to a scene");
  solid_cmd->add_option("--name", solid.name, "Body name");
  solid_cmd->add_option("--cells", solid.cells, "Cells NX,NY,NZ")->delimiter(',')->expected(3);
  solid_cmd->add_option("--size", solid.size, "Size X,Y,Z in m")->delimiter(',')->expected(3);
  solid_cmd->add_option("--center", solid.center, "Centre X,Y,Z")->delimiter(',')->expected(3);
  solid_cmd->add_option("--model", solid.model, "mass_spring, shape_matching or fem")
      ->capture_default_str();
  solid_cmd->add_option("--node-mass", solid.node_mass, "kg per node")->capture_default_str();
  solid_cmd->add_option("--json", body_json, "The body's scene JSON (or @FILE) instead");
  scene_options(solid_cmd, common);

  CLI::App* pause_cmd = app.add_subcommand("pause", "Stop the scene's clock");
  scene_options(pause_cmd, common);
  CLI::App* resume_cmd = app.add_subcommand("resume", "Run the scene in real time again");
  scene_options(resume_cmd, common);
  std::uint32_t steps = 0;
  CLI::App* step_cmd = app.add_subcommand("step", "Take N steps of a paused scene");
  step_cmd->add_option("N", steps, "How many steps")->required();
  scene_options(step_cmd, common);
  CLI::App* reset_cmd =
      app.add_subcommand("reset", "Build the scene again from its source, at step 0");
  scene_options(reset_cmd, common);
  std::string state_file;
  CLI::App* save_cmd = app.add_subcommand("save", "Save the scene's state to a JSON file");
  save_cmd->add_option("FILE", state_file, "Where to write it")->required();
  scene_options(save_cmd, common);
  CLI::App* restore_cmd = app.add_subcommand("restore", "Restore a state 'felt save' wrote");
  restore_cmd->add_option("FILE", state_file, "A file 'felt save' wrote")->required();
  scene_options(restore_cmd, common);
  std::uint64_t destroyed_scene = 0;
  CLI::App* destroy_cmd = app.add_subcommand(
      "destroy", "Stop a running scene and send its clients out (not the server's own scenes)");
  destroy_cmd->add_option("SCENE", destroyed_scene, "Scene id (from 'felt scenes')")->required();

  std::uint32_t body = 0;
  CLI::App* remove_cmd = app.add_subcommand("remove", "Remove a body");
  remove_cmd->add_option("--body", body, "Body id")->required();
  scene_options(remove_cmd, common);

  v1::SetBodyParameters parameters;
  std::string integrator;
  double drag = 0, structural = 0, shear = 0, bend = 0, max_strain = 0, damping = 0, friction = 0,
         max_step = 0;
  CLI::App* set_cmd = app.add_subcommand("set", "Change a body's integrator or parameters");
  set_cmd->add_option("--body", body, "Body id")->capture_default_str();
  auto* integrator_opt = set_cmd->add_option("--integrator", integrator, "Integrator name");
  auto* drag_opt = set_cmd->add_option("--drag", drag, "Viscous drag, N s/m");
  auto* structural_opt =
      set_cmd->add_option("--structural", structural, "Structural stiffness, N/m");
  auto* shear_opt = set_cmd->add_option("--shear", shear, "Shear stiffness, N/m");
  auto* bend_opt = set_cmd->add_option("--bend", bend, "Bend stiffness, N/m");
  auto* strain_opt =
      set_cmd->add_option("--max-strain", max_strain, "Stretch limit (0 switches it off)");
  auto* damping_opt =
      set_cmd->add_option("--damping", damping, "Spring damping (cloth) or the model's (solid)");
  auto* friction_opt = set_cmd->add_option("--friction", friction, "Coulomb friction (solid)");
  auto* max_step_opt = set_cmd->add_option(
      "--max-step", max_step, "The body's longest step, s (substeps of the scene's; 0: none)");
  scene_options(set_cmd, common);

  std::vector<std::uint32_t> pins, unpins;
  CLI::App* pin_cmd = app.add_subcommand("pin", "Pin particles where they are, or free them");
  pin_cmd->add_option("--body", body, "Body id")->capture_default_str();
  pin_cmd->add_option("--pin", pins, "Particles to pin, e.g. 0,19")->delimiter(',');
  pin_cmd->add_option("--unpin", unpins, "Particles to free")->delimiter(',');
  scene_options(pin_cmd, common);

  WatchOptions watch_options;
  CLI::App* watch_cmd =
      app.add_subcommand("watch", "Save streamed frames as OBJ, PLY or VTK files");
  watch_cmd->add_option("--frames", watch_options.frames, "How many frames")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  watch_cmd->add_option("--out", watch_options.out_dir, "Directory for the files")
      ->capture_default_str();
  watch_cmd->add_option("--format", watch_options.format, "obj, ply or vtk (a ParaView series)")
      ->capture_default_str();
  watch_cmd->add_option("--rate", watch_options.rate,
                        "Frames per second to ask for (0: the server's default)");
  watch_cmd->add_flag("--normals", watch_options.normals, "Ask for vertex normals too");
  watch_cmd->add_flag("--quantized", watch_options.quantized, "16-bit positions");
  watch_cmd->add_flag("--deltas", watch_options.deltas,
                      "16-bit deltas against acknowledged frames");
  watch_cmd->add_option("--bodies", watch_options.bodies, "Only these bodies, e.g. 0,2")
      ->delimiter(',');
  scene_options(watch_cmd, common);

  DeviceOptions device;
  CLI::App* touch_cmd = app.add_subcommand(
      "touch", "Drive a haptic proxy: one update --at a point, or a scripted --path at 1 kHz");
  touch_cmd->add_option("--at", device.at, "A single update at X,Y,Z")->delimiter(',')->expected(3);
  path_options(touch_cmd, device);
  local_model_options(touch_cmd, device);
  touch_cmd->add_option("--log", device.log,
                        "Write every update's force, contact and round trip (CSV)");
  scene_options(touch_cmd, common);

  CLI::App* grab_cmd = app.add_subcommand(
      "grab", "Press from --from to --to with the grab button held, dragging what it touches");
  path_options(grab_cmd, device);
  local_model_options(grab_cmd, device);
  grab_cmd->add_option("--log", device.log, "Write every update (CSV)");
  scene_options(grab_cmd, common);

  std::string record_out;
  CLI::App* record_cmd = app.add_subcommand(
      "record",
      "Run a scripted path and record the device and its contacts (feltd run --replay reads it)");
  path_options(record_cmd, device);
  record_cmd->add_option("--out", record_out, "Recording CSV")->required();
  scene_options(record_cmd, common);

  std::string replay_file;
  double tolerance = 1e-6;
  CLI::App* replay_cmd = app.add_subcommand(
      "replay", "Drive a proxy through a recording and count collision-equivalent updates");
  replay_cmd->add_option("recording", replay_file, "A recording CSV")
      ->required()
      ->check(CLI::ExistingFile);
  replay_cmd->add_option("--tolerance", tolerance, "Proxy distance that still counts as equal, m")
      ->capture_default_str();
  scene_options(replay_cmd, common);

  BenchOptions bench;
  CLI::App* bench_cmd =
      app.add_subcommand("bench-latency", "Measure the haptic round trip at 1 kHz");
  bench_cmd->add_option("--seconds", bench.seconds, "How long")->capture_default_str();
  bench_cmd->add_option("--rate", bench.rate, "Updates per second per client")
      ->capture_default_str();
  bench_cmd->add_option("--clients", bench.clients, "Clients at once")->capture_default_str();
  bench_cmd->add_option("--frame-rate", bench.frame_rate, "Frames each client streams (0: none)")
      ->capture_default_str();
  bench_cmd->add_flag("--quantized", bench.quantized, "Stream 16-bit frames");
  bench_cmd->add_flag("--deltas", bench.deltas, "Stream 16-bit deltas");
  bench_cmd->add_option("--at", bench.at, "Where the devices hold their proxies X,Y,Z")
      ->delimiter(',')
      ->expected(3);
  bench_cmd->add_option("--csv", bench.csv,
                        "Every round trip: client, sent_us, round_trip_us, inbound_us, "
                        "outbound_us (CSV)");
  bench_cmd->add_option("--slow-readers", bench.slow_readers,
                        "More clients that subscribe to frames and never read them");
  scene_options(bench_cmd, common);

  BenchOptions floor;
  CLI::App* floor_cmd = app.add_subcommand(
      "bench-floor", "The machine's own round trip: raw loopback TCP at the same rate, no Felt");
  floor_cmd->add_option("--seconds", floor.seconds, "How long")->capture_default_str();
  floor_cmd->add_option("--rate", floor.rate, "Messages per second per client")
      ->capture_default_str();
  floor_cmd->add_option("--clients", floor.clients, "Clients at once")->capture_default_str();
  floor_cmd
      ->add_option("--busy-threads", floor.busy_threads,
                   "Threads that spin at the kernel's time slice meanwhile, as physics does")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return felt::usage_status(app, e);
  }
  felt::LatencyOptions latency;
  latency.slice = std::chrono::microseconds(slice_us);
  latency.slice_inheritance = felt::SliceInheritance::kAlsoThreadsItStarts;
  if (wakeup_latency_us >= 0) {
    latency.cpu_wakeup_latency = std::chrono::microseconds(wakeup_latency_us);
  }
  latency.spin_until_exit = spin_idle_cores;
  const felt::AppliedLatency applied_latency =
      felt::apply(latency, {"felt's threads", "--slice-us", "--realtime", "--cpu-wakeup-latency-us",
                            "--spin-idle-cores"});
  for (const std::string& error : applied_latency.errors()) std::cerr << "felt: " << error << "\n";
  try {
    if (hello_cmd->parsed()) return hello(common);
    if (scenes_cmd->parsed()) return list_scenes(common);
    if (stats_cmd->parsed()) return stats(common);
    if (load_cmd->parsed()) {
      if (load_options.name.empty() == load_options.json_file.empty()) {
        std::cerr << "felt: load takes a scene name or --json FILE\n";
        return felt::kUsageStatus;
      }
      return load(common, load_options);
    }
    if (pause_cmd->parsed()) return pause(common);
    if (resume_cmd->parsed()) return resume(common);
    if (step_cmd->parsed()) return step(common, steps);
    if (reset_cmd->parsed()) return reset(common);
    if (save_cmd->parsed()) return save(common, state_file);
    if (restore_cmd->parsed()) return restore(common, state_file);
    if (destroy_cmd->parsed()) return destroy(common, destroyed_scene);
    if (cloth_cmd->parsed()) return add_cloth(common, cloth, body_json);
    if (solid_cmd->parsed()) return add_solid(common, solid, body_json);
    if (remove_cmd->parsed()) return remove_body(common, body);
    if (set_cmd->parsed()) {
      parameters.set_body_id(body);
      if (*integrator_opt) parameters.set_integrator(integrator);
      if (*drag_opt) parameters.set_drag(drag);
      if (*structural_opt) parameters.set_structural_stiffness(structural);
      if (*shear_opt) parameters.set_shear_stiffness(shear);
      if (*bend_opt) parameters.set_bend_stiffness(bend);
      if (*strain_opt) parameters.set_max_strain(max_strain);
      if (*damping_opt) parameters.set_damping(damping);
      if (*friction_opt) parameters.set_friction(friction);
      if (*max_step_opt) parameters.set_max_step(max_step);
      return set(common, parameters);
    }
    if (pin_cmd->parsed()) return pin(common, body, pins, unpins);
    if (watch_cmd->parsed()) return watch(common, watch_options);
    if (touch_cmd->parsed()) {
      if (device.at.empty() && device.path.empty()) {
        std::cerr << "felt: touch needs --at X,Y,Z or --path\n";
        return felt::kUsageStatus;
      }
      return touch(common, device);
    }
    if (grab_cmd->parsed()) return grab(common, device);
    if (record_cmd->parsed()) return record(common, device, record_out);
    if (replay_cmd->parsed()) return replay(common, replay_file, tolerance);
    if (floor_cmd->parsed()) return bench_floor(floor);
    return bench_latency(common, bench);
  } catch (const felt::client::ClientError& e) {
    std::cerr << "felt: " << e.what();
    // the code the server refused with, as docs/protocol.md names it
    if (e.code() != v1::ERROR_CODE_UNSPECIFIED) {
      std::cerr << " (" << v1::ErrorCode_Name(e.code()).substr(std::strlen("ERROR_CODE_")) << ")";
    }
    std::cerr << "\n";
    return 1;
  } catch (const UsageError& e) {
    std::cerr << "felt: " << e.what() << "\n";
    return felt::kUsageStatus;
  } catch (const LocalError& e) {
    std::cerr << "felt: " << e.what() << "\n";
    return 1;
  }
}
