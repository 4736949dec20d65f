#pragma once
// `feltd compare`: a scene run as given and a reference run of it (by default RK4 at a
// sixteenth of the step), sampled at the same times: each body's RMS and largest position
// error, both runs' energy drift and wall seconds per simulated second.

#include <CLI/CLI.hpp>

#include "feltd/measured_runs.hpp"

namespace felt::feltd {

struct CompareOptions : MeasureOptions {};

/// Adds `compare` and its flags to `app`, to be read into `options`; returns the subcommand.
CLI::App* add_compare_command(CLI::App& app, CompareOptions& options);

/// Runs both and prints the comparison; returns the exit status.
int compare(const CompareOptions& options);

}  // namespace felt::feltd
