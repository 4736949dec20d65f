#include "core/haptics/candidate_sweep.hpp"

#include <algorithm>

#include "core/geometry/triangle_geometry.hpp"
#include "core/haptics/proxy_skin.hpp"

namespace felt {

std::optional<CandidateHit> first_hit(const CandidateTriangles& c, const Vec3& p0, const Vec3& p1,
                                      Real radius) {
  const Aabb path = segment_box(p0, p1, radius + kProxySkin);
  const Real length = (p1 - p0).norm();
  std::optional<CandidateHit> best;
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!c.bounds(i).overlaps(path) || c.out_of_reach(i, p0, p1, length, radius)) continue;
    const TriangleCorners& t = c.corners(i);
    const std::optional<SweepHit> hit = sweep_sphere_triangle(p0, p1, radius, t.a, t.b, t.c);
    if (hit && (!best || hit->t < best->sweep.t ||
                (hit->t == best->sweep.t && c.triangle(i) < c.triangle(best->candidate))))
      best = CandidateHit{i, *hit};
  }
  return best;
}

SweepStop sweep_to(const CandidateTriangles& c, const Vec3& p0, const Vec3& p1, Real radius) {
  const std::optional<CandidateHit> hit = first_hit(c, p0, p1, radius);
  if (!hit) return {p1, hit};
  const Vec3 path = p1 - p0;
  const Real approach = -path.dot(hit->sweep.normal);
  const Real t =
      approach > 0 ? std::max(Real{0}, hit->sweep.t - kProxySkin / approach) : hit->sweep.t;
  return {p0 + t * path, hit};
}

bool touches(const CandidateTriangles& c, const Vec3& centre, Real radius) {
  const Real reach = radius + 2 * kProxySkin;
  const Aabb box = segment_box(centre, centre, reach);
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!c.bounds(i).overlaps(box) || c.distance_bound(i, centre) > reach) continue;
    const TriangleCorners& t = c.corners(i);
    const Vec3 nearest = closest_point_on_triangle(centre, t.a, t.b, t.c).point;
    if ((centre - nearest).squaredNorm() <= reach * reach) return true;
  }
  return false;
}

}  // namespace felt
