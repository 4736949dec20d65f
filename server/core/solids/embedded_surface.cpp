#include "core/solids/embedded_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/triangle_geometry.hpp"
#include "core/math/check.hpp"

namespace felt {
namespace {

/// The tetrahedra bucketed by the cells of a uniform grid that their bounding boxes overlap, so
/// a point is tested against the few tetrahedra near it instead of all of them.
struct TetBuckets {
  Vec3 origin = Vec3::Zero();
  Real cell = 1;
  std::array<int, 3> cells = {1, 1, 1};
  std::vector<std::uint32_t> offset;  ///< tets of cell c: tets[offset[c] .. offset[c + 1])
  std::vector<std::uint32_t> tets;

  /// The cell that contains p, or the nearest one when p is outside the grid.
  std::array<int, 3> cell_of(const Vec3& p) const {
    std::array<int, 3> c;
    for (int a = 0; a < 3; ++a) {
      const Real index = std::floor((p[a] - origin[a]) / cell);
      c[a] = static_cast<int>(std::clamp(index, Real{0}, Real(cells[a] - 1)));
    }
    return c;
  }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(cells[0]) * (j + static_cast<std::size_t>(cells[1]) * k);
  }
  std::span<const std::uint32_t> bucket(int i, int j, int k) const {
    const std::size_t c = index(i, j, k);
    return std::span(tets).subspan(offset[c], offset[c + 1] - offset[c]);
  }
};

TetBuckets bucket_tets(const TetMesh& mesh) {
  const std::size_t tet_count = mesh.tets.size();
  std::vector<Eigen::AlignedBox<Real, 3>> boxes(tet_count);
  Eigen::AlignedBox<Real, 3> bounds;
  Real mean_side = 0;
  for (std::size_t t = 0; t < tet_count; ++t) {
    for (std::uint32_t n : mesh.tets[t]) boxes[t].extend(mesh.nodes[n]);
    bounds.extend(boxes[t]);
    mean_side += boxes[t].sizes().maxCoeff() / static_cast<Real>(tet_count);
  }

  // cells about the size of a tetrahedron hold a handful each; a mesh of scattered small
  // tetrahedra gets coarser cells so the grid stays within a few cells per tetrahedron
  TetBuckets grid;
  grid.origin = bounds.min();
  grid.cell = mean_side;
  const auto cells_along = [&](Real cell) {
    std::array<int, 3> n;
    for (int a = 0; a < 3; ++a) {
      n[a] = std::max(1, static_cast<int>(std::ceil(bounds.sizes()[a] / cell)));
    }
    return n;
  };
  const Real max_cells = 8 * static_cast<Real>(tet_count);
  grid.cells = cells_along(grid.cell);
  const auto cell_count = [&] {
    return static_cast<Real>(grid.cells[0]) * grid.cells[1] * grid.cells[2];
  };
  while (cell_count() > max_cells) {
    grid.cell *= std::cbrt(cell_count() / max_cells) * 1.01;
    grid.cells = cells_along(grid.cell);
  }

  const auto for_each_cell = [&](const Eigen::AlignedBox<Real, 3>& box, auto&& visit) {
    const auto lo = grid.cell_of(box.min());
    const auto hi = grid.cell_of(box.max());
    for (int k = lo[2]; k <= hi[2]; ++k) {
      for (int j = lo[1]; j <= hi[1]; ++j) {
        for (int i = lo[0]; i <= hi[0]; ++i) visit(grid.index(i, j, k));
      }
    }
  };
  grid.offset.assign(static_cast<std::size_t>(cell_count()) + 1, 0);
  for (const auto& box : boxes) for_each_cell(box, [&](std::size_t c) { ++grid.offset[c + 1]; });
  for (std::size_t c = 1; c < grid.offset.size(); ++c) grid.offset[c] += grid.offset[c - 1];
  grid.tets.resize(grid.offset.back());
  std::vector<std::uint32_t> fill(grid.offset.begin(), grid.offset.end() - 1);
  for (std::size_t t = 0; t < tet_count; ++t) {
    for_each_cell(boxes[t],
                  [&](std::size_t c) { grid.tets[fill[c]++] = static_cast<std::uint32_t>(t); });
  }
  return grid;
}

/// Where a point sits relative to one tetrahedron.
struct Placement {
  std::uint32_t tet = 0;
  Vec4 weights = Vec4::Zero();
  Real distance = std::numeric_limits<Real>::infinity();  ///< 0 inside
  Real min_weight = -std::numeric_limits<Real>::infinity();

  /// Inside beats outside, nearer beats farther, and among the tetrahedra that contain the
  /// point the one it is deepest in wins (a point on a shared face is in both).
  bool better_than(const Placement& other) const {
    if (distance != other.distance) return distance < other.distance;
    return min_weight > other.min_weight;
  }
};

class Locator {
 public:
  explicit Locator(const TetMesh& mesh) : mesh_(mesh), grid_(bucket_tets(mesh)) {
    // the inverse edge matrix of each tetrahedron turns a point into barycentric coordinates
    inverse_edges_.reserve(mesh.tets.size());
    for (const Tetrahedron& t : mesh.tets) {
      FELT_CHECK(signed_volume(mesh.nodes, t) > 0);
      Mat3 edges;
      for (int c = 0; c < 3; ++c) edges.col(c) = mesh.nodes[t[c + 1]] - mesh.nodes[t[0]];
      inverse_edges_.push_back(edges.inverse());
    }
  }

