// Bodies: add, remove, change parameters, pin, push.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "net/requests.hpp"
#include "scene/body_step_reader.hpp"
#include "scene/scene_loader.hpp"

namespace felt::net {
namespace {

// beyond these a value is a mistake, not a material
constexpr double kMaxStiffness = 1e8;  // N/m
constexpr double kMaxDamping = 1e6;    // N·s/m, or s for FEM's Rayleigh damping
constexpr double kMaxStrain = 10;
constexpr double kMaxFriction = 10;
constexpr double kMaxForce = 1e6;      // N per vertex
constexpr double kMaxDuration = 3600;  // s

bool in_range(double x, double lo, double hi) {
  return std::isfinite(x) && x >= lo && x <= hi;
}

std::string range(const char* what, double lo, double hi) {
  std::ostringstream text;
  text << what << " must be a finite number in [" << lo << ", " << hi << "]";
  return text.str();
}

/// Why `set` cannot change a body of kind `kind`, or empty.
std::string check_parameters(const v1::SetBodyParameters& set, const BodyInfo& body) {
  const bool cloth = body.kind == "cloth";
  if (body.kind == "collider") return "a collider has no parameters to set";
  if (!cloth && (set.has_drag() || set.has_structural_stiffness() || set.has_shear_stiffness() ||
                 set.has_bend_stiffness() || set.has_max_strain())) {
    return "body " + std::to_string(set.body_id()) +
           " is a solid: it takes damping, friction, integrator and max_step only";
  }
  if (cloth && set.has_friction()) return "friction applies to solids only";
  if (set.has_integrator()) {
    if (!cloth && body.solid_model) {
      if (auto refused = solid_integrator_refusal(*body.solid_model, set.integrator())) {
        return "body " + std::to_string(set.body_id()) + ": " + *refused;
      }
    } else if (!make_integrator(set.integrator())) {
      return "unknown integrator \"" + set.integrator() + "\"";
    }
  }
  if (set.has_drag() && !in_range(set.drag(), 0, kMaxDamping)) {
    return range("drag", 0, kMaxDamping);
  }
  for (const auto& [given, k] :
       {std::pair{set.has_structural_stiffness(), set.structural_stiffness()},
        std::pair{set.has_shear_stiffness(), set.shear_stiffness()},
        std::pair{set.has_bend_stiffness(), set.bend_stiffness()}}) {
    if (given && !(k > 0 && in_range(k, 0, kMaxStiffness))) {
      return range("stiffness", 0, kMaxStiffness) + " and > 0";
    }
  }
  if (set.has_max_strain() && !in_range(set.max_strain(), 0, kMaxStrain)) {
    return range("max_strain", 0, kMaxStrain);
  }
  if (set.has_damping() && !in_range(set.damping(), 0, kMaxDamping)) {
    return range("damping", 0, kMaxDamping);
  }
  if (set.has_friction() && !in_range(set.friction(), 0, kMaxFriction)) {
    return range("friction", 0, kMaxFriction);
  }
  if (set.has_max_step() && set.max_step() != 0 &&
      !in_range(set.max_step(), scene_json::kMinBodyStep, scene_json::kMaxBodyStep)) {
    return range("max_step", scene_json::kMinBodyStep, scene_json::kMaxBodyStep) +
           " s, or 0 for the scene's step";
  }
  return {};
}

/// The max_step a body takes from `set`: 0 asks for none.
Real own_max_step(const v1::SetBodyParameters& set) {
  return set.max_step() > 0 ? set.max_step() : std::numeric_limits<Real>::infinity();
}

void change_cloth(const v1::SetBodyParameters& set, ClothBody& body) {
  ClothParams params = body.params();
  if (set.has_drag()) params.drag = set.drag();
  const std::pair<bool, double> stiffness[] = {
      {set.has_structural_stiffness(), set.structural_stiffness()},
      {set.has_shear_stiffness(), set.shear_stiffness()},
      {set.has_bend_stiffness(), set.bend_stiffness()}};
  for (int kind = 0; kind < kSpringKindCount; ++kind) {
    if (stiffness[kind].first) params.springs[kind].stiffness = stiffness[kind].second;
    if (set.has_damping()) params.springs[kind].damping = set.damping();
  }
  if (set.has_max_strain()) {
    params.stretch.enabled = set.max_strain() > 0;
    if (params.stretch.enabled) params.stretch.max_strain = set.max_strain();
  }
  body.set_params(params);
  if (set.has_integrator()) body.set_integrator(make_integrator(set.integrator()));
  if (set.has_max_step()) body.set_max_step(own_max_step(set));
}

void change_solid(const v1::SetBodyParameters& set, SolidBody& body) {
  SolidMaterial material = body.material();
  if (set.has_friction()) material.friction = set.friction();
  if (set.has_damping()) {
    material.mass_spring.damping = set.damping();
    material.fem.damping = set.damping();
  }
  body.set_material(material);
  if (set.has_max_step()) body.set_max_step(own_max_step(set));
  if (set.has_integrator()) {
    body.set_integrator(
        set.integrator() == kTimeCorrectedVerlet ? nullptr : make_integrator(set.integrator()));
  }
}

Completion<BodyId> answer_body_updated(std::shared_ptr<PendingReply> pending) {
  return answer<BodyId>(std::move(pending), [](const BodyId& body, v1::ServerMessage& message) {
    message.mutable_body_updated()->set_body_id(body.value());
  });
}

Completion<BodyInfo> answer_body_added(std::shared_ptr<PendingReply> pending) {
  return answer<BodyInfo>(std::move(pending), [](const BodyInfo& body, v1::ServerMessage& m) {
    fill_body_info(body, *m.mutable_body_added()->mutable_body());
  });
}

}  // namespace

std::optional<BodyInfo> changeable_body(Session& session, std::uint64_t id, BodyId body_id) {
  const auto bodies = session.scene()->bodies();
  const BodyInfo* body = bodies->find(body_id);
  if (!body) {
    session.send_error(id, v1::ERROR_CODE_UNKNOWN_ID,
                       "no body " + std::to_string(body_id.value()) + " in this scene");
    return std::nullopt;
  }
  if (!session.scene()->may_change(session.client_id(), *body)) {
    session.send_error(id, v1::ERROR_CODE_PERMISSION_DENIED,
                       "body " + std::to_string(body_id.value()) + " belongs to client " +
                           std::to_string(body->owner.value()) + " and the scene is not shared");
    return std::nullopt;
  }
  return *body;
}

void handle_add_body(Session& session, std::uint64_t id, const v1::AddBody& add) {
  if (add.source_case() == v1::AddBody::SOURCE_NOT_SET) {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, "AddBody needs body_json or collider_json");
    return;
  }
  auto pending = defer_or_refuse(session, id);
  if (!pending) return;
  ServerContext& context = session.context();
  std::shared_ptr<SceneRunner> scene = session.scene();
  const auto bad = [](const SceneError& error) -> std::expected<BuiltBody, RunnerError> {
    return std::unexpected(load_error(error));
  };
  // a body can be a big mesh to voxelize: built on the loader thread, then added in its place
  // among the client's requests
  scene->add_body(
      session.client_id(), on_loader(context, scene),
      [&context, bad, scene = scene.get(), add]() -> std::expected<BuiltBody, RunnerError> {
        const bool collider = add.has_collider_json();
        auto entry = parse_json(collider ? add.collider_json() : add.body_json(),
                                collider ? "the collider" : "the body");
        if (!entry) return bad(entry.error());
        if (collider) {
          auto built = load_collider(*entry, "collider");
          if (!built) return bad(built.error());
          return *built;
        }
        SceneLoadOptions options;
        const std::uint64_t used = scene->bodies()->particles();
        const std::uint64_t limit = context.options.max_particles_per_scene;
        options.max_particles = used < limit ? limit - used : 0;
        options.asset_root = context.scene_directory.root();
        auto built = load_body(*entry, "body", scene->bodies()->bodies.size(), scene->time_step(),
                               options, scene->health_settings());
        if (!built) return bad(built.error());
        return std::move(*built);
      },
      answer_body_added(pending));
}

