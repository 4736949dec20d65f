#pragma once
// The surfaces a haptic proxy touches, as the haptic loop sees them: each moves linearly from
// one physics snapshot to the next and is rendered at a point in between (Zhuang & Canny's
// haptic interpolation, thesis 1 §7), so a 1 kHz loop sees smooth motion from a slower step.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/collision/sphere_sweep.hpp"
#include "core/collision/triangle_query.hpp"
#include "core/haptics/surface_motion.hpp"
#include "core/math/types.hpp"

namespace felt {

struct HapticBody {
  std::uint32_t body_id = 0;
  std::span<const Triangle> triangles;
  std::span<const Vec3> from;          ///< vertex positions at the older snapshot
  std::span<const Vec3> to;            ///< at the newer one (same size)
  std::span<const Vec3> normals_from;  ///< unit vertex normals, same instants
  std::span<const Vec3> normals_to;
  /// bounds every triangle over [from, to]; never null
  const TriangleQuery* query = nullptr;
  /// how far its vertices move from `from` to `to`, and along its chain of snapshot pairs
  SurfaceMotion motion;

  /// How far a vertex moves between the snapshots: motion.max_displacement, 0 when it does not
  /// say.
  Real displacement() const;
  /// Triangle `triangle` at `alpha` between the snapshots (HapticSurface::vertex's formula),
  /// unless it is not there (a bad index, a non-finite corner).
  std::optional<TriangleCorners> triangle_at(std::uint32_t triangle, Real alpha) const;
};

struct HapticSurface {
  std::vector<HapticBody> bodies;
  /// the physics step of the newer snapshot: while it stays the same, `from` and `to` do too
  std::uint64_t step = 0;
  /// where between the snapshots the surface is rendered: 0 = from, 1 = to
  Real alpha = 1;
  /// keeps the spans' storage alive while the surface is kept: a proxy keeps the surface it
  /// rendered against until its next update. Null when the caller keeps the storage valid and
  /// unchanged that long itself.
  std::shared_ptr<const void> storage;

  /// The body with id `body_id`, or null.
  const HapticBody* find(std::uint32_t body_id) const {
    for (const HapticBody& body : bodies) {
      if (body.body_id == body_id) return &body;
    }
    return nullptr;
  }

  Vec3 vertex(const HapticBody& body, std::uint32_t i) const {
    return (1 - alpha) * body.from[i] + alpha * body.to[i];
  }
  /// The vertex normal, interpolated in time and renormalised (zero if it vanishes).
  Vec3 normal(const HapticBody& body, std::uint32_t i) const {
    const Vec3 n = (1 - alpha) * body.normals_from[i] + alpha * body.normals_to[i];
    const Real length = n.norm();
    return length > 0 ? Vec3(n / length) : Vec3::Zero();
  }
};

}  // namespace felt
