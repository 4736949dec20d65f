#include "scene/scene_directory.hpp"

#include <algorithm>

namespace felt {
namespace {

constexpr std::size_t kMaxNameLength = 200;

bool valid_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.' || c == '/';
}

bool valid_relative_path(std::string_view path) {
  if (path.empty() || path.size() > kMaxNameLength) return false;
  if (!std::all_of(path.begin(), path.end(), valid_char)) return false;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = path.find('/', start);
    const std::string_view part = path.substr(start, slash - start);
    if (part.empty() || part == "." || part == "..") return false;
    if (slash == std::string_view::npos) return true;
    start = slash + 1;
  }
}

}  // namespace

std::expected<std::filesystem::path, std::string> resolve_inside(const std::filesystem::path& root,
                                                                 std::string_view relative) {
  namespace fs = std::filesystem;
  const std::string shown(relative.substr(0, kMaxNameLength));
  if (!valid_relative_path(relative)) {
    return std::unexpected("bad name \"" + shown +
                           "\": use letters, digits, '_', '-', '.' and '/' between parts");
  }
  std::error_code ec;
  const fs::path canonical_root = fs::canonical(root, ec);
  if (ec) return std::unexpected("the scene directory is not available");
  const fs::path file = fs::weakly_canonical(canonical_root / relative, ec);
  // a symbolic link inside the directory must not lead out of it
  const auto [root_end, unused] =
      std::mismatch(canonical_root.begin(), canonical_root.end(), file.begin(), file.end());
  if (ec || root_end != canonical_root.end() || !fs::is_regular_file(file, ec)) {
    return std::unexpected("no file \"" + shown + "\"");
  }
  return file;
}

SceneDirectory::SceneDirectory(std::filesystem::path root) : root_(std::move(root)) {}

std::expected<std::filesystem::path, std::string> SceneDirectory::resolve(
    std::string_view name) const {
  // scene names carry no extension: "thesis/three_cubes" is thesis/three_cubes.json
  if (name.find('.') != std::string_view::npos) {
    return std::unexpected("bad scene name \"" + std::string(name.substr(0, kMaxNameLength)) +
                           "\": use letters, digits, '_', '-' and '/' between parts");
  }
  auto file = resolve_inside(root_, std::string(name) + ".json");
  if (!file && file.error().starts_with("no file")) {
    return std::unexpected("no scene \"" + std::string(name) + "\"");
  }
  return file;
}

std::vector<std::string> SceneDirectory::list() const {
  namespace fs = std::filesystem;
  std::vector<std::string> names;
  std::error_code ec;
  fs::recursive_directory_iterator it(root_, fs::directory_options::skip_permission_denied, ec);
  for (; !ec && it != fs::recursive_directory_iterator() && names.size() < kMaxListed;
       it.increment(ec)) {
    if (it.depth() > 8) it.disable_recursion_pending();
    if (it->path().extension() != ".json") continue;
    std::string name = it->path().lexically_relative(root_).replace_extension().generic_string();
    // only what a client could name: the same checks as resolve()
    if (resolve(name)) names.push_back(std::move(name));
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace felt
