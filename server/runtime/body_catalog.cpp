#include "runtime/body_catalog.hpp"

#include <algorithm>

namespace felt {

const BodyInfo* BodyCatalog::find(BodyId id) const {
  const auto it = std::find_if(bodies.begin(), bodies.end(),
                               [id](const BodyInfo& body) { return body.body_id == id; });
  return it == bodies.end() ? nullptr : &*it;
}

std::uint64_t BodyCatalog::particles() const {
  std::uint64_t total = 0;
  for (const BodyInfo& body : bodies) total += body.particles;
  return total;
}

BodyInfo describe_body(const World& world, BodyId id, ClientId owner) {
  BodyInfo info;
  info.body_id = id;
  info.owner = owner;
  info.particles = static_cast<std::uint32_t>(world.surface_vertex_count(id));
  if (const ClothBody* cloth = world.cloth(id)) {
    info.name = cloth->name();
    info.kind = "cloth";
    info.triangles = static_cast<std::uint32_t>(cloth->model().triangles.size());
    info.nodes = info.particles;
  } else if (const SolidBody* solid = world.solid(id)) {
    info.name = solid->name();
    info.kind = "solid";
    const EmbeddedSurface* fine = solid->embedded_surface();
    info.triangles = static_cast<std::uint32_t>(fine ? fine->triangles.size()
                                                     : solid->topology().surface.size());
    info.nodes = static_cast<std::uint32_t>(solid->node_count());
    info.solid_model = solid->material().model;
  } else {
    info.name = "collider" + std::to_string(id.value());
    info.kind = "collider";
    info.collider = world.colliders()[world.body_ref(id).index];
  }
  return info;
}

}  // namespace felt
