#include "scene/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/cloth/cloth_grid.hpp"
#include "core/cloth/mesh_cloth.hpp"
#include "core/integrate/xpbd_integrator.hpp"
#include "scene/body_step_reader.hpp"
#include "scene/cloth_integrator_reader.hpp"
#include "scene/haptics_reader.hpp"
#include "scene/health_reader.hpp"
#include "scene/obj_reader.hpp"
#include "scene/object_reader.hpp"
#include "scene/solid_reader.hpp"
#include "scene/thesis_scene_reader.hpp"

namespace felt {
namespace {

using namespace scene_json;

// Particles per body are capped so that a typo cannot ask for terabytes.
constexpr std::uint32_t kMaxGridSide = 2048;
// A cloth's mass, kg, and its springs' constants: wide enough for a silk scarf and a tarpaulin
// of lead, narrow enough that m, k and c stay where their products and quotients are finite.
constexpr Real kMinMass = 1e-6, kMaxMass = 1e6;
constexpr Real kMinStiffness = 1e-6, kMaxStiffness = 1e9;  // N/m
constexpr Real kMaxDamping = 1e6;                          // N·s/m

GridClothSpec read_grid(const ObjectReader& reader) {
  const ObjectReader grid(reader.at("grid"), reader.path_of("grid"),
                          {"width", "height", "nx", "ny", "center", "plane", "transform"});
  GridClothSpec spec;
  spec.width = grid.length("width", 1);
  spec.height = grid.length("height", 1);
  spec.nx = grid.count("nx", 20, 2, kMaxGridSide);
  spec.ny = grid.count("ny", 20, 2, kMaxGridSide);
  spec.center = grid.vec3("center", Vec3::Zero());
  const std::string plane = grid.string("plane", "xy");
  if (plane == "xy") {
    spec.plane = GridClothSpec::Plane::kXY;
  } else if (plane == "xz") {
    spec.plane = GridClothSpec::Plane::kXZ;
  } else {
    fail(grid.path_of("plane"), "must be \"xy\" (hanging) or \"xz\" (lying)");
  }
  spec.transform = read_transform(grid);
  return spec;
}

ClothParams read_springs(const ObjectReader& body) {
  // defaults give a light cloth that is stable with symplectic Euler at h = 1 ms
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 200, 0.05};
  params.spring(SpringKind::kShear) = {true, 50, 0.02};
  params.spring(SpringKind::kBend) = {true, 5, 0.005};
  params.drag = body.ranged("drag", 0.005, 0, kMaxDamping, "N·s/m");
  params.thickness = body.non_negative("thickness", params.thickness);
  params.self_collision = body.boolean("self_collision", params.self_collision);
  if (params.self_collision && params.thickness == 0) {
    fail(body.path_of("thickness"), "must be > 0 when self_collision is on");
  }
  if (body.has("wind")) {
    const ObjectReader wind(body.at("wind"), body.path_of("wind"),
                            {"velocity", "drag_coefficient", "gust_amplitude", "gust_period"});
    Wind& w = params.wind;
    w.enabled = true;
    w.velocity = wind.vec3("velocity", w.velocity);
    w.drag_coefficient = wind.non_negative("drag_coefficient", w.drag_coefficient);
    w.gust_amplitude = wind.non_negative("gust_amplitude", w.gust_amplitude);
    w.gust_period = wind.positive("gust_period", w.gust_period);
  }
  if (body.has("stretch_limit")) {
    const ObjectReader limit(
        body.at("stretch_limit"), body.path_of("stretch_limit"),
        {"enabled", "max_strain", "max_compression", "iterations", "projection_iterations",
         "position_correction", "velocity_correction"});
    StretchLimit& stretch = params.stretch;
    stretch.enabled = limit.boolean("enabled", true);
    stretch.max_strain = limit.positive("max_strain", stretch.max_strain);
    if (limit.has("max_compression")) {
      stretch.max_compression = limit.non_negative("max_compression", 0);
      if (stretch.max_compression >= 1) fail(limit.path_of("max_compression"), "must be < 1");
    }
    stretch.iterations = static_cast<int>(limit.count("iterations", stretch.iterations, 1, 1000));
    stretch.projection_iterations = static_cast<int>(
        limit.count("projection_iterations", stretch.projection_iterations, 0, 100));
    stretch.position_correction = limit.boolean("position_correction", stretch.position_correction);
    stretch.velocity_correction = limit.boolean("velocity_correction", stretch.velocity_correction);
  }
  if (!body.has("springs")) return params;

