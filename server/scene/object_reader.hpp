#pragma once
// Reading scene JSON with errors that name the path of the bad value
// ("bodies[2].springs.shear.stiffness: must be > 0"), shared by the readers of each kind of
// body. Used inside the scene loader only: a Failure thrown here becomes its SceneError.

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/geometry/triangle_mesh.hpp"
#include "core/math/bounds.hpp"
#include "scene/scene_error.hpp"

namespace felt::scene_json {

using nlohmann::json;

// Thrown inside the loader only; load_scene turns it into a SceneError.
struct Failure {
  SceneError error;
};

[[noreturn]] void fail(const std::string& path, std::string message);

std::string child(const std::string& path, std::string_view key);

std::string element(const std::string& path, std::size_t index);

/// A JSON object being read, with its path for error messages.
class ObjectReader {
 public:
  ObjectReader(const json& value, std::string path, std::initializer_list<std::string_view> keys)
      : value_(value), path_(std::move(path)) {
    if (!value_.is_object()) fail(path_, "must be an object");
    for (const auto& [key, unused] : value_.items()) {
      // a key is named in the message, which goes to a client: not one of any length
      if (key.size() > kMaxNameBytes) fail(path_, "has an unknown key of over 100 bytes");
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
        fail(child(path_, key), "unknown key");
      }
    }
  }

  const std::string& path() const { return path_; }
  bool has(std::string_view key) const { return value_.contains(key); }
  /// The value of `key`, which the scene must give.
  const json& at(std::string_view key) const {
    const auto it = value_.find(key);
    if (it == value_.end()) fail(path_of(key), "is required");
    return *it;
  }
  std::string path_of(std::string_view key) const { return child(path_, key); }

  Real number(std::string_view key, Real fallback) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    if (!v.is_number()) fail(path_of(key), "must be a number");
    const Real x = v.get<Real>();
    if (!std::isfinite(x)) fail(path_of(key), "must be finite");
    return x;
  }

  Real positive(std::string_view key, Real fallback) const {
    const Real x = number(key, fallback);
    if (!(x > 0)) fail(path_of(key), "must be > 0");
    return x;
  }

  /// A number within [min, max] (the message gives both, in `unit`).
  Real ranged(std::string_view key, Real fallback, Real min, Real max,
              std::string_view unit = "") const {
    const Real x = number(key, fallback);
    if (!(x >= min && x <= max)) fail(path_of(key), between(min, max, unit));
    return x;
  }
  /// "must be between 1e-06 and 1000000 m"
  static std::string between(Real min, Real max, std::string_view unit);

  Real non_negative(std::string_view key, Real fallback) const {
    const Real x = number(key, fallback);
    if (x < 0) fail(path_of(key), "must be >= 0");
    return x;
  }

  std::uint32_t count(std::string_view key, std::uint32_t fallback, std::uint32_t min,
                      std::uint32_t max) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    if (!v.is_number_integer()) fail(path_of(key), "must be an integer");
    const auto n = v.get<std::int64_t>();
    if (n < min || n > max) {
      fail(path_of(key), "must be between " + std::to_string(min) + " and " + std::to_string(max));
    }
    return static_cast<std::uint32_t>(n);
  }

  bool boolean(std::string_view key, bool fallback) const {
    if (!has(key)) return fallback;
    if (!at(key).is_boolean()) fail(path_of(key), "must be true or false");
    return at(key).get<bool>();
  }

  /// A string of at most kMaxStringBytes: a file, a type, a model.
  std::string string(std::string_view key, std::string fallback) const {
    return bounded_string(key, std::move(fallback), kMaxStringBytes);
  }
  /// A name of at most kMaxNameBytes: the scene's, a body's, a device's, which every client's
  /// ListScenes, SceneLoaded and events repeat.
  std::string name(std::string_view key, std::string fallback) const {
    return bounded_string(key, std::move(fallback), kMaxNameBytes);
  }
  static constexpr std::size_t kMaxNameBytes = 100;
  static constexpr std::size_t kMaxStringBytes = 1024;

  /// Three numbers within ±kMaxVectorComponent (core/math/bounds.hpp): a point, a size, a
  /// direction, a scale.
  Vec3 vec3(std::string_view key, const Vec3& fallback) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    if (!v.is_array() || v.size() != 3) fail(path_of(key), "must be an array of 3 numbers");
    Vec3 out;
    for (int i = 0; i < 3; ++i) {
      if (!v[i].is_number() || !(std::abs(v[i].get<Real>()) <= kMaxVectorComponent)) {
        fail(element(path_of(key), i), "must be a number between -1e6 and 1e6");
      }
      out[i] = v[i].get<Real>();
    }
    return out;
  }
  /// A length in metres, within [kMinLength, kMaxLength]: a size, a radius.
  Real length(std::string_view key, Real fallback) const {
    const Real x = number(key, fallback);
    if (!(x >= kMinLength && x <= kMaxLength)) fail(path_of(key), "must be between 1e-6 and 1e6 m");
    return x;
  }
  /// Three lengths (a box's size) or three scale factors, each within [kMinLength, kMaxLength].
  Vec3 extent(std::string_view key, const Vec3& fallback) const {
    const Vec3 v = vec3(key, fallback);
    if ((v.array() < kMinLength).any()) fail(path_of(key), "must be at least 1e-6 in each axis");
    return v;
  }
  /// Geometry below a micrometre is degenerate to the core: a lattice 1e-300 m thick had springs
  /// whose squared lengths underflowed to 0 and failed an invariant of the server.
  static constexpr Real kMinLength = 1e-6;
  static constexpr Real kMaxLength = 1e6;

 private:
  std::string bounded_string(std::string_view key, std::string fallback,
                             std::size_t max_bytes) const {
    if (!has(key)) return fallback;
    if (!at(key).is_string()) fail(path_of(key), "must be a string");
    const auto& text = at(key).get_ref<const std::string&>();
    if (text.size() > max_bytes) {
      fail(path_of(key), "must be at most " + std::to_string(max_bytes) + " bytes");
    }
    return text;
  }

  const json& value_;
  std::string path_;
};

/// "transform": {"rotate": [deg x, y, z], "scale": s or [x, y, z], "translate": [x, y, z]}
Transform read_transform(const ObjectReader& reader);

/// Counts `particles` against what the scene's particle limit has left.
void take_particles(const std::string& path, std::size_t particles, std::size_t& particles_left);

/// The file named by `key` of `reader`, inside `asset_root` and never outside it.
std::filesystem::path asset_file(const ObjectReader& reader, std::string_view key,
                                 const std::filesystem::path& asset_root);

}  // namespace felt::scene_json
