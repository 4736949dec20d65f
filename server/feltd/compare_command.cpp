#include "feltd/compare_command.hpp"

#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "feltd/measured_runs.hpp"
#include "feltd/scene_file.hpp"

namespace felt::feltd {
namespace {

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : " ") + item;
  return out;
}

void print_run(const char* label, const SampledRunStats& s) {
  std::printf("%-10s %13.6g %15.4g %15.4g %16.4g %16.4g %8llu %13llu\n", label, s.time_step,
              s.cpu_per_sim_second, s.wall_per_sim_second, s.energy_drift, s.max_energy_drift,
              static_cast<unsigned long long>(s.rescued_steps),
              static_cast<unsigned long long>(s.unrecoverable_steps));
}

}  // namespace

int compare(const CompareOptions& options) {
  auto document = read_scene_file(options.scene, options.overrides);
  auto scene = document ? load_scene_file(*document, options.scene, options.scene_dir)
                        : std::unexpected(document.error());
  if (!scene) {
    std::cerr << "feltd: " << scene.error() << "\n";
    return 2;
  }
  const double h = scene->world.settings().time_step;
  const std::vector<std::string> reference_overrides =
      options.reference.empty() ? default_reference(*document, h) : options.reference;
  auto reference_scene = load_scene_variant(*document, reference_overrides, "--reference",
                                            options.scene, options.scene_dir);
  if (!reference_scene) {
    std::cerr << "feltd: " << reference_scene.error() << "\n";
    return 2;
  }
  const auto plan = plan_samples(options.duration, h, options.sample_interval);
  if (!plan) {
    std::cerr << "feltd: " << plan.error() << "\n";
    return 2;
  }
  SampledRunStats reference_stats;
  const auto reference = run_reference(*reference_scene, *plan, reference_stats);
  const auto run =
      reference ? run_measured(*scene, *reference, *plan) : std::unexpected(reference.error());
  if (!run) {
    std::cerr << "feltd: " << run.error() << "\n";
    return 2;
  }
  if (options.json) {
    nlohmann::json bodies = nlohmann::json::array();
    for (const BodyError& e : run->errors) {
      bodies.push_back(
          {{"name", e.name}, {"rms_error", e.rms}, {"max_error", e.max}, {"end_error", e.end}});
    }
    const nlohmann::json out = {{"scene", options.scene},
                                {"overrides", options.overrides},
                                {"reference_overrides", reference_overrides},
                                {"sample_interval", plan->interval},
                                {"samples", plan->samples},
                                {"bodies", bodies},
                                {"run", feltd::to_json(run->stats)},
                                {"reference", feltd::to_json(reference_stats)}};
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
  }
  std::printf("reference: %s\n%zu samples every %g s to t = %g s\n\n",
              joined(reference_overrides).c_str(), plan->samples, plan->interval,
              plan->interval * static_cast<double>(plan->samples));
  std::printf("%-20s %14s %14s %14s\n", "body", "rms error (m)", "max error (m)", "at end (m)");
  for (const BodyError& e : run->errors) {
    std::printf("%-20s %14.4g %14.4g %14.4g\n", e.name.c_str(), e.rms, e.max, e.end);
  }
  std::printf("\n%-10s %13s %15s %15s %16s %16s %8s %13s\n", "run", "time step (s)",
              "CPU s / sim s", "wall s / sim s", "energy drift (J)", "max |drift| (J)", "rescued",
              "unrecoverable");
  print_run("as given", run->stats);
  print_run("reference", reference_stats);
  return 0;
}

CLI::App* add_compare_command(CLI::App& app, CompareOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Run a scene and a reference of it (default: rk4 at a sixteenth of the step) and print "
      "each body's position error, the energy drift and the cost of both");
  add_measure_options(*cmd, options, "rk4 for every body and time_step divided by 16");
  return cmd;
}

}  // namespace felt::feltd
