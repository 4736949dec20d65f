#pragma once
// How feltd and felt end on a command line they cannot take: the parser's message and status 2,
// the one status both programs use for every usage error; --help and --version end with 0.

#include <CLI/CLI.hpp>

namespace felt {

inline constexpr int kUsageStatus = 2;

/// Prints what `error` says (help and the version to standard output, the rest to standard
/// error) and returns the process's exit status.
inline int usage_status(const CLI::App& app, const CLI::ParseError& error) {
  return app.exit(error) == 0 ? 0 : kUsageStatus;
}

}  // namespace felt
