#include "cli/csv_path.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>

#include "cli/command_errors.hpp"

namespace felt::cli {

DevicePath read_csv_path(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw UsageError("cannot read " + file);
  const auto fault = [&](int number, const std::string& why) {
    return UsageError(file + ":" + std::to_string(number) + ": " + why);
  };
  DevicePath path;
  path.shape = DevicePath::Shape::kSamples;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#' ||
        line.starts_with("time")) {
      continue;
    }
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    DeviceSample s;
    std::string buttons, rest;
    if (!(fields >> s.time >> s.position.x() >> s.position.y() >> s.position.z())) {
      throw fault(number, "expected time, x, y, z[, buttons]");
    }
    // buttons as digits only: a stream would take "-1" as 4294967295 and "x" as 0
    if (fields >> buttons) {
      const char* end = buttons.data() + buttons.size();
      const auto [stop, error] = std::from_chars(buttons.data(), end, s.buttons);
      if (error != std::errc() || stop != end) {
        throw fault(number, "buttons must be a whole number, not \"" + buttons + "\"");
      }
    }
    if (fields >> rest) throw fault(number, "more than time, x, y, z and buttons");
    if (!path.samples.empty() && s.time <= path.samples.back().time) {
      throw fault(number, "times must increase");
    }
    path.samples.push_back(s);
  }
  if (path.samples.empty()) throw UsageError(file + ": no samples");
  return path;
}

}  // namespace felt::cli
