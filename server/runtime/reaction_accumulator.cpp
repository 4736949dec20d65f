#include "runtime/reaction_accumulator.hpp"

#include <algorithm>
#include <cmath>

namespace felt {
namespace {

// ids come from a snapshot, so they are checked against the world they are applied to
bool in_world(const World& world, BodyId body, std::uint32_t vertex) {
  return world.contains(body) && vertex < world.surface_vertex_count(body);  // 0: collider
}

bool corners_in_world(const World& world, const ProxySample::Push& push) {
  return std::ranges::all_of(push.corners,
                             [&](std::uint32_t v) { return in_world(world, push.body_id, v); });
}

/// Where the point `push` touched is now.
Vec3 touched_point(const World& world, const ProxySample::Push& push) {
  Vec3 point = Vec3::Zero();
  for (int c = 0; c < 3; ++c) {
    point += push.barycentric[c] * world.surface_position(push.body_id, push.corners[c]);
  }
  return point;
}

}  // namespace

void ReactionAccumulator::apply_contact(World& world, ProxyReaction& reaction, bool held) {
  const std::optional<ProxySample::Push>& push = reaction.held_push;
  Real scale = 1;
  if (push && push->spring && corners_in_world(world, *push)) {
    scale = spring_scale(world, reaction, held);
  } else {
    reaction.contact = {};  // no contact spring: the push as it was rendered
  }
  for (const ParticleForce& pf : reaction.held) {
    if (in_world(world, pf.body_id, pf.particle))
      world.add_surface_force(pf.body_id, pf.particle, scale * pf.force);
  }
}

Real ReactionAccumulator::spring_scale(const World& world, ProxyReaction& reaction, bool held) {
  ContactEnergy& observed = reaction.contact;
  const ProxySample::Push& push = *reaction.held_push;
  // the observer: the work the body took out over the last step at the point it was pushed at
  Vec3 moved = Vec3::Zero();
  const bool went_on = observed.touching && corners_in_world(world, observed.push);
  if (went_on) {
    moved = touched_point(world, observed.push) - observed.contact;
    observed.energy += observed.device_work - observed.force.dot(moved);
  } else {
    observed.energy = observed.device_work;  // a contact starts with nothing stored
  }
  observed.device_work = 0;

  const ContactSpring& spring = *push.spring;
  Real inverse_mass = 0;
  for (int c = 0; c < 3; ++c) {
    inverse_mass += push.barycentric[c] * push.barycentric[c] *
                    world.surface_inverse_mass(push.body_id, push.corners[c]);
  }
  const Real h = world.settings().time_step;
  const Real stable = inverse_mass > 0 ? 1 / (inverse_mass * h * h) : spring.stiffness;
  const Vec3 contact = touched_point(world, push);
  const Real stretch = spring.stretch + std::min(Real{1}, stable / spring.stiffness) *
                                            (contact - spring.contact).dot(spring.normal);
  Vec3 total = Vec3::Zero();
  for (const ParticleForce& pf : reaction.held) total += pf.force;
  Real scale = std::max(Real{0}, stretch) / spring.stretch;
  if (total.norm() * scale > spring.max_force) scale = spring.max_force / total.norm();
  if (!std::isfinite(scale)) scale = 0;
  // the controller: a held push in deficit is withheld from a body that gives way under it (the
  // motion of the last step, taken to go on); pressed in, it gets the spring
  if (held && went_on && observed.energy < 0 && total.dot(moved) > 0) scale = 0;
  observed.touching = true;
  observed.push = push;
  observed.contact = contact;
  observed.force = scale * total;
  return scale;
}

void ReactionAccumulator::record(ProxyKey proxy_key, const ProxySample& sample) {
  std::lock_guard lock(mutex_);
  ProxyReaction& reaction = reactions_[proxy_key];
  ++reaction.samples;
  reaction.sphere = sample.sphere;
  reaction.grab = sample.grab;
  // the device's work into the contact since its last update in contact: the push it held the
  // body with then (all the device could press with) along the device's motion since
  if (sample.push && sample.push->spring && reaction.latest && reaction.latest->spring) {
    reaction.contact.device_work +=
        reaction.latest->force.dot(sample.push->spring->device - reaction.latest->spring->device);
  }
  reaction.latest = sample.push;
  if (!sample.push) return;
  const ProxySample::Push& push = *sample.push;
  for (int corner = 0; corner < 3; ++corner) {
    const std::uint32_t particle = push.corners[corner];
    const Vec3 share = push.barycentric[corner] * push.force;
    bool merged = false;
    for (ParticleForce& pf : reaction.forces) {
      if (pf.body_id == push.body_id && pf.particle == particle) {
        pf.force += share;
        merged = true;
        break;
      }
    }
    if (!merged && reaction.forces.size() < kMaxParticlesPerProxy) {
      reaction.forces.push_back({push.body_id, particle, share});
    }
  }
}

void ReactionAccumulator::forget(ProxyKey proxy_key) {
  std::lock_guard lock(mutex_);
  const auto it = reactions_.find(proxy_key);
  if (it != reactions_.end()) it->second.closed = true;
}

void ReactionAccumulator::apply_and_clear(World& world) {
  std::lock_guard lock(mutex_);
  spheres_.clear();
  for (const auto& [body, vertex] : anchored_) {
    if (world.contains(body)) world.remove_surface_anchor(body, vertex);
  }
  anchored_.clear();
  for (auto it = reactions_.begin(); it != reactions_.end();) {
    ProxyReaction& reaction = it->second;
    if (reaction.sphere && !reaction.closed) spheres_.push_back(*reaction.sphere);
    const bool held = reaction.samples == 0;  // no update since the last step
    if (!held) {
      const Real weight = Real{1} / reaction.samples;
      reaction.held.swap(reaction.forces);
      for (ParticleForce& pf : reaction.held) pf.force *= weight;
      reaction.forces.clear();
      reaction.samples = 0;
      reaction.held_push = reaction.latest;
    }
    if (reaction.grab && !reaction.closed &&
        in_world(world, reaction.grab->body_id, reaction.grab->vertex)) {
      const GrabSpring& g = *reaction.grab;
      world.set_surface_anchor(g.body_id, g.vertex, g.target, g.stiffness, g.damping);
      anchored_.emplace_back(g.body_id, g.vertex);
      reaction.contact = {};
      it = std::next(it);
      continue;  // the anchor is the reaction
    }
    apply_contact(world, reaction, held);
    it = reaction.closed ? reactions_.erase(it) : std::next(it);
  }
  world.set_moving_colliders(spheres_);
}

}  // namespace felt
