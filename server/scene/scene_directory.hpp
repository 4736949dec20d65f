#pragma once
// Maps scene names from clients to files, never outside the scene directory.

#include <expected>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace felt {

/// The regular file `relative` ("meshes/bunny.obj") inside `root`: relative, made of letters,
/// digits, '_', '-', '.' and '/', no "." or ".." part, and not leading (through links) outside
/// `root`. Errors are fit for a client: they name `relative`, never the server's paths.
std::expected<std::filesystem::path, std::string> resolve_inside(const std::filesystem::path& root,
                                                                 std::string_view relative);

class SceneDirectory {
 public:
  explicit SceneDirectory(std::filesystem::path root);

  /// The file of scene `name` ("default" -> ROOT/default.json, "thesis/three_cubes" ->
  /// ROOT/thesis/three_cubes.json). Names are letters, digits, '_', '-' and '/' between
  /// segments; anything else, or a file that resolves (through links) outside the root, is an
  /// error with a message fit for the client.
  std::expected<std::filesystem::path, std::string> resolve(std::string_view name) const;

  /// The names resolve() takes for the scene files in the directory, sorted (at most
  /// kMaxListed; empty when the directory is not available).
  std::vector<std::string> list() const;

  const std::filesystem::path& root() const { return root_; }

  static constexpr std::size_t kMaxListed = 1000;

 private:
  std::filesystem::path root_;
};

}  // namespace felt
