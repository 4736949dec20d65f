#pragma once
// What `feltd compare` and `feltd sweep` share: variants of one scene file (its overrides), a
// reference run kept sample by sample, and runs measured against it at the same times.

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "runtime/sampled_run.hpp"
#include "runtime/trajectory_error.hpp"

namespace felt::feltd {

/// What compare and sweep are both told: the scene, its overrides, the reference, how long to
/// run and when to sample.
struct MeasureOptions {
  std::string scene;
  std::string scene_dir;
  std::vector<std::string> overrides;  ///< --set, for every run and the reference
  std::vector<std::string> reference;  ///< KEY=VALUE for the reference; empty: the default
  double duration = 1;                 ///< simulated seconds
  double sample_interval = 0;          ///< s; 0: chosen by plan_samples
  bool json = false;
};

/// Adds the options of MeasureOptions to `command`; `reference` says what the default
/// reference is.
void add_measure_options(CLI::App& command, MeasureOptions& options, const std::string& reference);

/// The default reference takes steps this many times smaller than the run it checks, with RK4:
/// its own error is then about 16⁴ ≈ 6.6·10⁴ times smaller than RK4's at the run's step.
constexpr int kReferenceStepDivisor = 16;

/// `KEY=VALUE` overrides giving every body of `document` that takes an integrator (cloths,
/// solids but shape matching) the integrator `name`.
std::vector<std::string> integrator_overrides(const nlohmann::json& document,
                                              std::string_view name);

/// The default reference of a run at step `h`: RK4 for every body at h / 16.
std::vector<std::string> default_reference(const nlohmann::json& document, double h);

/// `time_step=h`, written so that it reads back as exactly h.
std::string time_step_override(double h);

/// When samples are taken: every `interval` simulated seconds, `samples` times.
struct SamplePlan {
  double interval = 0;
  std::size_t samples = 0;
};

/// Samples every `interval` (0: the smallest multiple of `largest_step` giving at most 200
/// samples) over `duration`; an error when that leaves no sample.
std::expected<SamplePlan, std::string> plan_samples(double duration, double largest_step,
                                                    double interval);

/// A run measured against a reference: its cost, drift and health, and its bodies' errors.
struct MeasuredRun {
  SampledRunStats stats;
  std::vector<BodyError> errors;
};

/// Runs `scene` as the reference, keeping its positions at every sample of `plan`.
std::expected<ReferenceTrajectory, std::string> run_reference(Scene& scene, const SamplePlan& plan,
                                                              SampledRunStats& stats);

/// Runs `scene` and measures it against `reference` at every sample of `plan`. An error when
/// its time step does not divide the sample interval or its bodies are not the reference's.
std::expected<MeasuredRun, std::string> run_measured(Scene& scene,
                                                     const ReferenceTrajectory& reference,
                                                     const SamplePlan& plan);

nlohmann::json to_json(const SampledRunStats& stats);

}  // namespace felt::feltd
