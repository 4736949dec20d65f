#include "net/page_files.hpp"

#include <array>
#include <utility>

#include "scene/scene_directory.hpp"

namespace felt::net {

namespace {

std::string_view content_type(const std::filesystem::path& file) {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 9> kTypes{{
      {".html", "text/html; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"},
      {".css", "text/css; charset=utf-8"},
      {".map", "application/json"},
      {".json", "application/json"},
      {".png", "image/png"},
      {".svg", "image/svg+xml"},
      {".ico", "image/x-icon"},
      {".wasm", "application/wasm"},
  }};
  const std::string extension = file.extension().string();
  for (const auto& [suffix, type] : kTypes) {
    if (extension == suffix) return type;
  }
  return "application/octet-stream";
}

}  // namespace

std::optional<PageFile> page_file(const std::filesystem::path& root, std::string_view target) {
  target = target.substr(0, target.find_first_of("?#"));
  if (!target.starts_with('/')) return std::nullopt;
  target.remove_prefix(1);
  if (target.empty()) target = "index.html";
  // the same rules as the files clients name in scenes: no "." or ".." part, nothing outside
  auto file = resolve_inside(root, target);
  if (!file) return std::nullopt;
  return PageFile{*file, content_type(*file)};
}

}  // namespace felt::net
