#pragma once
// A scene file as the batch commands (run, compare, sweep) read it: JSON, with `KEY=VALUE`
// overrides applied, and meshes resolved in --scene-dir or beside the file.

#include <expected>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"

namespace felt::feltd {

/// `file` with `overrides` applied in order; the error is what feltd prints, naming `flag`
/// (the option the overrides came with) and the override that failed.
std::expected<nlohmann::json, std::string> read_scene_file(const std::string& file,
                                                           std::span<const std::string> overrides,
                                                           std::string_view flag = "--set");

/// Loads `document`, read from `file`; meshes resolve in `scene_dir`, or beside `file` when it
/// is empty. The error names the file.
std::expected<Scene, std::string> load_scene_file(const nlohmann::json& document,
                                                  const std::string& file,
                                                  const std::string& scene_dir);

/// Reads `file` with `overrides` (--set) applied and loads it, as read_scene_file and
/// load_scene_file do.
std::expected<Scene, std::string> load_scene_file(const std::string& file,
                                                  std::span<const std::string> overrides,
                                                  const std::string& scene_dir);

/// Loads a copy of `document` with `overrides` (named `flag` in errors) applied.
std::expected<Scene, std::string> load_scene_variant(const nlohmann::json& document,
                                                     std::span<const std::string> overrides,
                                                     std::string_view flag, const std::string& file,
                                                     const std::string& scene_dir);

}  // namespace felt::feltd