  /// The tetrahedron that contains p or, failing that, the nearest one. Searches rings of
  /// cells outwards from p's cell and stops once no farther ring can hold a nearer tetrahedron.
  Placement locate(const Vec3& p) const {
    Placement best;
    const auto centre = grid_.cell_of(p);
    int last_ring = 0;
    for (int a = 0; a < 3; ++a) {
      last_ring = std::max({last_ring, centre[a], grid_.cells[a] - 1 - centre[a]});
    }
    for (int ring = 0; ring <= last_ring; ++ring) {
      visit_ring(centre, ring, [&](std::uint32_t t) {
        const Placement candidate = place_in(p, t);
        if (candidate.better_than(best)) best = candidate;
      });
      // every cell of the next ring lies at least `ring` whole cells away from p
      if (best.distance <= ring * grid_.cell) break;
    }
    return best;
  }

 private:
  template <typename Visit>
  void visit_ring(const std::array<int, 3>& centre, int ring, Visit&& visit) const {
    std::array<int, 3> lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(0, centre[a] - ring);
      hi[a] = std::min(grid_.cells[a] - 1, centre[a] + ring);
    }
    for (int k = lo[2]; k <= hi[2]; ++k) {
      for (int j = lo[1]; j <= hi[1]; ++j) {
        for (int i = lo[0]; i <= hi[0]; ++i) {
          const int chebyshev =
              std::max({std::abs(i - centre[0]), std::abs(j - centre[1]), std::abs(k - centre[2])});
          if (chebyshev != ring) continue;
          for (std::uint32_t t : grid_.bucket(i, j, k)) visit(t);
        }
      }
    }
  }

  Placement place_in(const Vec3& p, std::uint32_t t) const {
    const Tetrahedron& tet = mesh_.tets[t];
    const auto& x = mesh_.nodes;
    const Vec3 bcd = inverse_edges_[t] * (p - x[tet[0]]);
    Placement placement;
    placement.tet = t;
    placement.weights << 1 - bcd.sum(), bcd;
    placement.min_weight = placement.weights.minCoeff();
    if (placement.min_weight >= 0) {
      placement.distance = 0;
      return placement;
    }
    constexpr std::array<std::array<int, 3>, 4> kFaces = {
        {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}};
    for (const auto& [a, b, c] : kFaces) {
      const Vec3 nearest = closest_point_on_triangle(p, x[tet[a]], x[tet[b]], x[tet[c]]).point;
      placement.distance = std::min(placement.distance, (p - nearest).norm());
    }
    return placement;
  }

  const TetMesh& mesh_;
  TetBuckets grid_;
  std::vector<Mat3> inverse_edges_;
};

/// Per fine vertex of `surface`, the weighted sum of what its tetrahedron's nodes carry.
template <typename Value>
void interpolate(const EmbeddedSurface& surface, std::span<const Value> nodes,
                 std::span<const Tetrahedron> tets, std::vector<Value>& out) {
  out.resize(surface.vertex_count());
  for (std::size_t v = 0; v < surface.vertex_count(); ++v) {
    const Tetrahedron& t = tets[surface.tet[v]];
    const Vec4& w = surface.weights[v];
    out[v] = static_cast<Value>(w[0] * nodes[t[0]] + w[1] * nodes[t[1]] + w[2] * nodes[t[2]] +
                                w[3] * nodes[t[3]]);
  }
}

}  // namespace

void EmbeddedSurface::positions(std::span<const Vec3> nodes, std::span<const Tetrahedron> tets,
                                std::vector<Vec3>& out) const {
  interpolate(*this, nodes, tets, out);
}

void EmbeddedSurface::values(std::span<const float> node_values, std::span<const Tetrahedron> tets,
                             std::vector<float>& out) const {
  interpolate(*this, node_values, tets, out);
}

EmbeddedSurface embed_surface(const TetMesh& lattice, const TriangleMesh& fine) {
  FELT_CHECK(!lattice.tets.empty());
  const Locator locator(lattice);
  EmbeddedSurface surface;
  surface.tet.reserve(fine.positions.size());
  surface.weights.reserve(fine.positions.size());
  for (const Vec3& p : fine.positions) {
    const Placement placement = locator.locate(p);
    surface.tet.push_back(placement.tet);
    surface.weights.push_back(placement.weights);
  }
  surface.triangles = fine.triangles;
  surface.uv = fine.uv;
  return surface;
}

EmbeddedSurface embed_lattice_surface(const TetMesh& lattice, std::span<const Triangle> surface) {
  constexpr std::uint32_t kInterior = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> vertex_of(lattice.nodes.size(), kInterior);
  for (const Triangle& face : surface) {
    for (std::uint32_t node : face) vertex_of[node] = 0;
  }
  std::uint32_t count = 0;
  for (std::uint32_t& vertex : vertex_of) {
    if (vertex != kInterior) vertex = count++;
  }
  EmbeddedSurface out;
  out.lattice_own = true;
  out.tet.assign(count, kInterior);
  out.weights.assign(count, Vec4::Zero());
  for (std::size_t t = 0; t < lattice.tets.size(); ++t) {
    for (int corner = 0; corner < 4; ++corner) {
      const std::uint32_t vertex = vertex_of[lattice.tets[t][corner]];
      if (vertex == kInterior || out.tet[vertex] != kInterior) continue;
      out.tet[vertex] = static_cast<std::uint32_t>(t);
      out.weights[vertex][corner] = 1;
    }
  }
  out.triangles.reserve(surface.size());
  for (const Triangle& face : surface) {
    out.triangles.push_back({vertex_of[face[0]], vertex_of[face[1]], vertex_of[face[2]]});
  }
  return out;
}

}  // namespace felt
