// feltd: the Felt daemon (`serve`), the headless batch runner (`run`) and the measurements of a
// scene's speed/accuracy trade (`compare`, `sweep`).

#include <CLI/CLI.hpp>

#include "command_line/usage_status.hpp"
#include "feltd/compare_command.hpp"
#include "feltd/run_command.hpp"
#include "feltd/serve_command.hpp"
#include "feltd/sweep_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"feltd " FELT_VERSION " - simulation service for touching deformable things"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "feltd " FELT_VERSION);
  felt::feltd::ServeOptions serve_options;
  const CLI::App* serve_command = felt::feltd::add_serve_command(app, serve_options);
  felt::feltd::RunOptions run_options;
  const CLI::App* run_command = felt::feltd::add_run_command(app, run_options);
  felt::feltd::CompareOptions compare_options;
  const CLI::App* compare_command = felt::feltd::add_compare_command(app, compare_options);
  felt::feltd::SweepOptions sweep_options;
  felt::feltd::add_sweep_command(app, sweep_options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return felt::usage_status(app, e);
  }
  if (serve_command->parsed()) return felt::feltd::serve(serve_options);
  if (run_command->parsed()) return felt::feltd::run(run_options);
  if (compare_command->parsed()) return felt::feltd::compare(compare_options);
  return felt::feltd::sweep(sweep_options);
}
