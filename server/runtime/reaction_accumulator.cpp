#include "runtime/reaction_accumulator.hpp"

namespace felt {

void ReactionAccumulator::record(std::uint64_t proxy_key, const ProxySample& sample) {
  std::lock_guard lock(mutex_);
  ProxyReaction& reaction = reactions_[proxy_key];
  ++reaction.samples;
  reaction.sphere = sample.sphere;
  reaction.grab = sample.grab;
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

void ReactionAccumulator::forget(std::uint64_t proxy_key) {
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
    if (reaction.samples > 0) {
      const Real weight = Real{1} / reaction.samples;
      reaction.held.swap(reaction.forces);
      for (ParticleForce& pf : reaction.held) pf.force *= weight;
      reaction.forces.clear();
      reaction.samples = 0;
    }
    // ids come from a snapshot, so check them against the world they are applied to
    const auto in_world = [&](BodyId body, std::uint32_t vertex) {
      return world.contains(body) && vertex < world.surface_vertex_count(body);  // 0: collider
    };
    if (reaction.grab && !reaction.closed &&
        in_world(reaction.grab->body_id, reaction.grab->vertex)) {
      const GrabSpring& g = *reaction.grab;
      world.set_surface_anchor(g.body_id, g.vertex, g.target, g.stiffness, g.damping);
      anchored_.emplace_back(g.body_id, g.vertex);
      it = std::next(it);
      continue;  // the anchor is the reaction
    }
    for (const ParticleForce& pf : reaction.held) {
      if (in_world(pf.body_id, pf.particle))
        world.add_surface_force(pf.body_id, pf.particle, pf.force);
    }
    it = reaction.closed ? reactions_.erase(it) : std::next(it);
  }
  world.set_moving_colliders(spheres_);
}

}  // namespace felt
