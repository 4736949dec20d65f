#pragma once
// Surfaces for the god-object's tests: triangle sheets moving from one snapshot to the next as
// the physics thread publishes them, grids and squares to build them from, and a device stroke.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <utility>
#include <vector>

#include "core/collision/triangle_query.hpp"
#include "core/geometry/surface_normals.hpp"
#include "core/haptics/god_object.hpp"

namespace felt::test {

/// A triangle surface moving linearly from one snapshot to the next, as the physics thread
/// would publish it: `advance` makes the newer snapshot the older one. Snapshots are shared
/// and immutable, as the runtime's are, so a proxy may keep one past `advance`.
struct Sheet {
  struct Snapshot {
    std::vector<Vec3> positions, normals;
  };

  std::uint32_t id = 0;
  std::vector<Triangle> triangles;
  std::shared_ptr<const Snapshot> older, newer;
  std::unique_ptr<TriangleQuery> query;
  SurfaceMotion motion{0, 0, 1};  ///< one chain of its own

  Sheet(std::uint32_t body_id, std::vector<Vec3> positions, std::vector<Triangle> tris)
      : id(body_id), triangles(std::move(tris)) {
    newer = snapshot(std::move(positions));
    older = newer;
    query = make_triangle_query(TriangleQueryKind::kBruteForce, triangles, newer->positions);
  }

  const std::vector<Vec3>& from() const { return older->positions; }
  const std::vector<Vec3>& to() const { return newer->positions; }

  void advance(std::vector<Vec3> next) {
    older = newer;
    newer = snapshot(std::move(next));
    query->refit(from(), to());
    motion = motion.then(from(), to());
  }

  HapticBody body() const {
    return {id, triangles, from(), to(), older->normals, newer->normals, query.get(), motion};
  }

 private:
  std::shared_ptr<const Snapshot> snapshot(std::vector<Vec3> positions) const {
    auto s = std::make_shared<Snapshot>();
    s->positions = std::move(positions);
    compute_vertex_normals(s->positions, triangles, s->normals);
    return s;
  }
};

inline HapticSurface surface_of(std::initializer_list<const Sheet*> sheets, std::uint64_t step = 1,
                                Real alpha = 1) {
  HapticSurface surface;
  auto storage = std::make_shared<std::vector<std::shared_ptr<const Sheet::Snapshot>>>();
  for (const Sheet* sheet : sheets) {
    surface.bodies.push_back(sheet->body());
    storage->push_back(sheet->older);
    storage->push_back(sheet->newer);
  }
  surface.storage = std::move(storage);
  surface.step = step;
  surface.alpha = alpha;
  return surface;
}

/// An n × n grid of vertices over [−size/2, size/2]² at height z, two triangles per cell.
struct Grid {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

inline Grid grid(std::uint32_t n, Real size, Real z) {
  Grid g;
  for (std::uint32_t j = 0; j < n; ++j) {
    for (std::uint32_t i = 0; i < n; ++i) {
      g.positions.emplace_back(size * (Real(i) / (n - 1) - 0.5), size * (Real(j) / (n - 1) - 0.5),
                               z);
    }
  }
  for (std::uint32_t j = 0; j + 1 < n; ++j) {
    for (std::uint32_t i = 0; i + 1 < n; ++i) {
      const std::uint32_t v = j * n + i;
      g.triangles.push_back({v, v + 1, v + n + 1});
      g.triangles.push_back({v, v + n + 1, v + n});
    }
  }
  return g;
}

inline std::vector<Vec3> shifted(std::vector<Vec3> positions, const Vec3& by) {
  for (Vec3& p : positions) p += by;
  return positions;
}

/// Squares given by their corners, appended as two triangles each.
inline Grid squares(std::initializer_list<std::array<Vec3, 4>> quads) {
  Grid g;
  for (const auto& q : quads) {
    const auto first = static_cast<std::uint32_t>(g.positions.size());
    g.positions.insert(g.positions.end(), q.begin(), q.end());
    g.triangles.push_back({first, first + 1, first + 2});
    g.triangles.push_back({first, first + 2, first + 3});
  }
  return g;
}

inline ProxySettings plain_settings(Real radius) {
  ProxySettings s;
  s.radius = radius;
  s.stiffness = 400;
  s.max_force = 1e6;
  s.max_force_change = 0;
  return s;
}

/// Moves the device from `a` to `b` in `updates` equal steps at 1 kHz; returns the last reply.
inline HapticContact stroke(GodObject& proxy, const HapticSurface& surface, const Vec3& a,
                            const Vec3& b, int updates) {
  HapticContact last;
  for (int i = 1; i <= updates; ++i) {
    last = proxy.update(surface, a + (b - a) * (Real(i) / updates), 1e-3);
  }
  return last;
}

}  // namespace felt::test
