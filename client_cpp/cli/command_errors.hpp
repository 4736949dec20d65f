#pragma once
// What a command throws when felt itself, not the server, finds a fault: the server's refusals
// are client::ClientError and carry its error code; these carry none.

#include <stdexcept>

namespace felt::cli {

/// The command line asks for something felt cannot do (a value out of range, a file that cannot
/// be read or is not what the command takes): felt exits with status 2, as for a parse error.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// felt failed on this machine (a file it cannot write, a socket or process it cannot make):
/// felt exits with status 1.
class LocalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace felt::cli
