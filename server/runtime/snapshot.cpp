#include "runtime/snapshot.hpp"

#include <cmath>

#include "core/cloth/cloth_point_compliance.hpp"
#include "core/geometry/surface_normals.hpp"
#include "core/solids/solid_point_compliance.hpp"

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

/// The most nodes a body's point compliance is found for: its two sparse factorizations took
/// 33 ms for the default curtain's 400 particles, 386 ms for 1,600 and 1.07 s for the 10,000 of
/// scenes/service_bench.json (2 cores, load 4), every kComplianceRefresh; off the physics thread
/// (ComplianceWorker) that is the age of the stiffness a local model carries, and a larger
/// body keeps the fit to the pushes alone (local_model_stiffness) until it is found over the
/// nodes near the proxy only.
constexpr std::size_t kMaxComplianceNodes = 1000;

/// Gives `out` the point compliance of `before` (the same body's previous snapshot) while it is
/// recent; false when it must be found again.
bool share_compliance(const BodySnapshot* before, Real time, BodySnapshot& out) {
  if (!before || !before->compliance_time ||
      !(std::abs(time - *before->compliance_time) < kComplianceRefresh) ||
      before->surface != out.surface) {
    return false;
  }
  out.compliance = before->compliance;
  out.prompt_compliance = before->prompt_compliance;
  out.compliance_time = before->compliance_time;
  return true;
}

/// Gives `out`, body `id` of `nodes` nodes at simulated time `time`, the latest point
/// compliance `worker` found for it, after asking for a new one from `problem()` when that is
/// older than kComplianceRefresh and none is on its way (threaded, `out` keeps the older one
/// meanwhile; before the first is found, none).
template <class MakeProblem>
void find_compliance(ComplianceWorker& worker, BodyId id, Real time, std::size_t nodes,
                     const MakeProblem& problem, BodySnapshot& out) {
  std::optional<FoundCompliance> found = worker.latest(id);
  const bool recent =
      found && found->nodes == nodes && std::abs(time - found->time) < kComplianceRefresh;
  if (!recent && !worker.busy(id)) {
    if (std::optional<ComplianceProblem> asked = problem()) {
      worker.request(id, time, std::move(*asked));
      found = worker.latest(id);  // inline, already the new one
    }
  }
  if (!found || found->nodes != nodes) return;
  out.compliance = found->at_rest;
  out.prompt_compliance = found->prompt;
  out.compliance_time = found->time;
}

}  // namespace

std::shared_ptr<SceneSnapshot> make_snapshot(const World& world, const SceneSnapshot* previous,
                                             ComplianceWorker* compliance, VertexNormals normals) {
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
      const std::size_t nodes = body.model().particle_count();
      if (compliance && nodes <= kMaxComplianceNodes &&
          !share_compliance(previous ? previous->find(id, at) : nullptr, world.time(), out)) {
        find_compliance(
            *compliance, id, world.time(), nodes,
            [&] { return std::optional(compliance_problem(body)); }, out);
      }
    } else {
      const SolidBody& body = world.solids().bodies()[ref.index];
      out.name = body.name();
      const BodySnapshot* before = previous ? previous->find(id, at) : nullptr;
      out.surface = solid_surface(body, before ? before->surface : nullptr, out.positions);
      out.solid = BodySnapshot::SolidShape{body.shared_rest(), body.shared_embedded_surface(), {}};
      if (out.solid->embedded) out.solid->nodes = body.positions();
      if (compliance && body.node_count() <= kMaxComplianceNodes &&
          !share_compliance(before, world.time(), out)) {
        find_compliance(
            *compliance, id, world.time(), body.node_count(),
            [&] { return compliance_problem(body, world.colliders()); }, out);
      }
    }
    if (normals == VertexNormals::kComputed) {
      compute_vertex_normals(out.positions, out.triangles(), out.normals);
    }
  }
  return snapshot;
}

void BodySnapshot::add_load(std::uint32_t vertex, Real weight,
                            std::vector<WeightedNode>& load) const {
  if (solid && solid->embedded) {
    const EmbeddedSurface& fine = *solid->embedded;
    if (vertex >= fine.vertex_count() || fine.tet[vertex] >= solid->rest->tets.size()) return;
    const Tetrahedron& tet = solid->rest->tets[fine.tet[vertex]];
    for (int i = 0; i < 4; ++i) load.push_back({tet[i], weight * fine.weights[vertex][i]});
    return;
  }
  load.push_back({vertex, weight});
}

const BodySnapshot* SceneSnapshot::find(BodyId id, std::size_t hint) const {
  if (hint < bodies.size() && bodies[hint].body_id == id) return &bodies[hint];
  for (const BodySnapshot& body : bodies) {
    if (body.body_id == id) return &body;
  }
  return nullptr;
}

}  // namespace felt
