#include "runtime/snapshot.hpp"

namespace felt {

std::shared_ptr<const SceneSnapshot> make_snapshot(const World& world) {
  auto snapshot = std::make_shared<SceneSnapshot>();
  snapshot->step = world.step_count();
  snapshot->sim_time = world.time();
  snapshot->bodies.reserve(world.bodies().size());
  for (std::uint32_t id = 0; id < world.bodies().size(); ++id) {
    const ClothBody& body = world.bodies()[id];
    snapshot->bodies.push_back(
        {id, body.name(), body.shared_model(), body.state().x, body.vertex_normals()});
  }
  return snapshot;
}

}  // namespace felt
