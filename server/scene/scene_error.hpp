#pragma once

#include <string>

namespace felt {

/// Why a scene did not load: where (a JSON path, empty for the whole document) and what.
struct SceneError {
  std::string path;
  std::string message;

  std::string what() const { return path.empty() ? message : path + ": " + message; }
};

}  // namespace felt
