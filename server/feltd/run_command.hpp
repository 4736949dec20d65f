#pragma once
// `feltd run`: one scene stepped headless for a number of steps, without a network, with its
// statistics printed and optionally written as JSON, scripted devices recorded or replayed, and
// the run traced step by step (runtime/run_trace.hpp).

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace felt::feltd {

struct RunOptions {
  std::string scene;
  std::string scene_dir;
  std::uint64_t steps = 0;
  std::vector<std::string> overrides;
  std::string stats_json;
  std::string record;
  std::string replay;
  std::string trace;         ///< directory of the trace; empty: none
  std::uint64_t every = 10;  ///< steps between the trace's VTK frames
};

/// Adds `run` and its flags to `app`, to be read into `options`; returns the subcommand.
CLI::App* add_run_command(CLI::App& app, RunOptions& options);

/// Runs the scene; returns the exit status (3 when a step could not be rescued).
int run(const RunOptions& options);

}  // namespace felt::feltd
