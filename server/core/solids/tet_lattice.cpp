#include "core/solids/tet_lattice.hpp"

#include <limits>

namespace felt {
namespace {

// Cube corners numbered by their bits (x = 1, y = 2, z = 4). In an even cell the corners with
// an odd bit count form the central tetrahedron and each even corner cuts off one with its
// three neighbours; an odd cell swaps the roles, which mirrors every face diagonal.
constexpr std::array<std::array<int, 4>, 5> kEvenCell = {{
    {1, 2, 4, 7},
    {0, 1, 2, 4},
    {3, 1, 2, 7},
    {5, 1, 4, 7},
    {6, 2, 4, 7},
}};
constexpr std::array<std::array<int, 4>, 5> kOddCell = {{
    {0, 3, 5, 6},
    {1, 0, 3, 5},
    {2, 0, 3, 6},
    {4, 0, 5, 6},
    {7, 3, 5, 6},
}};

}  // namespace

TetMesh make_cell_lattice(const LatticeGrid& grid, const std::function<bool(int, int, int)>& keep) {
  const auto [nx, ny, nz] = grid.cells;
  const auto grid_index = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(nx + 1) * (j + static_cast<std::size_t>(ny + 1) * k);
  };
  constexpr auto kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> node_of(grid_index(nx, ny, nz) + 1, kUnused);
  std::vector<std::array<int, 3>> kept;
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        if (!keep(i, j, k)) continue;
        kept.push_back({i, j, k});
        for (int c = 0; c < 8; ++c) {
          node_of[grid_index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))] = 0;
        }
      }
    }
  }

  TetMesh mesh;
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) {
        std::uint32_t& node = node_of[grid_index(i, j, k)];
        if (node == kUnused) continue;
        node = static_cast<std::uint32_t>(mesh.nodes.size());
        mesh.nodes.push_back(grid.node_position(i, j, k));
      }
    }
  }
  mesh.tets.reserve(kept.size() * 5);
  for (const auto& [i, j, k] : kept) {
    const auto& split = (i + j + k) % 2 == 0 ? kEvenCell : kOddCell;
    for (const auto& corners : split) {
      Tetrahedron t;
      for (int v = 0; v < 4; ++v) {
        const int c = corners[v];
        t[v] = node_of[grid_index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))];
      }
      mesh.tets.push_back(t);
    }
  }
  orient_positive(mesh);
  return mesh;
}

TetMesh make_box_lattice(const LatticeGrid& grid) {
  return make_cell_lattice(grid, [](int, int, int) { return true; });
}

}  // namespace felt
