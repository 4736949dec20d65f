#include "core/solids/node_volume_change.hpp"

#include <cstdint>

namespace felt {

void node_volume_change(const TetMesh& rest, std::span<const Vec3> x, std::vector<float>& out) {
  out.assign(x.size(), 0.0f);
  std::vector<std::uint16_t> tets_at(x.size(), 0);
  for (const Tetrahedron& t : rest.tets) {
    const Real rest_volume = signed_volume(rest.nodes, t);
    const auto change =
        rest_volume > 0 ? static_cast<float>(signed_volume(x, t) / rest_volume - 1) : 0.0f;
    for (std::uint32_t n : t) {
      out[n] += change;
      ++tets_at[n];
    }
  }
  for (std::size_t n = 0; n < out.size(); ++n) {
    if (tets_at[n] > 0) out[n] /= static_cast<float>(tets_at[n]);
  }
}

}  // namespace felt
