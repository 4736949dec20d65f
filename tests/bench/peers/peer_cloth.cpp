#include "peer_cloth.hpp"

#include <algorithm>
#include <limits>

#include "core/math/check.hpp"

namespace felt::peers {

Vec3 rest_position(std::uint32_t n, std::uint32_t i, std::uint32_t j) {
  const Real s = kSide / static_cast<Real>(n - 1);
  return Vec3(-kSide / 2 + i * s, kSide / 2 - j * s, 0);
}

Real max_structural_strain(std::uint32_t n, std::span<const Vec3> x) {
  FELT_CHECK(x.size() == std::size_t{n} * n);
  const Real rest = kSide / static_cast<Real>(n - 1);
  Real strain = 0;
  for (std::uint32_t j = 0; j < n; ++j) {
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::size_t p = std::size_t{j} * n + i;
      if (i + 1 < n) strain = std::max(strain, (x[p] - x[p + 1]).norm() / rest - 1);
      if (j + 1 < n) strain = std::max(strain, (x[p] - x[p + n]).norm() / rest - 1);
    }
  }
  return strain;
}

Real sag_error(std::span<const Vec3> x) {
  Real lowest = std::numeric_limits<Real>::infinity();
  for (const Vec3& p : x) lowest = std::min(lowest, p.y());
  return (kSide / 2 - lowest - kSide) / kSide;
}

bool intact(Real max_strain, std::span<const Vec3> x) {
  return max_strain < kBlownUpStrain &&
         std::all_of(x.begin(), x.end(), [](const Vec3& p) { return p.allFinite(); });
}

}  // namespace felt::peers
