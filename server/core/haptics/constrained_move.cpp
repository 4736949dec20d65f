#include "core/haptics/constrained_move.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <span>
#include <utility>

#include "core/geometry/triangle_geometry.hpp"
#include "core/haptics/candidate_sweep.hpp"
#include "core/haptics/proxy_skin.hpp"
#include "core/haptics/triangle_placement.hpp"

namespace felt {
namespace {

// Sweeps per move: a corner takes four (three planes and the final slide); the rest is room for
// planes that are dropped and met again.
constexpr int kMaxMoveIterations = 8;
constexpr int kMaxPlanes = 3;
// A plane met again (rounding) has the same normal to this cosine.
constexpr Real kSamePlaneCos = 1 - 1e-12;
// A plane counts as satisfied this far on its wrong side (rounding of the projection).
constexpr Real kPlaneTolerance = 1e-3 * kProxySkin;

/// A constraint of the move: the proxy's centre must satisfy normal · x ≥ offset.
struct Plane {
  Vec3 normal;
  Real offset;
};

/// The point nearest to `goal` on the free side of every plane (at most three): the
/// Karush–Kuhn–Tucker point of the subset of planes held as equalities, tried fewest first
/// (Ruspini et al. 1997 solve the same problem). `active` gets that subset as a bit mask. None
/// when no point is free of all (planes facing each other closer than the proxy's size).
std::optional<Vec3> nearest_free_point(const Vec3& goal, std::span<const Plane> planes,
                                       unsigned& active) {
  using Normals = Eigen::Matrix<Real, 3, Eigen::Dynamic, 0, 3, kMaxPlanes>;
  using Small = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxPlanes, kMaxPlanes>;
  using SmallVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxPlanes, 1>;
  const auto count = static_cast<unsigned>(planes.size());
  for (unsigned size = 0; size <= count; ++size) {
    for (unsigned mask = 0; mask < (1u << count); ++mask) {
      if (static_cast<unsigned>(std::popcount(mask)) != size) continue;
      Normals normals(3, size);
      SmallVector rhs(size);
      for (unsigned i = 0, k = 0; i < count; ++i) {
        if (!(mask & (1u << i))) continue;
        normals.col(k) = planes[i].normal;
        rhs(k) = planes[i].offset - planes[i].normal.dot(goal);
        ++k;
      }
      Vec3 x = goal;
      if (size > 0) {
        const Small gram = normals.transpose() * normals;
        if (!(gram.determinant() > 1e-12)) continue;  // parallel planes: no single point
        const SmallVector lambda = gram.partialPivLu().solve(rhs);
        if ((lambda.array() < 0).any()) continue;  // this plane would pull, not hold
        x += normals * lambda;
      }
      bool free = x.allFinite();
      for (const Plane& plane : planes) {
        free = free && plane.normal.dot(x) >= plane.offset - kPlaneTolerance;
      }
      if (!free) continue;
      active = mask;
      return x;
    }
  }
  return std::nullopt;
}

}  // namespace

ConstrainedMove move_proxy(const HapticSurface& surface, CandidateTriangles& candidates,
                           const Vec3& start, const Vec3& goal, Real radius) {
  const auto gather = [&](const Aabb& box) { candidates.gather(surface, box); };
  std::array<Plane, kMaxPlanes> planes{};
  std::size_t count = 0;
  // a plane joins the others unless one has its normal; false when there are three already
  const auto add = [&](const Vec3& normal, const Vec3& touched) {
    const Plane plane{normal, normal.dot(touched) + radius + kProxySkin};
    for (std::size_t i = 0; i < count; ++i) {
      if (planes[i].normal.dot(normal) >= kSamePlaneCos) {
        planes[i].offset = std::max(planes[i].offset, plane.offset);
        return true;
      }
    }
    if (count == kMaxPlanes) return false;
    planes[count++] = plane;
    return true;
  };
  // what the sphere rests on within `reach` holds it (no sweep into it again), and so does a
  // surface that moved onto it: pushed out to the side its centre is on. Returns the plane of
  // what it rests on.
  const auto hold = [&](const Vec3& centre, Real reach) -> std::optional<Plane> {
    const Aabb box = segment_box(centre, centre, reach);
    gather(box);
    std::optional<std::pair<Vec3, Vec3>> resting;  // normal, touched point
    Real resting_distance = reach;
    std::uint32_t resting_id = ~0u;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (!candidates.bounds(i).overlaps(box) || candidates.distance_bound(i, centre) > reach) {
        continue;
      }
      const TriangleCorners& t = candidates.corners(i);
      const ClosestPoint nearest = closest_point_on_triangle(centre, t.a, t.b, t.c);
      const Real distance = (centre - nearest.point).norm();
      if (!(distance > 0 && distance <= reach)) continue;  // on it: no side to hold it on
      const Vec3 normal = contact_normal(centre, t, nearest);
      if (distance < radius) add(normal, nearest.point);
      if (distance < resting_distance ||
          (distance == resting_distance && candidates.triangle(i) < resting_id)) {
        resting_id = candidates.triangle(i);
        resting_distance = distance;
        resting.emplace(normal, nearest.point);
      }
    }
    if (!resting) return std::nullopt;
    add(resting->first, resting->second);
    return Plane{resting->first, resting->first.dot(resting->second) + radius + kProxySkin};
  };
  hold(start, radius + 2 * kProxySkin);
  ConstrainedMove move;
  Vec3 position = start;
  for (int iteration = 0; iteration < kMaxMoveIterations; ++iteration) {
    unsigned active = 0;
    const std::optional<Vec3> target =
        nearest_free_point(goal, std::span<const Plane>(planes.data(), count), active);
    if (!target) break;  // squeezed between planes: stay
    std::size_t kept = 0;
    for (std::size_t i = 0; i < count; ++i) {
      if (active & (1u << i)) planes[kept++] = planes[i];
    }
    count = kept;
    const Vec3 path = *target - position;
    if (path.squaredNorm() == 0) break;
    gather(segment_box(position, *target, radius + kProxySkin));
    const SweepStop stop = sweep_to(candidates, position, *target, radius);
    position = stop.position;
    if (!stop.hit) {
      if (count == 0) break;
      gather(segment_box(position, position, radius + 2 * kProxySkin));
      if (touches(candidates, position, radius)) break;
      // the planes ran on past the surface they stood for (over a convex edge, or a curved
      // surface): let go of them for what lies under the proxy now, at most as far below as
      // the slide went, and settle straight down onto it; sweeping on toward the goal instead
      // would float off the next tangent plane again
      count = 0;
      const std::optional<Plane> under = hold(position, radius + 2 * kProxySkin + path.norm());
      const Real above = under ? under->normal.dot(position) - under->offset : 0;
      if (above > 0) {
        const Vec3 down = position - above * under->normal;
        gather(segment_box(position, down, radius + kProxySkin));
        const SweepStop settled = sweep_to(candidates, position, down, radius);
        position = settled.position;
        if (settled.hit) {
          const CandidateHit& hit = *settled.hit;
          add(hit.sweep.normal, point_at(candidates.corners(hit.candidate), hit.sweep.barycentric));
        }
      }
      continue;
    }
    if (!move.first_stop) move.first_stop = position;
    const CandidateHit& hit = *stop.hit;
    const Vec3 touched = point_at(candidates.corners(hit.candidate), hit.sweep.barycentric);
    if (!add(hit.sweep.normal, touched)) break;  // a corner: nowhere left to go
  }
  move.position = position;
  if (position != goal) {
    for (std::size_t i = 0; i < count; ++i) {
      if (planes[i].normal.dot(position) - planes[i].offset <= 0.5 * kProxySkin) ++move.constraints;
    }
  }
  return move;
}

}  // namespace felt
