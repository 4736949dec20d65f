#include "runtime/vertex_scalars.hpp"

#include "core/cloth/vertex_strain.hpp"
#include "core/solids/node_volume_change.hpp"

namespace felt {

void vertex_scalars(const BodySnapshot& body, std::vector<float>& out) {
  out.clear();
  if (body.cloth) {
    vertex_strain(*body.cloth, body.positions, out);
  } else if (const auto& solid = body.solid) {
    if (!solid->embedded) {
      node_volume_change(*solid->rest, body.positions, out);
      return;
    }
    thread_local std::vector<float> at_nodes;
    node_volume_change(*solid->rest, solid->nodes, at_nodes);
    solid->embedded->values(at_nodes, solid->rest->tets, out);
  }
}

}  // namespace felt
