#include "feltd/sweep_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <expected>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "core/integrate/integrator.hpp"
#include "feltd/measured_runs.hpp"
#include "feltd/scene_file.hpp"
#include "feltd/sweep_plot.hpp"

namespace felt::feltd {
namespace {

/// One integrator at one step, summed over the bodies by their worst.
struct SweepRow {
  std::string integrator;
  double h = 0;
  SampledRunStats stats;
  Real max_error = 0;  ///< m, the largest of the bodies'
  Real rms_error = 0;  ///< m, the largest body RMS
  Real end_error = 0;  ///< m, the largest at the last sample
  bool pareto = false;
  bool searched = false;  ///< a step the search chose between two swept ones

  /// Ran to the end on its own: no step rescued by substeps, none unrecoverable, errors finite.
  bool stable() const {
    return stats.rescued_steps == 0 && stats.unrecoverable_steps == 0 && !stats.nonfinite &&
           std::isfinite(max_error);
  }
};

/// Marks the stable rows no other stable row beats in both error and cost. Cost is CPU time: on
/// a shared machine wall time also counts the waits for a core, which have nothing to do with
/// the run.
void mark_pareto_front(std::vector<SweepRow>& rows) {
  for (SweepRow& row : rows) {
    if (!row.stable()) continue;
    row.pareto = std::ranges::none_of(rows, [&](const SweepRow& other) {
      return other.stable() && other.max_error <= row.max_error &&
             other.stats.cpu_per_sim_second <= row.stats.cpu_per_sim_second &&
             (other.max_error < row.max_error ||
              other.stats.cpu_per_sim_second < row.stats.cpu_per_sim_second);
    });
  }
}

std::vector<std::string> run_overrides(const nlohmann::json& document, const std::string& name,
                                       double h) {
  std::vector<std::string> out = integrator_overrides(document, name);
  out.push_back(time_step_override(h));
  return out;
}

void write_csv(std::ostream& out, const std::vector<SweepRow>& rows) {
  out.precision(std::numeric_limits<double>::max_digits10);
  out << "integrator,time_step,max_error,rms_error,end_error,cpu_per_sim_second,wall_per_sim_"
         "second,"
         "energy_drift,"
         "max_energy_drift,rescued_steps,unrecoverable_steps,stable,pareto,searched\n";
  for (const SweepRow& r : rows) {
    out << r.integrator << ',' << r.h << ',' << r.max_error << ',' << r.rms_error << ','
        << r.end_error << ',' << r.stats.cpu_per_sim_second << ',' << r.stats.wall_per_sim_second
        << ',' << r.stats.energy_drift << ',' << r.stats.max_energy_drift << ','
        << r.stats.rescued_steps << ',' << r.stats.unrecoverable_steps << ','
        << (r.stable() ? 1 : 0) << ',' << (r.pareto ? 1 : 0) << ',' << (r.searched ? 1 : 0) << '\n';
  }
}

/// An integrator's largest stable run, and its smallest unstable run at a longer step.
struct StableBracket {
  const SweepRow* stable = nullptr;
  const SweepRow* unstable = nullptr;
};

StableBracket stable_bracket(const std::vector<SweepRow>& rows, const std::string& name) {
  StableBracket b;
  for (const SweepRow& r : rows) {
    if (r.integrator == name && r.stable() && (!b.stable || r.h > b.stable->h)) b.stable = &r;
  }
  for (const SweepRow& r : rows) {
    if (r.integrator != name || r.stable() || (b.stable && r.h <= b.stable->h)) continue;
    if (!b.unstable || r.h < b.unstable->h) b.unstable = &r;
  }
  return b;
}

std::string ms(double h) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", 1e3 * h);
  return text;
}

void print_tables(const std::vector<SweepRow>& rows, const SweepOptions& options) {
  std::printf(
      "| integrator | h (ms) | max error (m) | RMS error (m) | error at end (m) | CPU s / sim s "
      "| wall s / sim s "
      "| energy drift (J) | rescued | unrecoverable | Pareto |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|:---:|\n");
  for (const SweepRow& r : rows) {
    std::printf("| %s%s | %.4g | %.3g | %.3g | %.3g | %.3g | %.3g | %+.3g | %llu | %llu | %s |\n",
                r.integrator.c_str(), r.searched ? " (searched)" : "", 1e3 * r.h, r.max_error,
                r.rms_error, r.end_error, r.stats.cpu_per_sim_second, r.stats.wall_per_sim_second,
                r.stats.energy_drift, static_cast<unsigned long long>(r.stats.rescued_steps),
                static_cast<unsigned long long>(r.stats.unrecoverable_steps),
                r.pareto ? "yes" : "");
  }
  std::printf(
      "\n| integrator | largest stable step (ms) | smallest unstable step above it (ms) | runs "
      "searched |\n|---|---:|---:|---:|\n");
  for (const std::string& name : options.integrators) {
    const StableBracket b = stable_bracket(rows, name);
    const auto searched = std::ranges::count_if(
        rows, [&](const SweepRow& r) { return r.integrator == name && r.searched; });
    std::printf("| %s | %s | %s | %td |\n", name.c_str(),
                b.stable ? ms(b.stable->h).c_str() : "none",
                b.unstable ? ms(b.unstable->h).c_str() : "none", searched);
  }
}

nlohmann::json rows_to_json(const std::vector<SweepRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const SweepRow& r : rows) {
    out.push_back({{"integrator", r.integrator},
                   {"time_step", r.h},
                   {"max_error", r.max_error},
                   {"rms_error", r.rms_error},
                   {"end_error", r.end_error},
                   {"stable", r.stable()},
                   {"pareto", r.pareto},
                   {"searched", r.searched},
                   {"run", feltd::to_json(r.stats)}});
  }
  return out;
}

}  // namespace

