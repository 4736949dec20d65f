#include "core/haptics/proxy_anchor.hpp"

#include <algorithm>
#include <utility>

#include "core/haptics/proxy_skin.hpp"
#include "core/haptics/triangle_placement.hpp"

namespace felt {
namespace {

// The distance bound may round above a true distance that ties the nearest one; this slack
// keeps such a triangle in the comparison, where ties are broken by index.
constexpr Real kBoundSlack = 1e-12;

}  // namespace

std::optional<std::uint32_t> ProxyAnchor::body_in(const HapticSurface& surface) const {
  const auto fits = [&](std::uint32_t b) {
    return surface.bodies[b].body_id == body_id && triangle < surface.bodies[b].triangles.size();
  };
  if (body < surface.bodies.size() && fits(body)) return body;
  for (std::uint32_t b = 0; b < surface.bodies.size(); ++b) {
    if (fits(b)) return b;
  }
  return std::nullopt;
}

Touch find_touch(const HapticSurface& surface, CandidateTriangles& candidates, const Vec3& rest,
                 Real radius, Real motion) {
  candidates.gather(surface, segment_box(rest, rest, radius + 2 * kProxySkin + motion));
  std::optional<NearestTriangle> nearest;
  std::optional<NearestTriangle> anchor;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const HapticBody& body = surface.bodies[candidates.body(i)];
    const Real reach = radius + 2 * kProxySkin + body.displacement();
    // one farther than the nearest anchor so far cannot be the nearest of either kind
    const Real within = anchor ? std::min(reach, anchor->distance) : reach;
    if (!candidates.bounds(i).overlaps(segment_box(rest, rest, reach)) ||
        candidates.distance_bound(i, rest) > within + kBoundSlack) {
      continue;
    }
    const TriangleCorners& c = candidates.corners(i);
    const ClosestPoint point = closest_point_on_triangle(rest, c.a, c.b, c.c);
    const Real distance = (rest - point.point).norm();
    if (!(distance <= reach)) continue;
    const auto before = [&](const std::optional<NearestTriangle>& n) {
      return !n || distance < n->distance ||
             (distance == n->distance &&
              std::pair(candidates.body(i), candidates.triangle(i)) <
                  std::pair(candidates.body(n->candidate), candidates.triangle(n->candidate)));
    };
    if (before(nearest)) nearest = NearestTriangle{i, point, distance};
    if (before(anchor) && !candidates.normal(i).isZero()) {
      anchor = NearestTriangle{i, point, distance};
    }
  }
  Touch touch{nearest, std::nullopt};
  if (anchor) {
    const std::size_t i = anchor->candidate;
    if (const std::optional<Placement> placement = place(candidates.corners(i), rest)) {
      touch.anchor = ProxyAnchor{surface.bodies[candidates.body(i)].body_id, candidates.body(i),
                                 candidates.triangle(i), placement->barycentric, placement->offset};
    }
  }
  return touch;
}

}  // namespace felt
