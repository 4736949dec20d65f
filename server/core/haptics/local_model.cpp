#include "core/haptics/local_model.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/geometry/triangle_geometry.hpp"
#include "core/math/aabb.hpp"
#include "core/math/bounds.hpp"

namespace felt {

LocalModel cut_local_model(const HapticSurface& surface, Real interval, const Vec3& centre,
                           Real radius, std::size_t max_triangles) {
  LocalModel model;
  const Aabb region{centre.array() - radius, centre.array() + radius};
  std::vector<std::uint32_t> near;
  std::unordered_map<std::uint32_t, std::uint32_t> vertex_slot;
  std::size_t sent = 0;
  for (const HapticBody& body : surface.bodies) {
    // the first frame after a quiet spell may come from a snapshot made without normals
    if (body.normals_to.size() != body.to.size()) continue;
    near.clear();
    body.query->collect(region, near);
    std::sort(near.begin(), near.end());
    LocalModelBody cut;
    cut.body_id = body.body_id;
    cut.vertex_count = static_cast<std::uint32_t>(body.to.size());
    cut.triangle_count = static_cast<std::uint32_t>(body.triangles.size());
    vertex_slot.clear();
    for (const std::uint32_t t : near) {
      if (t >= body.triangles.size()) continue;
      const Triangle& corners = body.triangles[t];
      if (std::max({corners[0], corners[1], corners[2]}) >= body.to.size()) continue;
      const ClosestPoint nearest = closest_point_on_triangle(
          centre, body.to[corners[0]], body.to[corners[1]], body.to[corners[2]]);
      if (!((nearest.point - centre).squaredNorm() <= radius * radius)) continue;
      if (sent == max_triangles) {
        model.truncated = true;
        break;
      }
      ++sent;
      cut.triangle_ids.push_back(t);
      cut.corners.push_back(corners);
      for (const std::uint32_t v : corners) {
        if (!vertex_slot.try_emplace(v, static_cast<std::uint32_t>(cut.vertex_ids.size())).second) {
          continue;
        }
        cut.vertex_ids.push_back(v);
        cut.positions.push_back(body.to[v]);
        cut.velocities.push_back(interval > 0 ? Vec3((body.to[v] - body.from[v]) / interval)
                                              : Vec3::Zero());
        cut.normals.push_back(body.normals_to[v]);
      }
    }
    if (!cut.triangle_ids.empty()) model.bodies.push_back(std::move(cut));
  }
  return model;
}

bool well_formed(const LocalModel& model) {
  if (!within_bounds(model.push)) return false;
  for (const LocalModelBody& body : model.bodies) {
    const std::size_t vertices = body.vertex_ids.size();
    if (body.corners.size() != body.triangle_ids.size() || body.positions.size() != vertices ||
        body.velocities.size() != vertices || body.normals.size() != vertices) {
      return false;
    }
    for (const std::uint32_t t : body.triangle_ids) {
      if (t >= body.triangle_count) return false;
    }
    for (const std::uint32_t v : body.vertex_ids) {
      if (v >= body.vertex_count) return false;
    }
    if (!(std::isfinite(body.stiffness) && body.stiffness >= 0)) return false;
    for (const Triangle& corners : body.corners) {
      for (const std::uint32_t v : corners) {
        if (v >= body.vertex_count) return false;
      }
    }
    for (std::size_t i = 0; i < vertices; ++i) {
      if (!within_bounds(body.positions[i]) || !within_bounds(body.velocities[i]) ||
          !body.normals[i].allFinite()) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace felt
