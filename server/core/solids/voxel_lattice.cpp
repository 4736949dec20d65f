#include "core/solids/voxel_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/math/bounds_of.hpp"
#include "core/math/check.hpp"
#include "core/solids/tet_lattice.hpp"

namespace felt {
namespace {

// Empty cells around the covering cells, so cells added to mend the surface stay in the grid.
constexpr int kMargin = 2;
// A vertex this close to a cell face (in cells) counts as lying on it, so the rounding of a
// surface built on the cell faces (the thesis's cube) does not add cells.
constexpr Real kOnFace = 1e-9;

/// Generalized winding number of the surface around p (Jacobson et al. 2013, eq. 6): the sum of
/// the solid angles of its triangles over 4π, each angle by Van Oosterom & Strackee (1983).
/// 1 inside a closed outward surface, 0 outside, in between near holes.
Real winding_number(const Vec3& p, const TriangleMesh& surface) {
  Real solid_angle = 0;
  for (const Triangle& t : surface.triangles) {
    const Vec3 a = surface.positions[t[0]] - p;
    const Vec3 b = surface.positions[t[1]] - p;
    const Vec3 c = surface.positions[t[2]] - p;
    const Real la = a.norm(), lb = b.norm(), lc = c.norm();
    const Real numerator = a.dot(b.cross(c));
    const Real denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    solid_angle += 2 * std::atan2(numerator, denominator);
  }
  return solid_angle / (4 * std::numbers::pi);
}

/// Whether the surface of the kept octants (bit o of `mask`) of the eight cells around a
/// lattice vertex is a disc there: the kept and the empty octants are each face-connected, and
/// no four octants around one of the six half-edges from the vertex are kept diagonally
/// (octants are numbered by their bits, x = 1, y = 2, z = 4; face neighbours differ in one bit).
bool is_manifold_corner(unsigned mask) {
  const auto connected = [](unsigned set) {
    if (set == 0) return true;
    unsigned reached = set & (~set + 1);  // lowest octant of the set
    for (unsigned grown = 0; grown != reached;) {
      grown = reached;
      for (unsigned o = 0; o < 8; ++o) {
        if (!(reached >> o & 1)) continue;
        for (unsigned axis = 0; axis < 3; ++axis) reached |= (1u << (o ^ (1u << axis))) & set;
      }
    }
    return reached == set;
  };
  if (!connected(mask) || !connected(~mask & 0xffu)) return false;
  for (unsigned axis = 0; axis < 3; ++axis) {
    const unsigned u = 1u << ((axis + 1) % 3), v = 1u << ((axis + 2) % 3);
    for (unsigned side : {0u, 1u << axis}) {
      const auto kept = [&](unsigned o) { return (mask >> (side | o) & 1) != 0; };
      if (kept(0) == kept(u | v) && kept(u) == kept(v) && kept(0) != kept(u)) return false;
    }
  }
  return true;
}

class CellSet {
 public:
  explicit CellSet(const std::array<int, 3>& cells)
      : cells_(cells), kept_(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2], 0) {}

  bool inside(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < cells_[0] && j < cells_[1] && k < cells_[2];
  }
  bool kept(int i, int j, int k) const { return inside(i, j, k) && kept_[index(i, j, k)]; }
  void keep(int i, int j, int k) {
    if (inside(i, j, k)) kept_[index(i, j, k)] = 1;
  }

  /// Keeps all eight cells around every lattice vertex whose surface is not a disc, until
  /// there are none: adding cells never uncovers a fine vertex.
  void mend_non_manifold_corners() {
    std::array<bool, 256> manifold;
    for (unsigned mask = 0; mask < 256; ++mask) manifold[mask] = is_manifold_corner(mask);
    for (bool changed = true; changed;) {
      changed = false;
      for (int k = 0; k <= cells_[2]; ++k) {
        for (int j = 0; j <= cells_[1]; ++j) {
          for (int i = 0; i <= cells_[0]; ++i) {
            const unsigned before = corner_mask(i, j, k);
            if (manifold[before]) continue;
            for (unsigned o = 0; o < 8; ++o) keep(octant(i, j, k, o));
            changed = changed || corner_mask(i, j, k) != before;
          }
        }
      }
    }
  }

