#include "scene/haptics_reader.hpp"

#include <string>

namespace felt::scene_json {
namespace {

constexpr Real kMinServoRate = 250;
constexpr Real kMaxServoRate = 4000;
constexpr std::size_t kMaxDevices = 16;
constexpr std::size_t kMaxSamples = 1'000'000;

std::vector<DeviceSample> read_samples(const ObjectReader& path) {
  const json& list = path.at("samples");
  const std::string where = path.path_of("samples");
  if (!list.is_array() || list.empty()) fail(where, "must be a non-empty array");
  if (list.size() > kMaxSamples) fail(where, "must have at most 1000000 samples");
  std::vector<DeviceSample> samples;
  samples.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ObjectReader sample(list[i], element(where, i), {"t", "position", "buttons"});
    DeviceSample& s = samples.emplace_back();
    s.time = sample.non_negative("t", 0);
    if (i > 0 && !(s.time > samples[i - 1].time)) {
      fail(sample.path_of("t"), "must be later than the sample before");
    }
    s.position = sample.vec3("position", Vec3::Zero());
    s.buttons = sample.count("buttons", 0, 0, 0xffff);
  }
  return samples;
}

DevicePath read_path(const ObjectReader& path) {
  DevicePath out;
  const std::string shape = path.string("shape", "");
  if (shape == "line") {
    out.shape = DevicePath::Shape::kLine;
  } else if (shape == "circle") {
    out.shape = DevicePath::Shape::kCircle;
  } else if (shape == "press") {
    out.shape = DevicePath::Shape::kPress;
  } else if (shape == "samples") {
    out.shape = DevicePath::Shape::kSamples;
    out.samples = read_samples(path);
    return out;
  } else {
    fail(path.path_of("shape"), "must be line, circle, press or samples");
  }
  const bool circle = out.shape == DevicePath::Shape::kCircle;
  out.a = path.vec3(circle ? "center" : "from", Vec3::Zero());
  if (!circle) out.b = path.vec3("to", out.a);
  if (circle) {
    out.axis = path.vec3("axis", out.axis);
    if (out.axis.norm() == 0) fail(path.path_of("axis"), "must not be zero");
    out.radius = path.length("radius", 0.1);
  }
  out.period = path.positive("period", out.period);
  out.buttons = path.count("buttons", 0, 0, 0xffff);
  return out;
}

}  // namespace

void read_haptics(const ObjectReader& haptics, Scene& scene) {
  ProxySettings& p = scene.haptics;
  p.radius = haptics.non_negative("proxy_radius", p.radius);
  p.stiffness = haptics.positive("stiffness", p.stiffness);
  p.damping = haptics.non_negative("damping", p.damping);
  p.max_force = haptics.positive("max_force", p.max_force);
  p.max_force_change = haptics.non_negative("max_force_change", p.max_force_change);
  p.static_friction = haptics.non_negative("static_friction", p.static_friction);
  p.dynamic_friction = haptics.non_negative("dynamic_friction", p.static_friction);
  if (p.dynamic_friction > p.static_friction) {
    fail(haptics.path_of("dynamic_friction"), "must be at most static_friction");
  }
  p.force_shading = haptics.boolean("force_shading", p.force_shading);

  if (haptics.has("structure")) {
    const auto kind = triangle_query_kind(haptics.string("structure", ""));
    if (!kind) {
      fail(haptics.path_of("structure"),
           "must be brute_force, bvh_sphere_2, bvh_sphere_4, bvh_aabb_2, bvh_aabb_4 or "
           "spatial_hash");
    }
    scene.haptic_structure = *kind;
  }
  scene.servo_rate = haptics.positive("servo_rate", scene.servo_rate);
  if (scene.servo_rate < kMinServoRate || scene.servo_rate > kMaxServoRate) {
    fail(haptics.path_of("servo_rate"), "must be between 250 and 4000 Hz");
  }

  if (!haptics.has("devices")) return;
  const json& devices = haptics.at("devices");
  const std::string where = haptics.path_of("devices");
  if (!devices.is_array()) fail(where, "must be an array");
  if (devices.size() > kMaxDevices) fail(where, "must have at most 16 devices");
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const ObjectReader device(devices[i], element(where, i), {"name", "path"});
    if (!device.has("path")) fail(device.path_of("path"), "is required");
    const ObjectReader path(
        device.at("path"), device.path_of("path"),
        {"shape", "from", "to", "center", "axis", "radius", "period", "buttons", "samples"});
    scene.devices.push_back({device.name("name", "device " + std::to_string(i)), read_path(path)});
  }
}

}  // namespace felt::scene_json