  const ObjectReader springs(body.at("springs"), body.path_of("springs"),
                             {"structural", "shear", "bend"});
  const std::pair<std::string_view, SpringKind> kinds[] = {{"structural", SpringKind::kStructural},
                                                           {"shear", SpringKind::kShear},
                                                           {"bend", SpringKind::kBend}};
  for (const auto& [key, kind] : kinds) {
    if (!springs.has(key)) continue;
    const ObjectReader spring(springs.at(key), springs.path_of(key),
                              {"stiffness", "damping", "enabled"});
    SpringParams& sp = params.spring(kind);
    sp.stiffness = spring.ranged("stiffness", sp.stiffness, kMinStiffness, kMaxStiffness, "N/m");
    sp.damping = spring.ranged("damping", sp.damping, 0, kMaxDamping, "N·s/m");
    sp.enabled = spring.boolean("enabled", sp.enabled);
  }
  return params;
}

/// Pins of a body with `n` particles; presets need the grid they refer to.
std::vector<std::uint32_t> read_pins(const ObjectReader& body, const GridClothSpec* grid,
                                     std::size_t n) {
  if (!body.has("pin")) {
    return grid ? grid_pin_indices(*grid, GridPinPreset::kTopCorners)
                : std::vector<std::uint32_t>{};
  }
  const json& pin = body.at("pin");
  const std::string path = body.path_of("pin");
  if (pin.is_string() && pin.get<std::string>() == "none") return {};
  if (pin.is_string() && !grid)
    fail(path, "a mesh cloth takes \"none\" or a list of particle indices");
  if (pin.is_string()) {
    const GridClothSpec& spec = *grid;
    const std::pair<std::string_view, GridPinPreset> presets[] = {
        {"none", GridPinPreset::kNone},
        {"four_corners", GridPinPreset::kFourCorners},
        {"top_corners", GridPinPreset::kTopCorners},
        {"top_row", GridPinPreset::kTopRow}};
    for (const auto& [name, preset] : presets) {
      if (pin.get<std::string>() == name) return grid_pin_indices(spec, preset);
    }
    fail(path, "must be none, four_corners, top_corners, top_row or a list of particle indices");
  }
  if (!pin.is_array()) fail(path, "must be a preset name or a list of particle indices");
  std::vector<std::uint32_t> indices;
  for (std::size_t i = 0; i < pin.size(); ++i) {
    if (!pin[i].is_number_integer() || pin[i].get<std::int64_t>() < 0 ||
        pin[i].get<std::uint64_t>() >= n) {
      fail(element(path, i), "must be a particle index below " + std::to_string(n));
    }
    indices.push_back(pin[i].get<std::uint32_t>());
  }
  return indices;
}

/// "constraints": [{"type": "plane" | "line", "particles": [...], "normal" | "direction": [...]}]
/// through each particle's start position.
void read_constraints(const ObjectReader& body, ClothBody& cloth) {
  if (!body.has("constraints")) return;
  const json& list = body.at("constraints");
  if (!list.is_array()) fail(body.path_of("constraints"), "must be an array");
  const std::size_t n = cloth.model().particle_count();
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ObjectReader c(list[i], element(body.path_of("constraints"), i),
                         {"type", "particles", "normal", "direction"});
    const std::string type = c.string("type", "");
    if (type != "plane" && type != "line") fail(c.path_of("type"), "must be plane or line");
    const bool plane = type == "plane";
    const char* axis_key = plane ? "normal" : "direction";
    const Vec3 axis = c.vec3(axis_key, Vec3::Zero());
    if (axis.norm() == 0) fail(c.path_of(axis_key), "is required and must not be zero");
    if (!c.has("particles") || !c.at("particles").is_array()) {
      fail(c.path_of("particles"), "must be a list of particle indices");
    }
    const json& particles = c.at("particles");
    for (std::size_t k = 0; k < particles.size(); ++k) {
      if (!particles[k].is_number_integer() || particles[k].get<std::int64_t>() < 0 ||
          particles[k].get<std::uint64_t>() >= n) {
        fail(element(c.path_of("particles"), k),
             "must be a particle index below " + std::to_string(n));
      }
      cloth.constrain(plane ? ParticleConstraint::Kind::kPlane : ParticleConstraint::Kind::kLine,
                      particles[k].get<std::uint32_t>(), axis);
    }
  }
}

