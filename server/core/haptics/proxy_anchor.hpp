#pragma once
// Where the god-object touches the surface after its move, and the triangle it is anchored to
// until the next update: the nearest triangle within its radius plus that body's
// max_displacement, held by its placement (triangle_placement.hpp), from which the next update
// starts on that triangle as it is rendered then (surface_carry.hpp).

#include <cstddef>
#include <cstdint>
#include <optional>

#include "core/geometry/triangle_geometry.hpp"
#include "core/haptics/candidate_triangles.hpp"
#include "core/haptics/haptic_surface.hpp"

namespace felt {

/// Where the proxy sits relative to a triangle of a body (see Placement).
struct ProxyAnchor {
  std::uint32_t body_id = 0;
  std::uint32_t body = 0;  ///< index into HapticSurface::bodies when it was made
  std::uint32_t triangle = 0;
  Vec3 barycentric = Vec3::Zero();
  Vec3 offset = Vec3::Zero();

  /// The anchor's body index in `surface`, or none when its body or triangle is gone.
  std::optional<std::uint32_t> body_in(const HapticSurface& surface) const;
};

/// A candidate triangle's point nearest to the proxy.
struct NearestTriangle {
  std::size_t candidate = 0;
  ClosestPoint point;
  Real distance = 0;
};

struct Touch {
  std::optional<NearestTriangle> nearest;  ///< the triangle touched, of any shape
  std::optional<ProxyAnchor> anchor;       ///< the nearest with a frame to hold a placement
};

/// What the proxy resting at `rest` touches within `radius` (plus the skin and how far each body
/// may move before the next update, its max_displacement), and its anchor. Ties go to the lower
/// (body, triangle). Gathers into `candidates` the triangles of `surface` that far around.
Touch find_touch(const HapticSurface& surface, CandidateTriangles& candidates, const Vec3& rest,
                 Real radius, Real motion);

}  // namespace felt
