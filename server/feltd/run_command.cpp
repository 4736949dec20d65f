#include "feltd/run_command.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "feltd/run_stats_json.hpp"
#include "feltd/scene_file.hpp"
#include "runtime/batch_run.hpp"
#include "runtime/run_trace.hpp"

namespace felt::feltd {

int run(const RunOptions& options) {
  auto scene = load_scene_file(options.scene, options.overrides, options.scene_dir);
  if (!scene) {
    std::cerr << "feltd: " << scene.error() << "\n";
    return 2;
  }
  felt::BatchHaptics haptics;
  std::vector<felt::HapticRecord> replayed;
  if (!options.replay.empty()) {
    std::ifstream in(options.replay);
    auto records =
        in ? felt::read_recording(in) : std::unexpected(std::string("cannot open the file"));
    if (!records) {
      std::cerr << "feltd: --replay " << options.replay << ": " << records.error() << "\n";
      return 2;
    }
    replayed = std::move(*records);
    haptics.replay = &replayed;
  }
  std::ofstream recording;
  if (!options.record.empty()) {
    recording.open(options.record);
    if (!recording) {
      std::cerr << "feltd: --record: cannot write " << options.record << "\n";
      return 2;
    }
    haptics.record = &recording;
  }
  std::optional<felt::RunTrace> trace;
  if (!options.trace.empty()) {
    auto opened = felt::RunTrace::open(options.trace, scene->name, options.every);
    if (!opened) {
      std::cerr << "feltd: --trace: " << opened.error() << "\n";
      return 2;
    }
    trace.emplace(std::move(*opened));
    trace->record(scene->world, {});
  }
  const felt::BatchRunStats stats = felt::run_batch(
      *scene, options.steps, haptics,
      trace
          ? felt::StepObserver([&trace](const felt::World& world, const felt::StepReport& report) {
              trace->record(world, report);
            })
          : felt::StepObserver());
  const nlohmann::json json = stats_to_json(stats);
  std::printf("%llu steps, sim %.4f s, wall %.3f s, %.4f ms/step\n",
              static_cast<unsigned long long>(stats.steps), stats.sim_time, stats.wall_seconds,
              stats.ms_per_step);
  if (const auto& totals = json["solids"]["totals"]; totals["nodes"].get<std::size_t>() > 0) {
    std::printf("solids: %zu nodes, %zu edges, %zu triangles, %zu tetrahedra\n",
                totals["nodes"].get<std::size_t>(), totals["edges"].get<std::size_t>(),
                totals["triangles"].get<std::size_t>(), totals["tets"].get<std::size_t>());
  }
  if (const felt::HapticRunStats& h = stats.haptics; h.ticks > 0) {
    std::printf(
        "haptics: %llu ticks, %llu in contact, %.2f us/tick in contact, %.2f free, "
        "max force %.3f N, force step max %.4f N mean %.5f N\n",
        static_cast<unsigned long long>(h.ticks), static_cast<unsigned long long>(h.contact_ticks),
        h.mean_contact_us, h.mean_free_us, h.max_force, h.max_force_step, h.mean_force_step);
    if (h.compared > 0) {
      std::printf("replay: %llu of %llu updates collision-equivalent to the recording\n",
                  static_cast<unsigned long long>(h.equivalent),
                  static_cast<unsigned long long>(h.compared));
    }
  }
  if (stats.nonfinite) {
    std::printf("UNSTABLE: %llu steps could not be rescued (rolled back, body stopped)\n",
                static_cast<unsigned long long>(stats.unrecoverable_steps));
  }
  if (trace) {
    if (!trace->finish()) {
      std::cerr << "feltd: --trace: " << trace->error() << "\n";
      return 1;
    }
    std::printf("trace: %s/trace.csv, %zu frames in %s/frames.pvd\n", options.trace.c_str(),
                trace->frames(), options.trace.c_str());
  }
  if (!options.stats_json.empty()) {
    std::ofstream out(options.stats_json);
    out << json.dump(2) << "\n";
    if (!out) {
      std::cerr << "feltd: cannot write " << options.stats_json << "\n";
      return 1;
    }
  }
  return stats.nonfinite ? 3 : 0;
}

CLI::App* add_run_command(CLI::App& app, RunOptions& options) {
  CLI::App* run_cmd = app.add_subcommand("run", "Step a scene headless, without a network");
  run_cmd->add_option("scene", options.scene, "Scene JSON file")
      ->required()
      ->check(CLI::ExistingFile);
  run_cmd->add_option("--steps", options.steps, "Number of steps")
      ->required()
      ->check(CLI::PositiveNumber);
  run_cmd->add_option(
      "--set", options.overrides,
      "KEY=VALUE override, KEY a dotted path (bodies.0.integrator), VALUE JSON or a string");
  run_cmd->add_option("--scene-dir", options.scene_dir,
                      "Directory mesh files resolve in (default: the scene file's directory)");
  run_cmd->add_option("--stats-json", options.stats_json, "Write run statistics to this file");
  run_cmd->add_option("--record", options.record,
                      "Write every scripted-device update (position, contact, force) to this CSV");
  run_cmd
      ->add_option("--replay", options.replay,
                   "Drive the devices from a --record CSV and compare their contacts with it")
      ->check(CLI::ExistingFile);
  run_cmd->add_option("--trace", options.trace,
                      "Write DIR/trace.csv (a row per step and body: energies and drift, centre of "
                      "mass, bounding box, speed, strain, substeps, state hash) and every body's "
                      "positions as a VTK series (DIR/frames.pvd)");
  run_cmd->add_option("--every", options.every, "With --trace: a VTK frame every N steps")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  return run_cmd;
}

}  // namespace felt::feltd
