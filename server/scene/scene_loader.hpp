#pragma once
// Scene JSON -> core objects (docs/scenes.md). Every mistake is reported with the JSON
// path of the bad value: "bodies[2].springs.shear.stiffness: must be > 0".

#include <expected>
#include <filesystem>
#include <string>
#include <string_view>
#include <variant>

#include <nlohmann/json_fwd.hpp>

#include "scene/scene.hpp"
#include "scene/scene_error.hpp"

namespace felt {

/// What a scene may ask for and where its files come from.
struct SceneLoadOptions {
  /// checked before memory is allocated for a body
  std::size_t max_particles = 4'000'000;
  /// Meshes ("mesh": {"file": ...}) resolve inside this directory and never outside it; empty:
  /// the scene may not load files (inline scenes from clients).
  std::filesystem::path asset_root;
};

/// A body of a scene file's "bodies" array, built.
using SceneBody = std::variant<ClothBody, SolidBody>;

std::expected<Scene, SceneError> load_scene(const nlohmann::json& document,
                                            const SceneLoadOptions& options = {});
std::expected<Scene, SceneError> load_scene_text(std::string_view text,
                                                 const SceneLoadOptions& options = {});
std::expected<Scene, SceneError> load_scene_file(const std::filesystem::path& file,
                                                 const SceneLoadOptions& options = {});

/// One entry of a scene's "bodies" array (a body added at run time), read as the scene loader
/// reads it: `path` names it in errors, `index` numbers its default name, `time_step` and
/// `health` are the scene's (a cloth's stable step is checked against them); options.max_particles
/// bounds this body alone.
std::expected<SceneBody, SceneError> load_body(const nlohmann::json& entry, const std::string& path,
                                               std::size_t index, Real time_step,
                                               const SceneLoadOptions& options,
                                               const HealthSettings& health = {});
/// One entry of a scene's "colliders" array.
std::expected<Collider, SceneError> load_collider(const nlohmann::json& entry,
                                                  const std::string& path);

/// Arrays and objects nested deeper than this are refused.
inline constexpr int kMaxJsonDepth = 32;

/// Parses JSON text; `source` names it in the error.
std::expected<nlohmann::json, SceneError> parse_json(std::string_view text,
                                                     const std::string& source);

/// Reads a scene file as JSON without building it (for --set overrides before loading). A
/// ".cfg" file is in the second thesis's own format (scene/thesis_scene_reader.hpp).
std::expected<nlohmann::json, SceneError> read_scene_json(const std::filesystem::path& file);

}  // namespace felt
