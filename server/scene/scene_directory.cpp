#include "scene/scene_directory.hpp"

#include <algorithm>

namespace felt {
namespace {

constexpr std::size_t kMaxNameLength = 200;

bool valid_segment_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

bool valid_name(std::string_view name) {
  if (name.empty() || name.size() > kMaxNameLength) return false;
  if (name.front() == '/' || name.back() == '/') return false;
  if (name.find("//") != std::string_view::npos) return false;
  return std::all_of(name.begin(), name.end(),
                     [](char c) { return c == '/' || valid_segment_char(c); });
}

}  // namespace

SceneDirectory::SceneDirectory(std::filesystem::path root) : root_(std::move(root)) {}

std::expected<std::filesystem::path, std::string> SceneDirectory::resolve(
    std::string_view name) const {
  namespace fs = std::filesystem;
  if (!valid_name(name)) {
    return std::unexpected("bad scene name \"" + std::string(name.substr(0, kMaxNameLength)) +
                           "\": use letters, digits, '_', '-' and '/' between parts");
  }
  std::error_code ec;
  const fs::path root = fs::canonical(root_, ec);
  if (ec) return std::unexpected("the scene directory is not available");
  const fs::path file = fs::weakly_canonical(root / (std::string(name) + ".json"), ec);
  if (ec) return std::unexpected("no scene \"" + std::string(name) + "\"");
  // a symbolic link inside the directory must not lead out of it
  const auto [root_end, unused] = std::mismatch(root.begin(), root.end(), file.begin(), file.end());
  if (root_end != root.end()) return std::unexpected("no scene \"" + std::string(name) + "\"");
  if (!fs::is_regular_file(file, ec))
    return std::unexpected("no scene \"" + std::string(name) + "\"");
  return file;
}

}  // namespace felt
