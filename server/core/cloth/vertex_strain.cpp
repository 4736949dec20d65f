#include "core/cloth/vertex_strain.hpp"

namespace felt {

void vertex_strain(const ClothModel& model, std::span<const Vec3> x, std::vector<float>& out) {
  out.assign(x.size(), 0.0f);
  std::vector<std::uint16_t> springs_at(x.size(), 0);
  for (const Spring& s : model.springs) {
    if (!is_limited(s)) continue;
    const auto strain = static_cast<float>((x[s.i] - x[s.j]).norm() / s.rest_length - 1);
    out[s.i] += strain;
    out[s.j] += strain;
    ++springs_at[s.i];
    ++springs_at[s.j];
  }
  for (std::size_t p = 0; p < out.size(); ++p) {
    if (springs_at[p] > 0) out[p] /= static_cast<float>(springs_at[p]);
  }
}

}  // namespace felt
