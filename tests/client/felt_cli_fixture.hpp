#pragma once
// The built felt binary against the real feltd on port 0 serving the default scene (a 20 x 20
// curtain), with a scratch directory for the files it writes.

#include <regex>
#include <string>
#include <vector>

#include "protocol/feltd_fixture.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace felt::test {

class FeltCliTest : public FeltdTest {
 protected:
  /// `felt --server <this feltd> ARGS...`, run to its end.
  CommandResult felt(const std::vector<std::string>& args,
                     StandardError standard_error = StandardError::kPipe) {
    std::vector<std::string> argv = {FELT_PATH, "--server",
                                     "127.0.0.1:" + std::to_string(server_->port())};
    argv.insert(argv.end(), args.begin(), args.end());
    return run_command(argv, standard_error);
  }

  ScratchDirectory dir_;
};

/// The numbers `pattern`'s groups capture in `text` (empty when it does not match).
inline std::vector<double> numbers_in(const std::string& text, const std::string& pattern) {
  std::smatch match;
  if (!std::regex_search(text, match, std::regex(pattern))) return {};
  std::vector<double> out;
  for (std::size_t g = 1; g < match.size(); ++g) out.push_back(std::stod(match[g]));
  return out;
}

}  // namespace felt::test
