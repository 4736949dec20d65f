#include "feltd/scene_file.hpp"

#include <filesystem>

#include "feltd/scene_options.hpp"
#include "scene/scene_loader.hpp"
#include "scene/scene_overrides.hpp"

namespace felt::feltd {
namespace {

std::expected<void, std::string> apply_overrides(nlohmann::json& document,
                                                 std::span<const std::string> overrides,
                                                 std::string_view flag) {
  for (const std::string& assignment : overrides) {
    if (auto applied = felt::apply_override(document, assignment); !applied) {
      return std::unexpected(std::string(flag) + " " + assignment + ": " + applied.error());
    }
  }
  return {};
}

}  // namespace

std::expected<nlohmann::json, std::string> read_scene_file(const std::string& file,
                                                           std::span<const std::string> overrides,
                                                           std::string_view flag) {
  auto document = felt::read_scene_json(file);
  if (!document) return std::unexpected(document.error().what());
  if (auto applied = apply_overrides(*document, overrides, flag); !applied) {
    return std::unexpected(applied.error());
  }
  return std::move(*document);
}

std::expected<Scene, std::string> load_scene_file(const nlohmann::json& document,
                                                  const std::string& file,
                                                  const std::string& scene_dir) {
  // without --scene-dir, meshes are looked up beside the scene file
  const std::filesystem::path beside = std::filesystem::path(file).parent_path();
  auto scene =
      felt::load_scene(document, scene_options(!scene_dir.empty() ? std::filesystem::path(scene_dir)
                                               : beside.empty()   ? std::filesystem::path(".")
                                                                  : beside));
  if (!scene) return std::unexpected(file + ": " + scene.error().what());
  return std::move(*scene);
}

std::expected<Scene, std::string> load_scene_file(const std::string& file,
                                                  std::span<const std::string> overrides,
                                                  const std::string& scene_dir) {
  auto document = read_scene_file(file, overrides);
  if (!document) return std::unexpected(document.error());
  return load_scene_file(*document, file, scene_dir);
}

std::expected<Scene, std::string> load_scene_variant(const nlohmann::json& document,
                                                     std::span<const std::string> overrides,
                                                     std::string_view flag, const std::string& file,
                                                     const std::string& scene_dir) {
  nlohmann::json variant = document;
  if (auto applied = apply_overrides(variant, overrides, flag); !applied) {
    return std::unexpected(applied.error());
  }
  return load_scene_file(variant, file, scene_dir);
}

}  // namespace felt::feltd
