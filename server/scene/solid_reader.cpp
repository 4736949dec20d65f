#include "scene/solid_reader.hpp"

#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <utility>

#include "core/geometry/procedural_surfaces.hpp"
#include "core/math/bounds_of.hpp"
#include "core/solids/tet_lattice.hpp"
#include "core/solids/voxel_lattice.hpp"
#include "scene/body_step_reader.hpp"
#include "scene/obj_reader.hpp"
#include "scene/tetgen_reader.hpp"

namespace felt::scene_json {
namespace {

constexpr std::uint32_t kMaxLatticeCells = 64;  ///< per axis
/// substeps per scene step beyond which a material is refused as too stiff for its mass
constexpr Real kMaxSubsteps = 2000;

/// A lattice and, when the shape has one, the fine surface it carries.
struct SolidShape {
  TetMesh lattice;
  std::optional<EmbeddedSurface> surface;
  /// a voxelized lattice: its surface is a staircase standing for a smooth one, whose steps'
  /// 90° edges should not count as sharp
  bool voxelized = false;
};

/// Checks a lattice of up to `cells` cells per axis against the particle limit before any
/// of it is allocated.
void take_lattice(const std::string& path, std::uint32_t cells, std::size_t& particles_left) {
  const std::size_t side = std::size_t{cells} + 1;
  take_particles(path, side * side * side, particles_left);
}

SolidShape embedded(const TriangleMesh& surface, std::uint32_t resolution) {
  EmbeddedSolid solid = voxelize_surface(surface, static_cast<int>(resolution));
  return {std::move(solid.lattice), std::move(solid.surface), true};
}

SolidShape read_shape(const ObjectReader& body, const std::filesystem::path& asset_root,
                      std::size_t& particles_left) {
  const char* shapes[] = {"lattice", "mesh", "tetgen", "torus", "sphere"};
  const char* given = nullptr;
  for (const char* key : shapes) {
    if (!body.has(key)) continue;
    if (given) fail(body.path_of(key), std::string("a solid takes one shape; it has ") + given);
    given = key;
  }
  if (!given) fail(body.path(), "a solid needs one of lattice, mesh, tetgen, torus, sphere");
  const std::string shape = given;
  if (shape == "lattice") {
    const ObjectReader lattice(body.at("lattice"), body.path_of("lattice"),
                               {"cells", "size", "fine_divisions"});
    const Vec3 cells = lattice.vec3("cells", Vec3(5, 5, 5));
    for (int a = 0; a < 3; ++a) {
      if (cells[a] != std::floor(cells[a]) || cells[a] < 1 || cells[a] > kMaxLatticeCells) {
        fail(element(lattice.path_of("cells"), a),
             "must be an integer between 1 and " + std::to_string(kMaxLatticeCells));
      }
    }
    const Vec3 size = lattice.extent("size", Vec3::Ones());
    LatticeGrid grid;
    grid.cells = {static_cast<int>(cells.x()), static_cast<int>(cells.y()),
                  static_cast<int>(cells.z())};
    grid.cell_size = size.cwiseQuotient(cells);
    grid.origin = -size / 2;
    take_particles(lattice.path_of("cells"), static_cast<std::size_t>((cells.array() + 1).prod()),
                   particles_left);
    SolidShape out{make_box_lattice(grid), std::nullopt};
    if (lattice.has("fine_divisions")) {
      const std::uint32_t divisions = lattice.count("fine_divisions", 1, 1, 256);
      const std::size_t side = divisions + 1;
      take_particles(lattice.path_of("fine_divisions"), 6 * side * side, particles_left);
      TriangleMesh fine = make_box_surface(size, static_cast<int>(divisions));
      out.surface = embed_surface(out.lattice, fine);
    }
    return out;
  }
  if (shape == "mesh") {
    const ObjectReader mesh(body.at("mesh"), body.path_of("mesh"), {"file", "resolution"});
    const std::uint32_t resolution = mesh.count("resolution", 6, 1, kMaxLatticeCells);
    auto surface = read_obj_file(asset_file(mesh, "file", asset_root));
    if (!surface) fail(mesh.path_of("file"), surface.error());
    take_particles(mesh.path_of("file"), surface->positions.size(), particles_left);
    take_lattice(mesh.path_of("resolution"), resolution, particles_left);
    // the lattice's cells are the surface's extent over the resolution: none, no cells
    // (found by scripts/fuzz obj_reader: the voxelizer's check stopped the process)
    if (!(bounds_of(surface->positions).sizes().maxCoeff() > 0)) {
      fail(mesh.path_of("file"),
           "its vertices all lie at one point: a solid needs a surface "
           "that encloses something");
    }
    return embedded(*surface, resolution);
  }
  if (shape == "tetgen") {
    const ObjectReader tetgen(body.at("tetgen"), body.path_of("tetgen"), {"file"});
    auto mesh = read_tetgen_files(asset_file(tetgen, "file", asset_root));
    if (!mesh) fail(tetgen.path_of("file"), mesh.error());
    take_particles(tetgen.path_of("file"), mesh->nodes.size(), particles_left);
    return {std::move(*mesh), std::nullopt};
  }
  if (shape == "torus") {
    const ObjectReader torus(body.at("torus"), body.path_of("torus"),
                             {"major_radius", "minor_radius", "resolution"});
    const Real major = torus.length("major_radius", 1);
    const Real minor = torus.length("minor_radius", 0.3);
    if (minor >= major) fail(torus.path_of("minor_radius"), "must be below major_radius");
    const std::uint32_t resolution = torus.count("resolution", 12, 1, kMaxLatticeCells);
    take_lattice(torus.path_of("resolution"), resolution, particles_left);
    return embedded(make_torus_surface(major, minor, 48, 16), resolution);
  }
  const ObjectReader sphere(body.at("sphere"), body.path_of("sphere"), {"radius", "resolution"});
  const Real radius = sphere.length("radius", 0.5);
  const std::uint32_t resolution = sphere.count("resolution", 6, 1, kMaxLatticeCells);
  take_lattice(sphere.path_of("resolution"), resolution, particles_left);
  return embedded(make_sphere_surface(radius, 3), resolution);
}

SolidMaterial read_material(const ObjectReader& body) {
  SolidMaterial m;
  const std::string model = body.string("model", "mass_spring");
  const std::pair<std::string_view, SolidModel> models[] = {
      {"mass_spring", SolidModel::kMassSpring},
      {"shape_matching", SolidModel::kShapeMatching},
      {"corotated_fem", SolidModel::kCorotatedFem}};
  bool known = false;
  for (const auto& [name, kind] : models) {
    if (model == name) m.model = kind, known = true;
  }
  if (!known) fail(body.path_of("model"), "must be mass_spring, shape_matching or corotated_fem");
  m.node_mass = body.positive("node_mass", m.node_mass);
  m.friction = body.non_negative("friction", m.friction);
  m.self_collision = body.boolean("self_collision", m.self_collision);
  if (body.has("mass_spring")) {
    const ObjectReader ms(body.at("mass_spring"), body.path_of("mass_spring"),
                          {"distance_stiffness", "volume_stiffness", "damping", "area_stiffness"});
    MassSpringMaterial& s = m.mass_spring;
    s.distance_stiffness = ms.positive("distance_stiffness", s.distance_stiffness);
    s.volume_stiffness = ms.non_negative("volume_stiffness", s.volume_stiffness);
    s.damping = ms.non_negative("damping", s.damping);
    s.area_stiffness = ms.non_negative("area_stiffness", s.area_stiffness);
  }
  if (body.has("shape_matching")) {
    const ObjectReader sm(body.at("shape_matching"), body.path_of("shape_matching"),
                          {"mode", "beta", "time_constant", "clusters", "plasticity"});
    ShapeMatchingMaterial& s = m.shape_matching;
    const std::string mode = sm.string("mode", "linear");
    if (mode == "rigid") {
      s.mode = ShapeMatchingMaterial::Mode::kRigid;
    } else if (mode == "linear") {
      s.mode = ShapeMatchingMaterial::Mode::kLinear;
    } else if (mode == "quadratic") {
      s.mode = ShapeMatchingMaterial::Mode::kQuadratic;
    } else {
      fail(sm.path_of("mode"), "must be rigid, linear or quadratic");
    }
    s.beta = sm.non_negative("beta", s.beta);
    if (s.beta > 1) fail(sm.path_of("beta"), "must be between 0 and 1");
    s.time_constant = sm.positive("time_constant", s.time_constant);
    s.clusters = sm.boolean("clusters", s.clusters);
    if (sm.has("plasticity")) {
      const ObjectReader p(sm.at("plasticity"), sm.path_of("plasticity"),
                           {"yield", "creep", "max"});
      s.plastic_yield = p.positive("yield", 0.1);
      s.plastic_creep = p.positive("creep", 1);
      s.plastic_max = p.positive("max", 1);
    }
  }
  if (body.has("fem")) {
    const ObjectReader fem(body.at("fem"), body.path_of("fem"),
                           {"young_modulus", "poisson_ratio", "damping"});
    FemMaterial& f = m.fem;
    f.young_modulus = fem.positive("young_modulus", f.young_modulus);
    f.poisson_ratio = fem.number("poisson_ratio", f.poisson_ratio);
    if (!(f.poisson_ratio >= 0 && f.poisson_ratio < 0.5)) {
      fail(fem.path_of("poisson_ratio"), "must be in [0, 0.5)");
    }
    f.damping = fem.non_negative("damping", f.damping);
  }
  return m;
}

}  // namespace

SolidBody read_solid(const ObjectReader& body, std::size_t index,
                     const std::filesystem::path& asset_root, Real time_step,
                     const HealthSettings& health, std::size_t& particles_left) {
  SolidShape shape = read_shape(body, asset_root, particles_left);
  const Transform transform = read_transform(body);
  for (Vec3& x : shape.lattice.nodes) x = transform.apply(x);
  // a rotation and positive scales keep every tetrahedron positive
  SolidMaterial material = read_material(body);
  const Real crease = body.number(
      "crease_angle", shape.voxelized ? 180 : kDefaultCreaseAngle * 180 / std::numbers::pi);
  if (!(crease >= 0 && crease <= 180)) fail(body.path_of("crease_angle"), "must be 0 to 180");
  material.crease_angle = crease * std::numbers::pi / 180;
  SolidBody solid(body.name("name", "solid" + std::to_string(index)), std::move(shape.lattice),
                  material);
  // clients see the fine surface, or the lattice's own surface without its interior nodes
  solid.set_embedded_surface(std::make_shared<const EmbeddedSurface>(
      shape.surface ? std::move(*shape.surface)
                    : embed_lattice_surface(solid.rest(), solid.topology().surface)));
  if (body.has("pin")) {
    const json& pins = body.at("pin");
    if (!pins.is_array()) fail(body.path_of("pin"), "must be a list of node indices");
    for (std::size_t i = 0; i < pins.size(); ++i) {
      if (!pins[i].is_number_integer() || pins[i].get<std::int64_t>() < 0 ||
          pins[i].get<std::uint64_t>() >= solid.node_count()) {
        fail(element(body.path_of("pin"), i),
             "must be a node index below " + std::to_string(solid.node_count()));
      }
      solid.pin(pins[i].get<std::uint32_t>());
    }
  }
  if (body.has("integrator")) {
    const std::string name = body.string("integrator", std::string(kTimeCorrectedVerlet));
    if (const auto refused = solid_integrator_refusal(solid.material().model, name)) {
      fail(body.path_of("integrator"), *refused);
    }
    if (name != kTimeCorrectedVerlet) solid.set_integrator(make_integrator(name));
  }
  if (!(solid.stable_time_step() > 0)) {
    fail(body.path_of("integrator"),
         std::string(solid.integrator()->name()) +
             " gains energy at every step on a body without damping: no step is stable. Give "
             "the material damping, or choose symplectic_euler, rk4 or the default " +
             std::string(kTimeCorrectedVerlet));
  }
  if (time_step / solid.stable_time_step() > kMaxSubsteps) {
    fail(body.path(), "too stiff for its node mass: a stable step would be " +
                          std::to_string(solid.stable_time_step()) +
                          " s; lower the stiffness or raise node_mass");
  }
  solid.set_max_step(read_max_step(body, time_step, health));
  return solid;
}

SolidStepSettings read_solid_settings(const ObjectReader& solids, Real time_step) {
  SolidStepSettings s;
  s.max_step = solids.positive("max_step", s.max_step);
  if (s.max_step > 0.015) fail(solids.path_of("max_step"), "must be at most 0.015 s");
  // 1e-9 s made a million substeps of every step and stalled the server
  if (time_step / s.max_step > kMaxSubsteps) {
    std::ostringstream text;
    text << "must be at least the time step / " << kMaxSubsteps << " = " << time_step / kMaxSubsteps
         << " s";
    fail(solids.path_of("max_step"), text.str());
  }
  s.contact_iterations =
      static_cast<int>(solids.count("contact_iterations", s.contact_iterations, 0, 16));
  s.min_depth = solids.non_negative("min_depth", s.min_depth);
  if (solids.has("max_speed")) s.max_speed = solids.ranged("max_speed", 0, 1e-3, 1e6, "m/s");
  const std::string friction = solids.string("friction", "coulomb");
  if (friction == "coulomb") {
    s.friction = SolidFriction::kRelativeCoulomb;
  } else if (friction == "thesis") {
    s.friction = SolidFriction::kThesis;
  } else {
    fail(solids.path_of("friction"), "must be coulomb or thesis");
  }
  return s;
}

}  // namespace felt::scene_json
