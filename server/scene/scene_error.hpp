#pragma once

#include <cstdint>
#include <string>

namespace felt {

/// A limit a scene is held to, when going past it (not a mistake in the scene) is why
/// something failed; the server names the setting that sets it.
enum class SceneLimit : std::uint8_t { kNone, kBodies, kParticles };

/// Why a scene did not load: where (a JSON path, empty for the whole document) and what.
struct SceneError {
  std::string path;
  std::string message;
  SceneLimit exceeded = SceneLimit::kNone;

  std::string what() const { return path.empty() ? message : path + ": " + message; }
};

}  // namespace felt
