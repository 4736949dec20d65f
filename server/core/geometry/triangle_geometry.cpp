#include "core/geometry/triangle_geometry.hpp"

#include <algorithm>

namespace felt {
namespace {

// Below this squared sine of the angle at a, the Voronoi-region arithmetic divides rounding
// noise by rounding noise; such a triangle is treated as the segments that make it up.
constexpr Real kDegenerateSinSq = 1e-14;

/// Parameter t in [0, 1] of the point of segment a + t (b − a) nearest to p.
Real segment_parameter(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Real length_sq = (b - a).squaredNorm();
  if (length_sq == 0) return 0;
  return std::clamp((p - a).dot(b - a) / length_sq, Real{0}, Real{1});
}

/// A triangle without area: the nearest point of its three edges.
ClosestPoint closest_point_on_edges(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Real t_ab = segment_parameter(p, a, b);
  const Real t_bc = segment_parameter(p, b, c);
  const Real t_ca = segment_parameter(p, c, a);
  const ClosestPoint candidates[] = {{a + t_ab * (b - a), Vec3(1 - t_ab, t_ab, 0)},
                                     {b + t_bc * (c - b), Vec3(0, 1 - t_bc, t_bc)},
                                     {c + t_ca * (a - c), Vec3(t_ca, 0, 1 - t_ca)}};
  const ClosestPoint* best = &candidates[0];
  for (const ClosestPoint& candidate : candidates) {
    if ((p - candidate.point).squaredNorm() < (p - best->point).squaredNorm()) best = &candidate;
  }
  return *best;
}

}  // namespace

ClosestPoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  if (ab.cross(ac).squaredNorm() <= kDegenerateSinSq * ab.squaredNorm() * ac.squaredNorm()) {
    return closest_point_on_edges(p, a, b, c);
  }
  const Vec3 ap = p - a;
  const Real d1 = ab.dot(ap);
  const Real d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, Vec3(1, 0, 0)};

  const Vec3 bp = p - b;
  const Real d3 = ab.dot(bp);
  const Real d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, Vec3(0, 1, 0)};

  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const Real v = d1 / (d1 - d3);
    return {a + v * ab, Vec3(1 - v, v, 0)};
  }

  const Vec3 cp = p - c;
  const Real d5 = ab.dot(cp);
  const Real d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, Vec3(0, 0, 1)};

  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const Real w = d2 / (d2 - d6);
    return {a + w * ac, Vec3(1 - w, 0, w)};
  }

  const Real va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const Real w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), Vec3(0, 1 - w, w)};
  }

  const Real sum = va + vb + vc;
  const Real v = vb / sum;
  const Real w = vc / sum;
  return {a + v * ab + w * ac, Vec3(1 - v - w, v, w)};
}

}  // namespace felt