/// "anchors": [{"particle": 5, "target": [x, y, z], "stiffness": 50, "damping": 0.5}]
void read_anchors(const ObjectReader& body, ClothBody& cloth) {
  if (!body.has("anchors")) return;
  const json& list = body.at("anchors");
  if (!list.is_array()) fail(body.path_of("anchors"), "must be an array");
  const std::uint32_t n = static_cast<std::uint32_t>(cloth.model().particle_count());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ObjectReader a(list[i], element(body.path_of("anchors"), i),
                         {"particle", "target", "stiffness", "damping"});
    Anchor anchor;
    if (!a.has("particle")) fail(a.path_of("particle"), "is required");
    anchor.particle = a.count("particle", 0, 0, n - 1);
    anchor.target = a.vec3("target", cloth.state().x[anchor.particle]);
    anchor.stiffness = a.ranged("stiffness", 100, kMinStiffness, kMaxStiffness, "N/m");
    anchor.damping = a.ranged("damping", 0, 0, kMaxDamping, "N·s/m");
    cloth.set_anchor(anchor);
  }
}

/// "constraint_forces": [{"type": "sphere", "particle": 3, "center": [...], "radius": 0.5,
/// "stiffness": 100, "damping": 20}, {"type": "plane", "particle": 4, "point": [...],
/// "normal": [...]}]: Witkin's constraint forces.
void read_constraint_forces(const ObjectReader& body, ClothBody& cloth) {
  if (!body.has("constraint_forces")) return;
  const json& list = body.at("constraint_forces");
  if (!list.is_array()) fail(body.path_of("constraint_forces"), "must be an array");
  const auto n = static_cast<std::uint32_t>(cloth.model().particle_count());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ObjectReader c(
        list[i], element(body.path_of("constraint_forces"), i),
        {"type", "particle", "center", "radius", "point", "normal", "stiffness", "damping"});
    ConstraintForce constraint;
    if (!c.has("particle")) fail(c.path_of("particle"), "is required");
    constraint.particle = c.count("particle", 0, 0, n - 1);
    constraint.stiffness = c.non_negative("stiffness", 100);
    constraint.damping = c.non_negative("damping", 20);
    const std::string type = c.string("type", "");
    if (type == "sphere") {
      constraint.kind = ConstraintForce::Kind::kSphere;
      constraint.point = c.vec3("center", Vec3::Zero());
      constraint.radius = c.length("radius", 1);
    } else if (type == "plane") {
      constraint.kind = ConstraintForce::Kind::kPlane;
      constraint.point = c.vec3("point", cloth.state().x[constraint.particle]);
      constraint.normal = c.vec3("normal", Vec3::UnitY());
      if (constraint.normal.norm() == 0) fail(c.path_of("normal"), "must not be zero");
    } else {
      fail(c.path_of("type"), "must be sphere or plane");
    }
    cloth.add_constraint_force(constraint);
  }
}

/// A cloth from an OBJ file inside the asset root, transformed.
ClothModel read_mesh_model(const ObjectReader& body, const SceneLoadOptions& options,
                           Real total_mass, std::size_t& particles_left) {
  const ObjectReader mesh(body.at("mesh"), body.path_of("mesh"), {"file", "transform"});
  auto triangles = read_obj_file(asset_file(mesh, "file", options.asset_root));
  if (!triangles) fail(mesh.path_of("file"), triangles.error());
  take_particles(mesh.path_of("file"), triangles->positions.size(), particles_left);
  const Transform transform = read_transform(mesh);
  for (Vec3& p : triangles->positions) p = transform.apply(p);
  return make_mesh_cloth(*triangles, total_mass);
}

ClothBody read_cloth(const ObjectReader& body, std::size_t index, const SceneLoadOptions& options,
                     Real time_step, const HealthSettings& health, std::size_t& particles_left) {
  if (body.has("grid") == body.has("mesh")) {
    fail(body.path_of("grid"), "a cloth needs exactly one of \"grid\" and \"mesh\"");
  }
  const Real total_mass = body.ranged("mass", 1, kMinMass, kMaxMass, "kg");
  std::optional<GridClothSpec> grid;
  std::shared_ptr<const ClothModel> model;
  if (body.has("grid")) {
    grid = read_grid(body);
    grid->total_mass = total_mass;
    // checked before anything is allocated for the body
    take_particles(body.path_of("grid"), std::size_t{grid->nx} * grid->ny, particles_left);
    model = std::make_shared<const ClothModel>(make_grid_cloth(*grid));
  } else {
    model = std::make_shared<const ClothModel>(
        read_mesh_model(body, options, total_mass, particles_left));
  }
  ClothBody cloth(body.name("name", "cloth" + std::to_string(index)), model, read_springs(body),
                  read_cloth_integrator(body));
  for (std::uint32_t p : read_pins(body, grid ? &*grid : nullptr, model->particle_count())) {
    cloth.pin(p);
  }
  read_constraints(body, cloth);
  read_anchors(body, cloth);
  read_constraint_forces(body, cloth);
  check_stable_step(body, cloth, time_step, health);
  // xpbd's substeps are the one integrator work the budget cannot cut (xpbd_integrator.hpp)
  const auto* xpbd = dynamic_cast<const XpbdIntegrator*>(&cloth.integrator());
  cloth.set_max_step(read_max_step(body, time_step, health, xpbd ? xpbd->substeps() : 1));
  return cloth;
}

