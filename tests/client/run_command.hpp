#pragma once
// Runs a command line to its end and keeps what it wrote, as a shell would: for end-to-end
// tests of the felt command-line tool.

#include <chrono>
#include <string>
#include <vector>

namespace felt::test {

struct CommandResult {
  int status = -1;  ///< the exit status; 128 + the signal when one ended it
  std::string out, err;
};

/// Where the command's standard error goes: a pipe, or a terminal (a pseudo-terminal, whose
/// output is returned all the same) for what a command shows only to a person.
enum class StandardError { kPipe, kTerminal };

/// Runs `argv` (argv[0] a path); kills it after `timeout`.
CommandResult run_command(const std::vector<std::string>& argv,
                          StandardError standard_error = StandardError::kPipe,
                          std::chrono::milliseconds timeout = std::chrono::seconds(30));

}  // namespace felt::test
