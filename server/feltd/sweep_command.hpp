#pragma once
// `feltd sweep`: one scene run with every integrator at every time step and measured against
// one reference (by default RK4 at a sixteenth of the smallest step): the trade of error
// against cost, the Pareto front, each integrator's largest stable step, as a table, a CSV and
// a gnuplot PNG.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "feltd/measured_runs.hpp"

namespace felt::feltd {

struct SweepOptions : MeasureOptions {
  std::vector<std::string> integrators;  ///< given to every body that takes one
  std::vector<double> time_steps;        ///< s
  std::string out_dir;                   ///< sweep.csv and sweep.png go here; empty: print only
  /// Runs per integrator spent bisecting between its largest stable swept step and the next
  /// unstable one (0: none)
  int search = 0;
};

/// Adds `sweep` and its flags to `app`, to be read into `options`; returns the subcommand.
CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options);

/// Runs the sweep and prints its tables; returns the exit status.
int sweep(const SweepOptions& options);

}  // namespace felt::feltd
