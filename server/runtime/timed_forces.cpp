#include "runtime/timed_forces.hpp"

#include <algorithm>

namespace felt {

void TimedForces::add(BodyId body, std::vector<std::uint32_t> vertices, const Vec3& force,
                      Real until) {
  forces_.push_back({body, std::move(vertices), force, until, false});
}

void TimedForces::apply(World& world) {
  const Real now = world.time();
  std::erase_if(forces_, [&](const Entry& e) {
    return !world.contains(e.body) || (e.applied && e.until <= now);
  });
  for (Entry& e : forces_) {
    const std::size_t count = world.surface_vertex_count(e.body);
    for (std::uint32_t v : e.vertices) {
      if (v < count) world.add_surface_force(e.body, v, e.force);
    }
    e.applied = true;
  }
}

}  // namespace felt
