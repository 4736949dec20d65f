#include "runtime/snapshot.hpp"

#include "core/surface_normals.hpp"

namespace felt {

std::shared_ptr<const SceneSnapshot> make_snapshot(const World& world) {
  auto snapshot = std::make_shared<SceneSnapshot>();
  snapshot->step = world.step_count();
  snapshot->sim_time = world.time();
  snapshot->bodies.reserve(world.bodies().size());
  for (std::uint32_t id = 0; id < world.bodies().size(); ++id) {
    const ClothBody& body = world.bodies()[id];
    BodySnapshot& out = snapshot->bodies.emplace_back(
        BodySnapshot{id, body.name(), body.shared_model(), body.state().x, {}});
    compute_vertex_normals(out.positions, body.model().triangles, out.normals);
  }
  return snapshot;
}

}  // namespace felt
