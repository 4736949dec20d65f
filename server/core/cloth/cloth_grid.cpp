#include "core/cloth/cloth_grid.hpp"

#include "core/math/check.hpp"

namespace felt {

ClothModel make_grid_cloth(const GridClothSpec& spec) {
  FELT_CHECK(spec.nx >= 2 && spec.ny >= 2 && spec.width > 0 && spec.height > 0 &&
             spec.total_mass > 0);
  const std::uint32_t nx = spec.nx;
  const std::uint32_t ny = spec.ny;
  const std::size_t n = std::size_t{nx} * ny;
  auto index = [nx](std::uint32_t i, std::uint32_t j) { return j * nx + i; };

  ClothModel model;
  model.rest_positions.reserve(n);
  model.uv.reserve(n);
  model.mass.assign(n, spec.total_mass / static_cast<Real>(n));
  for (std::uint32_t j = 0; j < ny; ++j) {
    for (std::uint32_t i = 0; i < nx; ++i) {
      const Real u = static_cast<Real>(i) / (nx - 1);
      const Real v = static_cast<Real>(j) / (ny - 1);
      const Real a = (u - 0.5) * spec.width;
      const Real b = (0.5 - v) * spec.height;
      const Vec3 local = spec.plane == GridClothSpec::Plane::kXY ? Vec3(a, b, 0) : Vec3(a, 0, -b);
      model.rest_positions.push_back(spec.transform.apply(spec.center + local));
      model.uv.emplace_back(u, v);
    }
  }

  auto add = [&](std::uint32_t p, std::uint32_t q, SpringKind kind) {
    const Real rest = (model.rest_positions[p] - model.rest_positions[q]).norm();
    model.springs.push_back({p, q, rest, kind});
  };
  for (std::uint32_t j = 0; j < ny; ++j) {
    for (std::uint32_t i = 0; i < nx; ++i) {
      if (i + 1 < nx) add(index(i, j), index(i + 1, j), SpringKind::kStructural);
      if (j + 1 < ny) add(index(i, j), index(i, j + 1), SpringKind::kStructural);
      if (i + 1 < nx && j + 1 < ny) {
        add(index(i, j), index(i + 1, j + 1), SpringKind::kShear);
        add(index(i + 1, j), index(i, j + 1), SpringKind::kShear);
      }
      if (i + 2 < nx) add(index(i, j), index(i + 2, j), SpringKind::kBend);
      if (j + 2 < ny) add(index(i, j), index(i, j + 2), SpringKind::kBend);
    }
  }

  // counter-clockwise seen from +z (kXY) or +y (kXZ), so normals face the viewer
  for (std::uint32_t j = 0; j + 1 < ny; ++j) {
    for (std::uint32_t i = 0; i + 1 < nx; ++i) {
      const std::uint32_t a = index(i, j), b = index(i + 1, j);
      const std::uint32_t c = index(i, j + 1), d = index(i + 1, j + 1);
      model.triangles.push_back({a, c, b});
      model.triangles.push_back({b, c, d});
    }
  }
  return model;
}

std::vector<std::uint32_t> grid_pin_indices(const GridClothSpec& spec, GridPinPreset preset) {
  const std::uint32_t nx = spec.nx;
  const std::uint32_t last_row = (spec.ny - 1) * nx;
  switch (preset) {
    case GridPinPreset::kNone:
      return {};
    case GridPinPreset::kFourCorners:
      return {0, nx - 1, last_row, last_row + nx - 1};
    case GridPinPreset::kTopCorners:
      return {0, nx - 1};
    case GridPinPreset::kTopRow: {
      std::vector<std::uint32_t> row(nx);
      for (std::uint32_t i = 0; i < nx; ++i) row[i] = i;
      return row;
    }
  }
  return {};
}

}  // namespace felt