int sweep(const SweepOptions& options) {
  for (const std::string& name : options.integrators) {
    if (!make_integrator(name)) {
      std::cerr << "feltd: --integrators: no integrator is called " << name << "\n";
      return 2;
    }
  }
  auto document = read_scene_file(options.scene, options.overrides);
  if (!document) {
    std::cerr << "feltd: " << document.error() << "\n";
    return 2;
  }
  const double smallest = std::ranges::min(options.time_steps);
  const double largest = std::ranges::max(options.time_steps);
  const std::vector<std::string> reference_overrides =
      options.reference.empty() ? default_reference(*document, smallest) : options.reference;
  const auto plan = plan_samples(options.duration, largest, options.sample_interval);
  auto reference_scene = plan ? load_scene_variant(*document, reference_overrides, "--reference",
                                                   options.scene, options.scene_dir)
                              : std::unexpected(plan.error());
  if (!reference_scene) {
    std::cerr << "feltd: " << reference_scene.error() << "\n";
    return 2;
  }
  std::fprintf(stderr, "reference (%s) ...\n", nlohmann::json(reference_overrides).dump().c_str());
  SampledRunStats reference_stats;
  const auto reference = run_reference(*reference_scene, *plan, reference_stats);
  if (!reference) {
    std::cerr << "feltd: " << reference.error() << "\n";
    return 2;
  }
  const auto measure = [&](const std::string& name,
                           double h) -> std::expected<SweepRow, std::string> {
    std::fprintf(stderr, "%s at h = %g s ...\n", name.c_str(), h);
    auto scene = load_scene_variant(*document, run_overrides(*document, name, h), "sweep",
                                    options.scene, options.scene_dir);
    auto run = scene ? run_measured(*scene, *reference, *plan) : std::unexpected(scene.error());
    if (!run) return std::unexpected(name + " at h = " + std::to_string(h) + ": " + run.error());
    SweepRow row{name, h, run->stats};
    for (const BodyError& e : run->errors) {
      // NaN wins: a body that went non-finite makes the run's error NaN
      if (!(e.max <= row.max_error)) row.max_error = e.max;
      if (!(e.rms <= row.rms_error)) row.rms_error = e.rms;
      if (!(e.end <= row.end_error)) row.end_error = e.end;
    }
    return row;
  };
  std::vector<SweepRow> rows;
  for (const std::string& name : options.integrators) {
    for (double h : options.time_steps) {
      auto row = measure(name, h);
      if (!row) {
        std::cerr << "feltd: " << row.error() << "\n";
        return 2;
      }
      rows.push_back(std::move(*row));
    }
    // bisection between the largest stable step and the next unstable one, over the steps
    // largest / k (whole k), which the samples' interval stays a multiple of
    for (int search = 0; search < options.search; ++search) {
      const StableBracket b = stable_bracket(rows, name);
      if (!b.stable || !b.unstable) break;
      const double k_stable = std::round(largest / b.stable->h);
      const double k_unstable = std::round(largest / b.unstable->h);
      if (k_stable - k_unstable < 2) break;
      // the geometric mean of the two steps, as a whole divisor
      const double k =
          std::clamp(std::round(std::sqrt(k_stable * k_unstable)), k_unstable + 1, k_stable - 1);
      auto row = measure(name, largest / k);
      if (!row) {
        std::cerr << "feltd: " << row.error() << "\n";
        return 2;
      }
      row->searched = true;
      rows.push_back(std::move(*row));
    }
  }
  mark_pareto_front(rows);
  if (!options.out_dir.empty()) {
    const std::filesystem::path dir = options.out_dir;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    std::ofstream csv(dir / "sweep.csv");
    write_csv(csv, rows);
    csv.close();
    if (ec || !csv) {
      std::cerr << "feltd: cannot write " << (dir / "sweep.csv").string() << "\n";
      return 1;
    }
    char title[256];
    std::snprintf(title, sizeof title, "%s: error against cost, %zu samples to t = %g s",
                  std::filesystem::path(options.scene).filename().c_str(), plan->samples,
                  plan->interval * static_cast<double>(plan->samples));
    std::vector<std::pair<double, double>> front;
    for (const SweepRow& r : rows) {
      if (r.pareto) front.emplace_back(r.stats.cpu_per_sim_second, r.max_error);
    }
    if (auto plotted = plot_sweep(dir / "sweep.csv", dir / "sweep.png", title, options.integrators,
                                  std::move(front));
        !plotted) {
      std::cerr << "feltd: " << plotted.error() << "\n";
      return 1;
    }
  }
  if (options.json) {
    const nlohmann::json out = {{"scene", options.scene},
                                {"overrides", options.overrides},
                                {"reference_overrides", reference_overrides},
                                {"sample_interval", plan->interval},
                                {"samples", plan->samples},
                                {"reference", to_json(reference_stats)},
                                {"runs", rows_to_json(rows)}};
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
  }
  std::printf(
      "Reference: %s, %.3g CPU s per simulated s. Errors: the largest over the bodies, "
      "against the reference at %zu samples every %g s. Stable: no step rescued or "
      "unrecoverable.\n\n",
      nlohmann::json(reference_overrides).dump().c_str(), reference_stats.cpu_per_sim_second,
      plan->samples, plan->interval);
  print_tables(rows, options);
  if (!options.out_dir.empty()) {
    std::printf("\nwrote %s/sweep.csv and %s/sweep.png\n", options.out_dir.c_str(),
                options.out_dir.c_str());
  }
  return 0;
}

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Run a scene with each integrator at each time step against one reference: error "
      "against cost, the Pareto front and the largest stable step");
  add_measure_options(*cmd, options, "rk4 for every body and the smallest time step divided by 16");
  cmd->add_option("--integrators", options.integrators,
                  "Integrators to try, comma-separated (every body that takes one gets it)")
      ->required()
      ->delimiter(',');
  cmd->add_option("--time-steps", options.time_steps, "Time steps to try, s, comma-separated")
      ->required()
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", options.out_dir, "Write sweep.csv and sweep.png (gnuplot) here");
  cmd->add_option("--search", options.search,
                  "Runs per integrator spent bisecting between its largest stable step and the "
                  "next unstable one, over the largest step divided by whole numbers")
      ->check(CLI::Range(0, 20));
  return cmd;
}

}  // namespace felt::feltd