void handle_remove_body(Session& session, std::uint64_t id, const v1::RemoveBody& remove) {
  if (!changeable_body(session, id, remove.body_id())) return;
  auto pending = defer_or_refuse(session, id);
  if (!pending) return;
  session.scene()->remove_body(
      session.client_id(), remove.body_id(),
      answer<BodyId>(pending, [](const BodyId& body, v1::ServerMessage& message) {
        message.mutable_body_removed()->set_body_id(body.value());
      }));
}

void handle_set_body_parameters(Session& session, std::uint64_t id,
                                const v1::SetBodyParameters& set) {
  const auto body = changeable_body(session, id, set.body_id());
  if (!body) return;
  // everything is checked here, so the change the physics thread applies cannot fail
  if (const std::string why = check_parameters(set, *body); !why.empty()) {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, why);
    return;
  }
  auto pending = defer_or_refuse(session, id);
  if (!pending) return;
  // answered once applied: a body removed by a request queued before this one gets UNKNOWN_ID
  session.scene()->change_body(
      session.client_id(), set.body_id(),
      [set](World& world) {
        if (ClothBody* cloth = world.cloth(set.body_id())) change_cloth(set, *cloth);
        if (SolidBody* solid = world.solid(set.body_id())) change_solid(set, *solid);
      },
      answer_body_updated(pending));
}

