#include "core/geometry/procedural_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "core/math/check.hpp"

namespace felt {
namespace {

/// Longitude and latitude of a direction, both scaled to [0, 1].
Vec2 spherical_uv(const Vec3& direction) {
  const Vec3 d = direction.normalized();
  return {0.5 + std::atan2(d.z(), d.x()) / (2 * std::numbers::pi),
          0.5 + std::asin(std::clamp(d.y(), Real{-1}, Real{1})) / std::numbers::pi};
}

}  // namespace

TriangleMesh make_torus_surface(Real major_radius, Real minor_radius, int major_segments,
                                int minor_segments) {
  FELT_CHECK(0 < minor_radius && minor_radius < major_radius);
  FELT_CHECK(major_segments >= 3 && minor_segments >= 3);
  TriangleMesh mesh;
  const auto vertex = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % major_segments) * minor_segments + j % minor_segments);
  };
  for (int i = 0; i < major_segments; ++i) {
    const Real u = 2 * std::numbers::pi * i / major_segments;
    for (int j = 0; j < minor_segments; ++j) {
      const Real v = 2 * std::numbers::pi * j / minor_segments;
      const Real ring = major_radius + minor_radius * std::cos(v);
      mesh.positions.emplace_back(ring * std::cos(u), minor_radius * std::sin(v),
                                  ring * std::sin(u));
      mesh.uv.emplace_back(Real(i) / major_segments, Real(j) / minor_segments);
    }
  }
  // stepping around the tube before stepping around the axis turns the triangles outwards
  for (int i = 0; i < major_segments; ++i) {
    for (int j = 0; j < minor_segments; ++j) {
      mesh.triangles.push_back({vertex(i, j), vertex(i, j + 1), vertex(i + 1, j + 1)});
      mesh.triangles.push_back({vertex(i, j), vertex(i + 1, j + 1), vertex(i + 1, j)});
    }
  }
  return mesh;
}

TriangleMesh make_sphere_surface(Real radius, int subdivisions) {
  FELT_CHECK(radius > 0 && subdivisions >= 0);
  const Real t = std::numbers::phi;
  TriangleMesh mesh;
  mesh.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  mesh.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint_of;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto [it, inserted] = midpoint_of.try_emplace(
          std::minmax(a, b), static_cast<std::uint32_t>(mesh.positions.size()));
      if (inserted) mesh.positions.push_back((mesh.positions[a] + mesh.positions[b]) / 2);
      return it->second;
    };
    std::vector<Triangle> finer;
    finer.reserve(4 * mesh.triangles.size());
    for (const auto& [a, b, c] : mesh.triangles) {
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.push_back({a, ab, ca});
      finer.push_back({b, bc, ab});
      finer.push_back({c, ca, bc});
      finer.push_back({ab, bc, ca});
    }
    mesh.triangles = std::move(finer);
  }
  for (Vec3& p : mesh.positions) {
    mesh.uv.push_back(spherical_uv(p));
    p = radius * p.normalized();
  }
  return mesh;
}

TriangleMesh make_box_surface(const Vec3& size, int divisions) {
  FELT_CHECK((size.array() > 0).all() && divisions >= 1);
  const int n = divisions;
  const auto grid_index = [n](const std::array<int, 3>& g) {
    return static_cast<std::size_t>(g[0]) +
           static_cast<std::size_t>(n + 1) * (g[1] + (n + 1) * g[2]);
  };
  // number the grid points on the box's surface, x fastest
  TriangleMesh mesh;
  std::vector<std::uint32_t> vertex_of(grid_index({n, n, n}) + 1);
  for (int k = 0; k <= n; ++k) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const bool on_surface = i == 0 || j == 0 || k == 0 || i == n || j == n || k == n;
        if (!on_surface) continue;
        vertex_of[grid_index({i, j, k})] = static_cast<std::uint32_t>(mesh.positions.size());
        const Vec3 p = size.cwiseProduct(Vec3(i, j, k) / n - Vec3::Constant(0.5));
        mesh.positions.push_back(p);
        mesh.uv.push_back(spherical_uv(p));
      }
    }
  }
  // the face normal to axis a spans axes b and c with e_b × e_c = e_a, so a (b, c) rectangle
  // taken counter-clockwise faces +a; the face at the low end is taken the other way round
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (const int side : {0, n}) {
      for (int u = 0; u < n; ++u) {
        for (int v = 0; v < n; ++v) {
          const auto corner = [&](int du, int dv) {
            std::array<int, 3> g;
            g[a] = side;
            g[b] = u + du;
            g[c] = v + dv;
            return vertex_of[grid_index(g)];
          };
          const std::uint32_t p00 = corner(0, 0), p10 = corner(1, 0), p11 = corner(1, 1),
                              p01 = corner(0, 1);
          if (side == n) {
            mesh.triangles.push_back({p00, p10, p11});
            mesh.triangles.push_back({p00, p11, p01});
          } else {
            mesh.triangles.push_back({p00, p11, p10});
            mesh.triangles.push_back({p00, p01, p11});
          }
        }
      }
    }
  }
  return mesh;
}

}  // namespace felt
