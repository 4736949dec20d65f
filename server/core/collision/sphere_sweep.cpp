#include "core/collision/sphere_sweep.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "core/geometry/triangle_geometry.hpp"

namespace felt {
namespace {

// Below this squared sine of the angle at a corner a triangle has no usable plane (the same
// threshold closest_point_on_triangle uses).
constexpr Real kDegenerateSinSq = 1e-14;
// A point this far outside in barycentric terms still counts as inside: a path through a
// shared edge must hit at least one of the two triangles despite rounding.
constexpr Real kInsideTolerance = 1e-9;
// Bisection steps for a root of the coplanarity cubic: 2^-60 of the interval is below rounding.
constexpr int kBisections = 60;

bool has_area(const Vec3& normal, const Vec3& ab, const Vec3& ac) {
  return normal.squaredNorm() > kDegenerateSinSq * ab.squaredNorm() * ac.squaredNorm();
}

/// Barycentric coordinates of q's projection onto the plane of (a, b, c), whose unnormalised
/// normal is `normal` (nonzero).
Vec3 plane_barycentric(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c,
                       const Vec3& normal) {
  const Real area = normal.squaredNorm();
  const Real u = (c - b).cross(q - b).dot(normal) / area;
  const Real v = (a - c).cross(q - c).dot(normal) / area;
  return {u, v, 1 - u - v};
}

bool inside(const Vec3& barycentric) {
  return barycentric.minCoeff() >= -kInsideTolerance;
}

/// Clamped to the triangle and renormalised: the tolerance must not leak into callers.
Vec3 clamp_barycentric(const Vec3& barycentric) {
  const Vec3 clamped = barycentric.cwiseMax(0);
  return clamped / clamped.sum();
}

/// The smaller root t ≥ 0 of A t² + 2 B t + C = 0 for a path that starts outside (C > 0) and
/// approaches (B < 0); in the form that does not divide by A, so a path nearly parallel to a
/// capsule's axis stays exact.
std::optional<Real> entry_time(Real a, Real b, Real c) {
  if (!(c > 0) || !(b < 0)) return std::nullopt;
  const Real discriminant = b * b - a * c;
  if (discriminant < 0) return std::nullopt;
  return c / (-b + std::sqrt(discriminant));
}

/// Keeps the earlier of two hits.
void keep_earliest(std::optional<SweepHit>& best, Real t, const Vec3& normal,
                   const Vec3& barycentric) {
  if (t < 0 || t > 1) return;
  if (!best || t < best->t) best = SweepHit{t, normal, barycentric};
}

/// Unit vector from q toward p, or `fallback` when they coincide.
Vec3 direction_or(const Vec3& p, const Vec3& q, const Vec3& fallback) {
  const Vec3 offset = p - q;
  const Real length = offset.norm();
  return length > 0 ? Vec3(offset / length) : fallback;
}

}  // namespace

std::optional<SweepHit> sweep_sphere_triangle(const Vec3& p0, const Vec3& p1, Real radius,
                                              const Vec3& a, const Vec3& b, const Vec3& c) {
  if (!p0.allFinite() || !p1.allFinite() || !a.allFinite() || !b.allFinite() || !c.allFinite() ||
      !std::isfinite(radius)) {
    return std::nullopt;
  }
  const Real r = std::max(radius, Real{0});
  const Vec3 d = p1 - p0;
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 face = ab.cross(ac);
  const bool flat = has_area(face, ab, ac);
  Vec3 face_normal = flat ? Vec3(face.normalized()) : Vec3::Zero();
  Real height = flat ? face_normal.dot(p0 - a) : 0;
  if (flat) {
    // the whole path out of reach of the triangle's plane, on one side: the common case of a
    // proxy sliding over a surface, answered before anything costlier
    const Real h1 = face_normal.dot(p1 - a);
    if ((height > r && h1 > r) || (height < -r && h1 < -r)) return std::nullopt;
  }

  // already within reach (never, farther than r from the plane): the distance along a line to
  // a convex set is convex in t, so it shrinks at the start or never
  if (!flat || std::abs(height) <= r) {
    const ClosestPoint start = closest_point_on_triangle(p0, a, b, c);
    const Vec3 from_surface = p0 - start.point;
    if (from_surface.squaredNorm() <= r * r) {
      const Real distance = from_surface.norm();
      if (distance == 0) return std::nullopt;  // on the triangle: no side to hold it on
      const Vec3 normal = from_surface / distance;
      if (d.dot(normal) < 0) return SweepHit{0, normal, start.barycentric};
      return std::nullopt;
    }
  }

  // the face, offset by r toward the side p0 is on: met inside, it is met first (until then
  // the sphere is above the offset plane, out of reach of every point of the triangle)
  if (flat) {
    if (height < 0) {
      face_normal = -face_normal;
      height = -height;
    }
    const Real approach = face_normal.dot(d);
    // height ≤ r with p0 out of reach means p0 is beside the face: the edges meet it first
    if (height > r && approach < 0) {
      const Real t = (height - r) / -approach;
      if (t <= 1) {
        const Vec3 touched = p0 + t * d - r * face_normal;
        const Vec3 barycentric = plane_barycentric(touched, a, b, c, face);
        if (inside(barycentric)) return SweepHit{t, face_normal, clamp_barycentric(barycentric)};
      }
    }
  }
  if (r == 0) return std::nullopt;  // a point meets an edge or a corner only through a face

  std::optional<SweepHit> best;

  const Vec3 fallback_normal = flat ? face_normal : Vec3(-d.normalized());
  const std::array<Vec3, 3> corners = {a, b, c};
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const Vec3& e0 = corners[i];
    const Vec3 axis = corners[j] - e0;
    const Real axis_sq = axis.squaredNorm();
    if (axis_sq == 0) continue;  // coinciding corners: their spheres answer
    // the capsule's side: the distance to the edge's line, across the axis
    const Vec3 m = p0 - e0;
    const Vec3 m_across = m - axis * (m.dot(axis) / axis_sq);
    const Vec3 d_across = d - axis * (d.dot(axis) / axis_sq);
    const std::optional<Real> t =
        entry_time(d_across.squaredNorm(), m_across.dot(d_across), m_across.squaredNorm() - r * r);
    if (!t || *t > 1) continue;
    const Real u = (m + *t * d).dot(axis) / axis_sq;
    if (u < 0 || u > 1) continue;  // beyond the edge's ends: a corner's sphere
    Vec3 barycentric = Vec3::Zero();
    barycentric[i] = 1 - u;
    barycentric[j] = u;
    const Vec3 touched = e0 + u * axis;
    keep_earliest(best, *t, direction_or(p0 + *t * d, touched, fallback_normal), barycentric);
  }
  for (int i = 0; i < 3; ++i) {
    const Vec3 m = p0 - corners[i];
    const std::optional<Real> t = entry_time(d.squaredNorm(), m.dot(d), m.squaredNorm() - r * r);
    if (!t || *t > 1) continue;
    keep_earliest(best, *t, direction_or(p0 + *t * d, corners[i], fallback_normal), Vec3::Unit(i));
  }
  return best;
}

