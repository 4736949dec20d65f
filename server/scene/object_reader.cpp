#include "scene/object_reader.hpp"

#include <sstream>

#include "scene/scene_directory.hpp"

namespace felt::scene_json {

[[noreturn]] void fail(const std::string& path, std::string message) {
  throw Failure{{path, std::move(message)}};
}

std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string ObjectReader::between(Real min, Real max, std::string_view unit) {
  std::ostringstream text;
  text << "must be between " << min << " and " << max << (unit.empty() ? "" : " ") << unit;
  return text.str();
}

std::string element(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

Transform read_transform(const ObjectReader& reader) {
  Transform transform;
  if (!reader.has("transform")) return transform;
  const ObjectReader t(reader.at("transform"), reader.path_of("transform"),
                       {"rotate", "scale", "translate"});
  transform.rotate_degrees = t.vec3("rotate", transform.rotate_degrees);
  if (t.has("scale") && t.at("scale").is_number()) {
    transform.scale = Vec3::Constant(t.length("scale", 1));
  } else {
    transform.scale = t.extent("scale", transform.scale);
  }
  transform.translate = t.vec3("translate", transform.translate);
  return transform;
}

void take_particles(const std::string& path, std::size_t particles, std::size_t& particles_left) {
  if (particles > particles_left) {
    throw Failure{{path,
                   std::to_string(particles) + " particles exceed the " +
                       std::to_string(particles_left) + " the scene's particle limit leaves",
                   SceneLimit::kParticles}};
  }
  particles_left -= particles;
}

std::filesystem::path asset_file(const ObjectReader& reader, std::string_view key,
                                 const std::filesystem::path& asset_root) {
  if (!reader.has(key)) fail(reader.path_of(key), "is required");
  if (asset_root.empty()) {
    fail(reader.path_of(key), "files can only be loaded by scenes in the scene directory");
  }
  const auto file = resolve_inside(asset_root, reader.string(key, ""));
  if (!file) fail(reader.path_of(key), file.error());
  return *file;
}

}  // namespace felt::scene_json
