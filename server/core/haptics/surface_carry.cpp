#include "core/haptics/surface_carry.hpp"

#include <algorithm>
#include <cmath>

#include "core/haptics/proxy_skin.hpp"
#include "core/haptics/triangle_placement.hpp"

namespace felt {
namespace {

// Triangles tried in turn when the carry would pass the one before.
constexpr int kMaxReanchors = 2;

/// Whether `then` is `now`'s body as an earlier surface had it: the same id and surface.
bool same_body(const HapticBody& then, const HapticBody& now) {
  return then.body_id == now.body_id && then.triangles.data() == now.triangles.data() &&
         then.triangles.size() == now.triangles.size() && then.from.size() == now.from.size() &&
         then.to.size() == now.to.size();
}

Vec3 lerp(const Vec3& x0, const Vec3& x1, Real alpha) {
  return (1 - alpha) * x0 + alpha * x1;
}

/// A bound on how far any vertex of `now` (rendered at `alpha`) is from where it was in `then`
/// (rendered at `then_alpha`).
Real travel_between(const HapticBody& then, Real then_alpha, const HapticBody& now, Real alpha) {
  const Real motion = now.displacement();
  if (then.from.data() == now.from.data() && then.to.data() == now.to.data()) {
    return std::abs(alpha - then_alpha) * motion;  // the same snapshot pair
  }
  if (now.motion.chain != 0 && now.motion.chain == then.motion.chain) {
    // along the chain of pairs between them; the slack covers the sums' rounding
    const Real along = (now.motion.travelled - (1 - alpha) * motion) -
                       (then.motion.travelled - (1 - then_alpha) * then.displacement());
    const Real travel = std::abs(along) + 1e-12 * (1 + std::abs(now.motion.travelled));
    if (std::isfinite(travel)) return travel;
  }
  // unrelated snapshots (the scene went on while nobody touched it): look at every vertex
  Real largest_sq = 0;
  for (std::size_t i = 0; i < now.to.size(); ++i) {
    const Vec3 d = lerp(now.from[i], now.to[i], alpha) - lerp(then.from[i], then.to[i], then_alpha);
    if (d.allFinite()) largest_sq = std::max(largest_sq, d.squaredNorm());
  }
  return std::sqrt(largest_sq);
}

}  // namespace

void SurfaceCarry::follow(const HapticSurface& surface) {
  then_.assign(surface.bodies.size(), Then{});
  travel_.assign(surface.bodies.size(), 0);
  margin_ = 0;
  if (!previous_) return;
  const std::vector<HapticBody>& then = previous_->bodies;
  for (std::uint32_t b = 0; b < surface.bodies.size(); ++b) {
    const HapticBody& body = surface.bodies[b];
    // bodies mostly keep their places; else look for it
    std::optional<std::uint32_t> found;
    if (b < then.size() && same_body(then[b], body)) found = b;
    for (std::uint32_t i = 0; !found && i < then.size(); ++i) {
      if (same_body(then[i], body)) found = i;
    }
    if (!found) continue;  // new, or a new surface under its id: it moved onto nothing
    const HapticBody& was = then[*found];
    travel_[b] = travel_between(was, previous_->alpha, body, surface.alpha);
    if (was.from.data() == body.from.data() && was.to.data() == body.to.data()) {
      then_[b] = {&body, previous_->alpha};  // the same pair
    } else if (was.to.data() == body.from.data() && previous_->alpha == 1) {
      then_[b] = {&body, 0};  // the pair before, at its end
    } else {
      then_[b] = {&was, previous_->alpha};
    }
    margin_ = std::max(margin_, travel_[b]);
  }
}

std::optional<TriangleCorners> SurfaceCarry::previous_corners(std::uint32_t b,
                                                              std::uint32_t triangle) const {
  if (!then_[b].body) return std::nullopt;
  return then_[b].body->triangle_at(triangle, then_[b].alpha);
}

Vec3 SurfaceCarry::carry(const HapticSurface& surface, CandidateTriangles& candidates,
                         const Vec3& rest, const std::optional<ProxyAnchor>& anchor) const {
  Vec3 before = rest;
  Vec3 start = rest;
  if (anchor) {
    if (const std::optional<std::uint32_t> b = anchor->body_in(surface)) {
      const Placement placement{anchor->barycentric, anchor->offset};
      const std::optional<TriangleCorners> then = previous_corners(*b, anchor->triangle);
      const std::optional<TriangleCorners> now =
          surface.bodies[*b].triangle_at(anchor->triangle, surface.alpha);
      const std::optional<Vec3> was = then ? position_of(*then, placement) : std::nullopt;
      const std::optional<Vec3> is = now ? position_of(*now, placement) : std::nullopt;
      if (was && is) {
        before = *was;
        start = *is;
      }
    }
  }
  if (!previous_) return start;

  const Vec3 carried = start;
  for (int attempt = 0;; ++attempt) {
    // the earliest triangle the carry passes: a triangle's box now, grown by how far its body
    // moves, holds it at the previous state too
    const Aabb path = segment_box(before, start, kProxySkin);
    candidates.gather(surface, path.inflated(margin_));
    std::optional<TriangleCorners> passed;
    std::optional<std::size_t> passed_candidate;
    Real passed_at = 2;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const std::uint32_t b = candidates.body(i);
      if (!then_[b].body) continue;  // it came from nowhere: nothing to pass
      if (!candidates.bounds(i).inflated(travel_[b]).overlaps(path)) continue;
      const std::optional<TriangleCorners> was = previous_corners(b, candidates.triangle(i));
      if (!was) continue;
      const std::optional<Real> s =
          point_passes_moving_triangle(before, start, *was, candidates.corners(i));
      if (s && *s < passed_at) {
        passed_at = *s;
        passed = *was;
        passed_candidate = i;
      }
    }
    if (!passed) return start;
    if (attempt == kMaxReanchors) return carried;  // closed in from both sides: see the header
    // keep the placement it had relative to the triangle it would pass
    const std::optional<Placement> placement = place(*passed, before);
    if (!placement) return carried;
    const std::optional<Vec3> is = position_of(candidates.corners(*passed_candidate), *placement);
    if (!is) return carried;
    start = *is;
  }
}

}  // namespace felt
