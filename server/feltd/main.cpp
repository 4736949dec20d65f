// feltd: the Felt daemon (`serve`) and the headless batch runner (`run`).

#include <CLI/CLI.hpp>

#include "command_line/usage_status.hpp"
#include "feltd/run_command.hpp"
#include "feltd/serve_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"feltd " FELT_VERSION " - simulation service for touching deformable things"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "feltd " FELT_VERSION);
  felt::feltd::ServeOptions serve_options;
  const CLI::App* serve_command = felt::feltd::add_serve_command(app, serve_options);
  felt::feltd::RunOptions run_options;
  felt::feltd::add_run_command(app, run_options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return felt::usage_status(app, e);
  }
  if (serve_command->parsed()) return felt::feltd::serve(serve_options);
  return felt::feltd::run(run_options);
}