void handle_pin_particles(Session& session, std::uint64_t id, const v1::PinParticles& pins) {
  const auto body = changeable_body(session, id, pins.body_id());
  if (!body) return;
  if (body->kind == "collider") {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, "a collider has no particles");
    return;
  }
  for (const auto* list : {&pins.pin(), &pins.unpin()}) {
    for (std::uint32_t p : *list) {
      if (p >= body->nodes) {
        session.send_error(id, v1::ERROR_CODE_BAD_REQUEST,
                           "particle " + std::to_string(p) + " out of range (the body has " +
                               std::to_string(body->nodes) + ")");
        return;
      }
    }
  }
  auto pending = defer_or_refuse(session, id);
  if (!pending) return;
  session.scene()->change_body(
      session.client_id(), pins.body_id(),
      [pins](World& world) {
        if (ClothBody* cloth = world.cloth(pins.body_id())) {
          for (std::uint32_t p : pins.unpin()) cloth->unpin(p);
          for (std::uint32_t p : pins.pin()) cloth->pin(p);
        } else if (SolidBody* solid = world.solid(pins.body_id())) {
          for (std::uint32_t n : pins.unpin()) solid->unpin(n);
          for (std::uint32_t n : pins.pin()) solid->pin(n);
        }
      },
      answer_body_updated(pending));
}

void handle_apply_force(Session& session, std::uint64_t id, const v1::ApplyForce& push) {
  const auto body = changeable_body(session, id, push.body_id());
  if (!body) return;
  const auto bad = [&](const std::string& why) {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, why);
  };
  if (body->kind == "collider") return bad("a collider does not move");
  if (push.vertices().empty()) return bad("name at least one vertex");
  std::vector<std::uint32_t> vertices = sorted_unique(push.vertices());
  if (vertices.back() >= body->particles) {
    return bad("vertex " + std::to_string(vertices.back()) + " out of range (the body has " +
               std::to_string(body->particles) + ")");
  }
  const Vec3 force = to_vec3(push.force());
  if (!force.allFinite() || force.norm() > kMaxForce) {
    return bad(range("|force|", 0, kMaxForce));
  }
  if (!in_range(push.duration(), 0, kMaxDuration)) {
    return bad(range("duration", 0, kMaxDuration));
  }
  auto pending = defer_or_refuse(session, id);
  if (!pending) return;
  session.scene()->apply_force(session.client_id(), push.body_id(), std::move(vertices), force,
                               push.duration(), answer_body_updated(pending));
}

}  // namespace felt::net
