#pragma once
// `feltd run`: one scene stepped headless for a number of steps, without a network, with its
// statistics printed and optionally written as JSON, and scripted devices recorded or replayed.

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
};

/// Adds `run` and its flags to `app`, to be read into `options`; returns the subcommand.
CLI::App* add_run_command(CLI::App& app, RunOptions& options);

/// Runs the scene; returns the exit status (3 when a step could not be rescued).
int run(const RunOptions& options);

}  // namespace felt::feltd