 private:
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(cells_[0]) * (j + static_cast<std::size_t>(cells_[1]) * k);
  }
  /// The cell in octant o of lattice vertex (i, j, k).
  static std::array<int, 3> octant(int i, int j, int k, unsigned o) {
    return {i - 1 + static_cast<int>(o & 1), j - 1 + static_cast<int>(o >> 1 & 1),
            k - 1 + static_cast<int>(o >> 2 & 1)};
  }
  void keep(const std::array<int, 3>& c) { keep(c[0], c[1], c[2]); }
  unsigned corner_mask(int i, int j, int k) const {
    unsigned mask = 0;
    for (unsigned o = 0; o < 8; ++o) {
      const auto [ci, cj, ck] = octant(i, j, k, o);
      if (kept(ci, cj, ck)) mask |= 1u << o;
    }
    return mask;
  }

  std::array<int, 3> cells_;
  std::vector<std::uint8_t> kept_;
};

}  // namespace

EmbeddedSolid voxelize_surface(const TriangleMesh& surface, int resolution) {
  FELT_CHECK(resolution >= 1);
  FELT_CHECK(!surface.triangles.empty());
  const Eigen::AlignedBox<Real, 3> bounds = bounds_of(surface.positions);
  const Real cell = bounds.sizes().maxCoeff() / resolution;
  FELT_CHECK(cell > 0);

  LatticeGrid grid;
  for (int a = 0; a < 3; ++a) {
    const int covering =
        std::max(1, static_cast<int>(std::ceil(bounds.sizes()[a] / cell - kOnFace)));
    grid.cells[a] = covering + 2 * kMargin;
  }
  grid.cell_size = Vec3::Constant(cell);
  grid.origin = bounds.center() - Vec3(grid.cells[0], grid.cells[1], grid.cells[2]) * (cell / 2);
  CellSet cells(grid.cells);

  const auto [nx, ny, nz] = grid.cells;
  for (int k = kMargin; k < nz - kMargin; ++k) {
    for (int j = kMargin; j < ny - kMargin; ++j) {
      for (int i = kMargin; i < nx - kMargin; ++i) {
        const Vec3 centre = grid.node_position(i, j, k) + Vec3::Constant(cell / 2);
        if (winding_number(centre, surface) > 0.5) cells.keep(i, j, k);
      }
    }
  }

  // a vertex on a cell face lies in the cells on both sides; it needs a new cell only when none
  // of those is kept
  for (const Vec3& p : surface.positions) {
    const Vec3 t = (p - grid.origin) / cell;
    std::array<std::array<int, 2>, 3> range;
    for (int a = 0; a < 3; ++a) {
      const int below = static_cast<int>(std::floor(t[a]));
      range[a] = {t[a] - below < kOnFace ? below - 1 : below,
                  below + 1 - t[a] < kOnFace ? below + 1 : below};
    }
    bool covered = false;
    for (int k = range[2][0]; k <= range[2][1]; ++k) {
      for (int j = range[1][0]; j <= range[1][1]; ++j) {
        for (int i = range[0][0]; i <= range[0][1]; ++i) covered = covered || cells.kept(i, j, k);
      }
    }
    if (!covered) {
      cells.keep(static_cast<int>(std::floor(t[0])), static_cast<int>(std::floor(t[1])),
                 static_cast<int>(std::floor(t[2])));
    }
  }
  cells.mend_non_manifold_corners();

  EmbeddedSolid solid;
  solid.lattice = make_cell_lattice(grid, [&](int i, int j, int k) { return cells.kept(i, j, k); });
  solid.surface = embed_surface(solid.lattice, surface);
  return solid;
}

}  // namespace felt
