#include "feltd/measured_runs.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace felt::feltd {
namespace {

/// How many steps of `h` make `interval`; an error unless a whole number (to 1e-9).
std::expected<std::uint64_t, std::string> steps_per(double interval, double h) {
  const double ratio = interval / h;
  const double whole = std::round(ratio);
  if (!(whole >= 1) || std::abs(ratio - whole) > 1e-9 * ratio) {
    char why[160];
    std::snprintf(why, sizeof why,
                  "the time step %g s does not divide the sample interval %g s: choose steps "
                  "that divide each other, or --sample-interval",
                  h, interval);
    return std::unexpected(why);
  }
  return static_cast<std::uint64_t>(whole);
}

}  // namespace

std::vector<std::string> integrator_overrides(const nlohmann::json& document,
                                              std::string_view name) {
  std::vector<std::string> out;
  const auto bodies = document.find("bodies");
  if (bodies == document.end() || !bodies->is_array()) return out;
  for (std::size_t i = 0; i < bodies->size(); ++i) {
    const nlohmann::json& body = (*bodies)[i];
    if (!body.is_object()) continue;
    // shape matching has an update of its own and refuses every integrator
    if (body.value("type", "") == "solid" && body.value("model", "") == "shape_matching") continue;
    out.push_back("bodies." + std::to_string(i) + ".integrator=" + std::string(name));
  }
  return out;
}

std::string time_step_override(double h) {
  char text[32];
  // the shortest text that reads back as exactly h
  const auto end = std::to_chars(text, text + sizeof text, h).ptr;
  return "time_step=" + std::string(text, end);
}

std::vector<std::string> default_reference(const nlohmann::json& document, double h) {
  std::vector<std::string> out = integrator_overrides(document, "rk4");
  out.push_back(time_step_override(h / kReferenceStepDivisor));
  return out;
}

std::expected<SamplePlan, std::string> plan_samples(double duration, double largest_step,
                                                    double interval) {
  constexpr double kDefaultMaxSamples = 200;
  if (interval <= 0) {
    // the smallest multiple of the step giving at most 200 samples, or, within twice that, one
    // whose samples end on the duration
    const double steps = duration / largest_step;
    const double whole = std::round(steps);
    const double fewest = std::max(1.0, std::ceil(steps / kDefaultMaxSamples - 1e-9));
    double multiple = fewest;
    if (whole >= 1 && std::abs(steps - whole) <= 1e-9 * steps) {
      while (std::fmod(whole, multiple) != 0 && multiple < 2 * fewest) ++multiple;
      if (std::fmod(whole, multiple) != 0) multiple = fewest;
    }
    interval = largest_step * multiple;
  }
  // a duration meant as a multiple of the interval may fall a rounding error short of it
  const auto samples = static_cast<std::size_t>(std::floor(duration / interval + 1e-9));
  if (samples == 0) {
    return std::unexpected("--duration " + std::to_string(duration) +
                           " s is shorter than one sample interval (" + std::to_string(interval) +
                           " s)");
  }
  return SamplePlan{interval, samples};
}

std::expected<ReferenceTrajectory, std::string> run_reference(Scene& scene, const SamplePlan& plan,
                                                              SampledRunStats& stats) {
  const auto steps = steps_per(plan.interval, scene.world.settings().time_step);
  if (!steps) return std::unexpected("the reference: " + steps.error());
  ReferenceTrajectory reference;
  stats = run_sampled(scene, *steps, plan.samples,
                      [&](const World& world, std::size_t) { reference.add(world); });
  return reference;
}

std::expected<MeasuredRun, std::string> run_measured(Scene& scene,
                                                     const ReferenceTrajectory& reference,
                                                     const SamplePlan& plan) {
  const auto steps = steps_per(plan.interval, scene.world.settings().time_step);
  if (!steps) return std::unexpected(steps.error());
  TrajectoryError error(reference);
  std::string mismatch;
  MeasuredRun run;
  run.stats = run_sampled(scene, *steps, plan.samples, [&](const World& world, std::size_t k) {
    if (!mismatch.empty()) return;
    if (auto added = error.add(world, k); !added) mismatch = added.error();
  });
  if (!mismatch.empty()) return std::unexpected("not comparable with the reference: " + mismatch);
  run.errors = error.errors();
  return run;
}

void add_measure_options(CLI::App& command, MeasureOptions& options, const std::string& reference) {
  command.add_option("scene", options.scene, "Scene JSON file")
      ->required()
      ->check(CLI::ExistingFile);
  command.add_option("--set", options.overrides,
                     "KEY=VALUE override for every run (bodies.0.springs.shear.stiffness=80)");
  command.add_option(
      "--reference", options.reference,
      "KEY=VALUE overrides that make the reference, replacing the default (" + reference + ")");
  command.add_option("--duration", options.duration, "Simulated seconds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--sample-interval", options.sample_interval,
                  "Seconds between the samples the runs are compared at; every time step must "
                  "divide it (default: the largest step, or a multiple giving at most 200)")
      ->check(CLI::PositiveNumber);
  command.add_option("--scene-dir", options.scene_dir,
                     "Directory mesh files resolve in (default: the scene file's directory)");
  command.add_flag("--json", options.json, "Print the results as JSON");
}

nlohmann::json to_json(const SampledRunStats& stats) {
  return {{"time_step", stats.time_step},
          {"sim_time", stats.sim_time},
          {"wall_seconds", stats.wall_seconds},
          {"wall_seconds_per_sim_second", stats.wall_per_sim_second},
          {"cpu_seconds", stats.cpu_seconds},
          {"cpu_seconds_per_sim_second", stats.cpu_per_sim_second},
          {"start_energy", stats.start_energy},
          {"energy_drift", stats.energy_drift},
          {"max_energy_drift", stats.max_energy_drift},
          {"rescued_steps", stats.rescued_steps},
          {"unrecoverable_steps", stats.unrecoverable_steps},
          {"over_budget_steps", stats.over_budget_steps},
          {"nonfinite", stats.nonfinite}};
}

}  // namespace felt::feltd