Collider read_collider(const json& value, const std::string& path) {
  const ObjectReader reader(
      value, path,
      {"type", "point", "normal", "center", "radius", "half_extents", "a", "b", "friction"});
  Collider c;
  c.friction = reader.non_negative("friction", c.friction);
  const std::string type = reader.string("type", "");
  if (type == "plane") {
    c.shape = Collider::Shape::kPlane;
    c.center = reader.vec3("point", Vec3::Zero());
    const Vec3 normal = reader.vec3("normal", Vec3::UnitY());
    if (normal.norm() == 0) fail(reader.path_of("normal"), "must not be zero");
    c.normal = normal.normalized();
  } else if (type == "sphere") {
    c.shape = Collider::Shape::kSphere;
    c.center = reader.vec3("center", Vec3::Zero());
    c.radius = reader.length("radius", c.radius);
  } else if (type == "box") {
    c.shape = Collider::Shape::kBox;
    c.center = reader.vec3("center", Vec3::Zero());
    c.half_extents = reader.extent("half_extents", c.half_extents);
  } else if (type == "capsule") {
    c.shape = Collider::Shape::kCapsule;
    c.center = reader.vec3("a", Vec3::Zero());
    c.end = reader.vec3("b", Vec3::UnitX());
    c.radius = reader.length("radius", c.radius);
  } else {
    fail(reader.path_of("type"), "must be plane, sphere, box or capsule");
  }
  return c;
}

SceneBody read_body(const json& entry, const std::string& path, std::size_t index,
                    const SceneLoadOptions& options, Real time_step, const HealthSettings& health,
                    std::size_t& particles_left) {
  const json* type = entry.is_object() && entry.contains("type") ? &entry["type"] : nullptr;
  if (type && *type == "cloth") {
    const ObjectReader body(entry, path,
                            {"name", "type", "grid", "mesh", "mass", "springs", "drag",
                             "stretch_limit", "thickness", "self_collision", "wind", "integrator",
                             "pin", "constraints", "anchors", "constraint_forces", "max_step"});
    return read_cloth(body, index, options, time_step, health, particles_left);
  }
  if (type && *type == "solid") {
    const ObjectReader body(
        entry, path,
        {"name", "type", "lattice", "mesh", "tetgen", "torus", "sphere", "transform", "model",
         "node_mass", "friction", "self_collision", "crease_angle", "mass_spring", "shape_matching",
         "fem", "pin", "integrator", "max_step"});
    return read_solid(body, index, options.asset_root, time_step, health, particles_left);
  }
  fail(child(path, "type"), "must be \"cloth\" or \"solid\"");
}

void read_bodies(const json& bodies, const SceneLoadOptions& options, const WorldSettings& settings,
                 Scene& scene) {
  if (!bodies.is_array()) fail("bodies", "must be an array");
  std::size_t particles_left = options.max_particles;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    std::visit([&](auto&& body) { scene.world.add_body(std::move(body)); },
               read_body(bodies[i], element("bodies", i), i, options, settings.time_step,
                         settings.health, particles_left));
  }
}