std::optional<Real> point_passes_moving_triangle(const Vec3& p0, const Vec3& p1,
                                                 const TriangleCorners& from,
                                                 const TriangleCorners& to) {
  for (const Vec3* v : {&p0, &p1, &from.a, &from.b, &from.c, &to.a, &to.b, &to.c}) {
    if (!v->allFinite()) return std::nullopt;
  }
  const auto at = [](const Vec3& x0, const Vec3& x1, Real s) -> Vec3 {
    return (1 - s) * x0 + s * x1;  // exact at both ends
  };
  // signed volume of the point over the triangle: zero when the four are coplanar
  const auto volume = [&](Real s) {
    const Vec3 a = at(from.a, to.a, s);
    return (at(from.b, to.b, s) - a).cross(at(from.c, to.c, s) - a).dot(at(p0, p1, s) - a);
  };
  const auto passes_at = [&](Real s) {
    const Vec3 a = at(from.a, to.a, s);
    const Vec3 b = at(from.b, to.b, s);
    const Vec3 c = at(from.c, to.c, s);
    const Vec3 face = (b - a).cross(c - a);
    if (!has_area(face, b - a, c - a)) return false;
    return inside(plane_barycentric(at(p0, p1, s), a, b, c, face));
  };

  // the cubic's coefficients, for where it turns (Provot 1997)
  const Vec3 e1 = from.b - from.a;
  const Vec3 e2 = from.c - from.a;
  const Vec3 w = p0 - from.a;
  const Vec3 de1 = (to.b - to.a) - e1;
  const Vec3 de2 = (to.c - to.a) - e2;
  const Vec3 dw = (p1 - to.a) - w;
  const Vec3 n0 = e1.cross(e2);
  const Vec3 n1 = e1.cross(de2) + de1.cross(e2);
  const Vec3 n2 = de1.cross(de2);
  const Real c1 = n0.dot(dw) + n1.dot(w);
  const Real c2 = n1.dot(dw) + n2.dot(w);
  const Real c3 = n2.dot(dw);

  // cut [0, 1] where the cubic turns: between cuts it is monotone, one root at most
  std::array<Real, 4> cuts{0, 1, 1, 1};
  int count = 1;
  const auto add_cut = [&](Real s) {
    if (s > 0 && s < 1) cuts[count++] = s;
  };
  const Real qa = 3 * c3;
  const Real qb = 2 * c2;
  if (qa == 0) {
    if (qb != 0) add_cut(-c1 / qb);
  } else {
    const Real discriminant = qb * qb - 4 * qa * c1;
    if (discriminant >= 0) {
      const Real q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
      add_cut(q / qa);
      if (q != 0) add_cut(c1 / q);
    }
  }
  if (count == 3 && cuts[1] > cuts[2]) std::swap(cuts[1], cuts[2]);
  cuts[count++] = 1;

  const auto sign = [](Real x) { return (x > 0) - (x < 0); };
  Real lo = 0;
  Real f_lo = volume(0);
  int side = sign(f_lo);  // the last nonzero sign: the side the point is on
  for (int k = 1; k < count; ++k) {
    const Real hi = cuts[k];
    const Real f_hi = volume(hi);
    const int s_hi = sign(f_hi);
    if (side != 0 && s_hi != 0 && s_hi != side) {
      Real a = lo;
      Real b = hi;
      if (f_lo != 0) {
        for (int i = 0; i < kBisections && b - a > 0; ++i) {
          const Real mid = 0.5 * (a + b);
          if (sign(volume(mid)) == side) {
            a = mid;
          } else {
            b = mid;
          }
        }
      } else {
        b = lo;  // it touched the plane at the cut and came out the other side
      }
      if (passes_at(b)) return b;
    } else if (s_hi == 0 && hi == 1 && side != 0 && passes_at(1)) {
      return Real{1};  // ends on the triangle: the next update could not tell the side
    }
    if (s_hi != 0) side = s_hi;
    lo = hi;
    f_lo = f_hi;
  }
  return std::nullopt;
}

}  // namespace felt
