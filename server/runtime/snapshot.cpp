#include "runtime/snapshot.hpp"

#include "core/geometry/surface_normals.hpp"

namespace felt {
namespace {

using SharedTriangles = std::shared_ptr<const std::vector<Triangle>>;

/// A solid's visible surface and where its vertices are now.
SharedTriangles solid_surface(const SolidBody& body, const SharedTriangles& previous,
                              std::vector<Vec3>& positions) {
  if (const EmbeddedSurface* fine = body.embedded_surface()) {
    fine->positions(body.positions(), body.rest().tets, positions);
    return previous ? previous : SharedTriangles(body.shared_embedded_surface(), &fine->triangles);
  }
  // the lattice's own surface over all its nodes; interior nodes are simply not referenced
  positions = body.positions();
  return previous ? previous
                  : std::make_shared<const std::vector<Triangle>>(body.topology().surface);
}

}  // namespace

std::shared_ptr<SceneSnapshot> make_snapshot(const World& world, const SceneSnapshot* previous) {
  auto snapshot = std::make_shared<SceneSnapshot>();
  snapshot->step = world.step_count();
  snapshot->sim_time = world.time();
  snapshot->bodies.reserve(world.body_count());
  for (BodyId id : world.body_ids()) {
    const BodyRef& ref = world.body_ref(id);
    if (ref.kind == BodyRef::Kind::kCollider) continue;  // nothing to see or touch
    const std::size_t at = snapshot->bodies.size();
    BodySnapshot& out = snapshot->bodies.emplace_back();
    out.body_id = id;
    if (ref.kind == BodyRef::Kind::kCloth) {
      const ClothBody& body = world.cloths()[ref.index];
      out.name = body.name();
      out.surface = SharedTriangles(body.shared_model(), &body.model().triangles);
      out.cloth = body.shared_model();
      out.positions = body.state().x;
    } else {
      const SolidBody& body = world.solids().bodies()[ref.index];
      out.name = body.name();
      const BodySnapshot* before = previous ? previous->find(id, at) : nullptr;
      out.surface = solid_surface(body, before ? before->surface : nullptr, out.positions);
      out.solid = BodySnapshot::SolidShape{body.shared_rest(), body.shared_embedded_surface(), {}};
      if (out.solid->embedded) out.solid->nodes = body.positions();
    }
    compute_vertex_normals(out.positions, out.triangles(), out.normals);
  }
  return snapshot;
}

const BodySnapshot* SceneSnapshot::find(BodyId id, std::size_t hint) const {
  if (hint < bodies.size() && bodies[hint].body_id == id) return &bodies[hint];
  for (const BodySnapshot& body : bodies) {
    if (body.body_id == id) return &body;
  }
  return nullptr;
}

}  // namespace felt