Scene read_scene(const json& document, const SceneLoadOptions& options) {
  const ObjectReader root(document, "",
                          {"name", "time_step", "gravity", "max_speed", "health", "haptics",
                           "colliders", "solids", "bodies"});
  WorldSettings settings;
  settings.time_step = root.positive("time_step", settings.time_step);
  if (settings.time_step > 0.1) fail(root.path_of("time_step"), "must be at most 0.1 s");
  // no shorter: at 1e-9 s, a millisecond of the scene was a million steps before any frame
  if (settings.time_step < 1e-6) fail(root.path_of("time_step"), "must be at least 1e-6 s");
  settings.gravity = root.vec3("gravity", settings.gravity);
  if (root.has("max_speed")) settings.max_speed = root.ranged("max_speed", 0, 1e-3, 1e6, "m/s");
  if (root.has("health")) {
    read_health(ObjectReader(root.at("health"), root.path_of("health"),
                             {"enabled", "energy_check", "energy_tolerance", "energy_window",
                              "max_energy_growth", "speed_growth", "max_substep_doublings",
                              "relax_after", "auto_substeps", "step_budget"}),
                settings);
  }
  SolidStepSettings solid_settings;
  if (root.has("solids")) {
    solid_settings = read_solid_settings(
        ObjectReader(root.at("solids"), root.path_of("solids"),
                     {"max_step", "contact_iterations", "min_depth", "max_speed", "friction"}),
        settings.time_step);
  }

  Scene scene(root.name("name", "unnamed"), World(settings, solid_settings));
  if (root.has("haptics")) {
    read_haptics(ObjectReader(root.at("haptics"), root.path_of("haptics"),
                              {"proxy_radius", "stiffness", "damping", "max_force",
                               "max_force_change", "static_friction", "dynamic_friction",
                               "force_shading", "structure", "servo_rate", "devices"}),
                 scene);
  }

  // colliders take the body ids after the bodies, so a body's id is its index in "bodies"
  if (root.has("bodies")) read_bodies(root.at("bodies"), options, settings, scene);
  if (root.has("colliders")) {
    const json& colliders = root.at("colliders");
    if (!colliders.is_array()) fail("colliders", "must be an array");
    for (std::size_t i = 0; i < colliders.size(); ++i) {
      scene.world.add_collider(read_collider(colliders[i], element("colliders", i)));
    }
  }
  return scene;
}

}  // namespace

std::expected<Scene, SceneError> load_scene(const json& document, const SceneLoadOptions& options) {
  try {
    return read_scene(document, options);
  } catch (const Failure& failure) {
    return std::unexpected(failure.error);
  }
}

std::expected<SceneBody, SceneError> load_body(const json& entry, const std::string& path,
                                               std::size_t index, Real time_step,
                                               const SceneLoadOptions& options,
                                               const HealthSettings& health) {
  try {
    std::size_t particles_left = options.max_particles;
    return read_body(entry, path, index, options, time_step, health, particles_left);
  } catch (const Failure& failure) {
    return std::unexpected(failure.error);
  }
}

std::expected<Collider, SceneError> load_collider(const json& entry, const std::string& path) {
  try {
    return read_collider(entry, path);
  } catch (const Failure& failure) {
    return std::unexpected(failure.error);
  }
}

std::expected<json, SceneError> parse_json(std::string_view text, const std::string& source) {
  // Each nested container costs about 80 bytes for its 2 bytes of text, so a deeply nested
  // document took ~30 times its size in memory; no scene needs more than a handful of levels.
  struct TooDeep {};
  const auto limit_depth = [](int depth, json::parse_event_t event, json&) {
    const bool opens =
        event == json::parse_event_t::object_start || event == json::parse_event_t::array_start;
    if (opens && depth >= kMaxJsonDepth) throw TooDeep{};
    return true;
  };
  try {
    return json::parse(text, limit_depth);
  } catch (const TooDeep&) {
    return std::unexpected(SceneError{"", source + " nests arrays and objects deeper than " +
                                              std::to_string(kMaxJsonDepth) + " levels"});
  } catch (const json::exception& e) {
    // parse errors, and numbers no double can hold (1e400), among others
    return std::unexpected(SceneError{"", source + " is not valid JSON: " + e.what()});
  }
}

std::expected<Scene, SceneError> load_scene_text(std::string_view text,
                                                 const SceneLoadOptions& options) {
  const auto document = parse_json(text, "the scene");
  if (!document) return std::unexpected(document.error());
  return load_scene(*document, options);
}

std::expected<json, SceneError> read_scene_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return std::unexpected(SceneError{"", "cannot open " + file.string()});
  std::ostringstream text;
  text << in.rdbuf();
  if (file.extension() == ".cfg") return thesis_scene_to_json(text.str(), file.string());
  return parse_json(text.str(), file.string());
}

std::expected<Scene, SceneError> load_scene_file(const std::filesystem::path& file,
                                                 const SceneLoadOptions& options) {
  const auto document = read_scene_json(file);
  if (!document) return std::unexpected(document.error());
  return load_scene(*document, options);
}

}  // namespace felt
