#include "core/world/world_state.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/math/bounds.hpp"

namespace felt {
namespace {

bool all_within_bounds(const std::vector<Vec3>& vectors) {
  return std::all_of(vectors.begin(), vectors.end(),
                     [](const Vec3& v) { return within_bounds(v); });
}

std::string body_name(BodyId id) {
  return "body " + std::to_string(id.value());
}

/// Why `body` does not fit `world`, or nothing when it does.
std::optional<std::string> mismatch(const World& world, const BodyMotionState& body) {
  std::size_t particles = 0;
  if (const ClothBody* cloth = world.cloth(body.body_id)) {
    particles = cloth->model().particle_count();
  } else if (const SolidBody* solid = world.solid(body.body_id)) {
    particles = solid->node_count();
    if (body.previous_positions.size() != particles) {
      return body_name(body.body_id) + ": a solid needs its previous positions";
    }
  } else {
    return body_name(body.body_id) + " is not a cloth or solid of this scene";
  }
  if (body.positions.size() != particles || body.velocities.size() != particles) {
    return body_name(body.body_id) + " has " + std::to_string(particles) +
           " particles, the state " + std::to_string(body.positions.size()) + " positions and " +
           std::to_string(body.velocities.size()) + " velocities";
  }
  // as a scene file's vectors: a state far out published infinities in 32-bit frames
  if (!all_within_bounds(body.positions) || !all_within_bounds(body.velocities) ||
      !all_within_bounds(body.previous_positions)) {
    return body_name(body.body_id) + ": every value must be finite, every vector within ±1e6";
  }
  // no step of this scene was longer (a rescue's substeps are shorter): the Verlet step scales
  // its acceleration by it, and one of 1e300 s threw every node out of reach of the next step
  if (!(body.previous_step >= 0 && body.previous_step <= world.settings().time_step)) {
    return body_name(body.body_id) + ": previous_step must be within [0, the time step]";
  }
  for (std::uint32_t p : body.pinned) {
    if (p >= particles) return body_name(body.body_id) + ": pinned particle out of range";
  }
  return std::nullopt;
}

}  // namespace

WorldState capture_state(const World& world) {
  WorldState state;
  state.step = world.step_count();
  for (BodyId id : world.body_ids()) {
    BodyMotionState body;
    body.body_id = id;
    if (const ClothBody* cloth = world.cloth(id)) {
      body.positions = cloth->state().x;
      body.velocities = cloth->state().v;
      for (std::uint32_t p = 0; p < cloth->model().particle_count(); ++p) {
        if (cloth->is_pinned(p)) body.pinned.push_back(p);
      }
    } else if (const SolidBody* solid = world.solid(id)) {
      SolidBody::StepState motion;
      solid->save_step_state(motion);
      body.positions = std::move(motion.x);
      body.velocities = std::move(motion.v);
      body.previous_positions = std::move(motion.x_prev);
      body.previous_step = motion.previous_step;
      for (std::uint32_t n = 0; n < solid->node_count(); ++n) {
        if (solid->inv_mass()[n] == 0) body.pinned.push_back(n);
      }
    } else {
      continue;  // a collider
    }
    state.bodies.push_back(std::move(body));
  }
  return state;
}

std::expected<void, std::string> restore_state(World& world, const WorldState& state) {
  for (const BodyMotionState& body : state.bodies) {
    if (auto why = mismatch(world, body)) return std::unexpected(*why);
  }
  for (const BodyMotionState& body : state.bodies) {
    if (ClothBody* cloth = world.cloth(body.body_id)) {
      for (std::uint32_t p = 0; p < cloth->model().particle_count(); ++p) cloth->unpin(p);
      cloth->state().x = body.positions;
      for (std::uint32_t p : body.pinned) cloth->pin(p);
      cloth->state().v = body.velocities;
      cloth->integrator().reset();
    } else {
      SolidBody& solid = *world.solid(body.body_id);
      for (std::uint32_t n = 0; n < solid.node_count(); ++n) solid.unpin(n);
      for (std::uint32_t n : body.pinned) solid.pin(n);
      solid.restore_step_state({body.positions, body.previous_positions, body.velocities,
                                std::vector<Vec3>(solid.node_count(), Vec3::Zero()),
                                body.previous_step});
    }
  }
  world.set_step_count(state.step);
  return {};
}

}  // namespace felt
