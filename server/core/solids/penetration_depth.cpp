#include "core/solids/penetration_depth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/geometry/surface_normals.hpp"
#include "core/math/check.hpp"

namespace felt {
namespace {

// Squared distance below which the 1/d² weights (6.4) stop growing, when min_depth is smaller
// (a picometre: far below any mesh, far above where the weights would overflow).
constexpr Real kWeightDistanceFloorSq = 1e-24;

// Slack on the barycentric bounds of a ray–triangle hit, so a segment through the shared edge
// of two triangles is not lost to rounding in both.
constexpr Real kEdgeSlack = 1e-12;

// A segment at a smaller sine to a triangle's plane counts as parallel: in that plane, or
// nearly, rounding alone decides where it "crosses".
constexpr Real kParallelSine = 1e-10;

// Margin, relative to the segment's length plus the largest triangle's, by which boxes are
// grown before a segment's box rules a triangle out: far more than the rounding of a hit that
// the slack and the parallel test let through (for a well-shaped triangle about 1e-5 of those
// lengths at the smallest sine the parallel test allows), so the box test does not reject a
// triangle the exact test would accept.
constexpr Real kBoxMargin = 1e-3;

struct RayTriangleHit {
  Real t = 0;
  Vec3 barycentric = Vec3::Zero();
};

/// The hit of origin + t·direction, t ∈ [0, t_max], with triangle (a, b, c) from either side
/// (Möller and Trumbore 1997). Written so that NaN never hits.
std::optional<RayTriangleHit> intersect_triangle(const Vec3& origin, const Vec3& direction,
                                                 Real t_max, const Vec3& a, const Vec3& b,
                                                 const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 p = direction.cross(ac);
  const Real det = ab.dot(p);
  // a zero det makes u infinite or NaN, which fails its test; the near-parallel test, with its
  // two square roots, waits until everything else says "hit" (most triangles a contact scans
  // are missed)
  const Real inverse = 1 / det;
  const Vec3 s = origin - a;
  const Real u = s.dot(p) * inverse;
  if (!(u >= -kEdgeSlack && u <= 1 + kEdgeSlack)) return std::nullopt;
  const Vec3 q = s.cross(ab);
  const Real v = direction.dot(q) * inverse;
  if (!(v >= -kEdgeSlack && u + v <= 1 + kEdgeSlack)) return std::nullopt;
  const Real t = ac.dot(q) * inverse;
  if (!(t >= 0 && t <= t_max)) return std::nullopt;
  // det = −direction·(ab × ac): |direction| |ab × ac| times the sine to the plane
  const Real parallel = kParallelSine * direction.norm() * ab.cross(ac).norm();
  if (!(std::abs(det) > parallel)) return std::nullopt;  // parallel, or a triangle without area
  return RayTriangleHit{t, Vec3(1 - u - v, u, v)};
}

/// Whether the boxes [lo_a, hi_a] and [lo_b, hi_b], each grown by `margin`, overlap.
bool boxes_overlap(const Vec3& lo_a, const Vec3& hi_a, const Vec3& lo_b, const Vec3& hi_b,
                   Real margin) {
  for (int k = 0; k < 3; ++k) {
    if (lo_a[k] - margin > hi_b[k] + margin || lo_b[k] - margin > hi_a[k] + margin) return false;
  }
  return true;
}

/// w_i(x) = 1 / |x − x_i|² (6.4), its distance floored.
Real weight(const Vec3& x, const Vec3& x_i, Real floor_sq) {
  return 1 / std::max((x - x_i).squaredNorm(), floor_sq);
}

}  // namespace

std::uint32_t PenetrationDepthEstimator::entry_for(std::size_t flat_node,
                                                   std::uint32_t penetrated_body) const {
  for (std::uint32_t k = first_entry_[flat_node]; k != kNone; k = next_entry_[k]) {
    if (penetrated_[k] == penetrated_body) return k;
  }
  return kNone;
}

PenetrationDepthEstimator::SurfaceHit PenetrationDepthEstimator::cast(
    std::span<const SolidBody> bodies, const CollisionSet& collisions, std::uint32_t penetrated,
    const Vec3& x, const Vec3& direction, Real t_max, std::span<const std::uint32_t> exclude,
    CachedTriangle& cache) const {
  const std::vector<Vec3>& positions = bodies[penetrated].positions();
  const std::vector<Triangle>& surface = bodies[penetrated].topology().surface;
  const auto hit = [&](std::uint32_t s) -> std::optional<RayTriangleHit> {
    const Triangle& tri = surface[s];
    return intersect_triangle(x, direction, t_max, positions[tri[0]], positions[tri[1]],
                              positions[tri[2]]);
  };

  if (cache.body == penetrated && cache.triangle < surface.size()) {
    if (const auto cached = hit(cache.triangle)) {
      return SurfaceHit{cache.triangle, cached->t, cached->barycentric};
    }
  }
  // the colliding triangles in order, those whose box the segment's box misses skipped: most
  // of them, and the nearest hit and its ties are the same as with all of them
  const Vec3 end = x + t_max * direction;
  const Vec3 lo = x.cwiseMin(end), hi = x.cwiseMax(end);
  const TriangleBoxes& boxes = triangle_boxes_[penetrated];
  const Real margin = kBoxMargin * ((hi - lo).norm() + boxes.largest);
  const std::vector<std::uint32_t>& candidates = collisions.triangles[penetrated];
  SurfaceHit nearest;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (!boxes_overlap(lo, hi, boxes.lo[c], boxes.hi[c], margin)) continue;
    const std::uint32_t s = candidates[c];
    const bool excluded = std::ranges::any_of(surface[s], [&](std::uint32_t corner) {
      return std::ranges::find(exclude, corner) != exclude.end();
    });
    if (excluded) continue;
    const auto candidate = hit(s);
    if (candidate && (nearest.triangle == kNone || candidate->t < nearest.t)) {
      nearest = SurfaceHit{s, candidate->t, candidate->barycentric};
    }
  }
  if (nearest.triangle != kNone) cache = CachedTriangle{penetrated, nearest.triangle};
  return nearest;
}

void PenetrationDepthEstimator::add_crossing_estimates(std::span<const SolidBody> bodies,
                                                       const CollisionSet& collisions,
                                                       Real weight_floor_sq) {
  for (std::uint32_t body = 0; body < bodies.size(); ++body) {
    const std::vector<Vec3>& x = bodies[body].positions();
    const std::vector<Edge>& edges = bodies[body].topology().edges;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      for (int end = 0; end < 2; ++end) {
        const std::uint32_t inside = edges[e][end];
        const std::uint32_t outside = edges[e][1 - end];
        // (a) an intersection edge per body the inside end penetrated and the other end did
        // not: an edge whose ends are in different bodies counts twice
        for (std::uint32_t k = first_entry_[node_offset_[body] + inside]; k != kNone;
             k = next_entry_[k]) {
          const std::uint32_t penetrated = penetrated_[k];
          if (entry_for(node_offset_[body] + outside, penetrated) != kNone) continue;
          ++counts_.intersection_edges;

          // (b) where the edge leaves the penetrated body: the crossing nearest the inside
          // end, the edge's own triangles excluded when a body penetrates itself
          const std::uint32_t ends[] = {inside, outside};
          const std::span<const std::uint32_t> exclude = penetrated == body
                                                             ? std::span<const std::uint32_t>(ends)
                                                             : std::span<const std::uint32_t>();
          const Vec3 along = x[outside] - x[inside];
          const SurfaceHit crossing =
              cast(bodies, collisions, penetrated, x[inside], along, 1, exclude,
                   crossing_cache_[2 * (edge_offset_[body] + e) + end]);
          if (crossing.triangle == kNone) continue;
          const std::array<Vec3, 3>& normals =
              corner_normals_of(bodies[penetrated], penetrated, crossing.triangle);
          Vec3 normal = crossing.barycentric[0] * normals[0] +
                        crossing.barycentric[1] * normals[1] + crossing.barycentric[2] * normals[2];
          const Real norm = normal.norm();
          if (!(norm > 0)) continue;  // opposite corner normals cancel: no direction here
          normal /= norm;
          ++counts_.crossings;

          // (c) the weighted sums of the border-node estimate
          const Vec3 offset = crossing.t * along;  // x_e − x_i
          const Real w = weight(x[inside] + offset, x[inside], weight_floor_sq);
          weight_sum_[k] += w;
          depth_sum_[k] += w * offset.dot(normal);
          direction_sum_[k] += w * normal;
        }
      }
    }
  }
}

void PenetrationDepthEstimator::compute_triangle_boxes(const SolidBody& body,
                                                       std::span<const std::uint32_t> triangles,
                                                       TriangleBoxes& out) {
  const std::vector<Vec3>& x = body.positions();
  const std::vector<Triangle>& surface = body.topology().surface;
  out.lo.resize(triangles.size());
  out.hi.resize(triangles.size());
  out.largest = 0;
  for (std::size_t c = 0; c < triangles.size(); ++c) {
    const Triangle& t = surface[triangles[c]];
    out.lo[c] = x[t[0]].cwiseMin(x[t[1]]).cwiseMin(x[t[2]]);
    out.hi[c] = x[t[0]].cwiseMax(x[t[1]]).cwiseMax(x[t[2]]);
    out.largest = std::max(out.largest, (out.hi[c] - out.lo[c]).norm());
  }
}

bool PenetrationDepthEstimator::finish_estimate(std::uint32_t entry, std::uint32_t round,
                                                Real min_depth) {
  if (!(weight_sum_[entry] > 0)) return false;
  // r_i = r̃_i / |r̃_i|: the division of r̃_i by the weight sum cancels in the normalisation
  const Real norm = direction_sum_[entry].norm();
  if (!(norm > 0 && std::isfinite(norm))) return false;
  direction_[entry] = direction_sum_[entry] / norm;
  const Real depth = depth_sum_[entry] / weight_sum_[entry];
  // (e) shallow depths are zero; so are negative ones, which would pull the node further in
  depth_[entry] = depth >= min_depth ? depth : 0;
  round_[entry] = round;
  return true;
}

void PenetrationDepthEstimator::propagate(std::span<const SolidBody> bodies,
                                          const CollisionSet& collisions, Real weight_floor_sq,
                                          Real min_depth) {
  for (std::uint32_t round = 0; !front_.empty(); ++round) {
    // the next front: unprocessed neighbours of the last one, inside the same body
    next_front_.clear();
    for (std::uint32_t k : front_) {
      const CollidingNode& c = collisions.nodes[k];
      for (std::uint32_t j : bodies[c.body].topology().neighbours(c.node)) {
        const std::uint32_t f = entry_for(node_offset_[c.body] + j, c.penetrated_body);
        if (f == kNone || round_[f] != kNone || queued_round_[f] == round) continue;
        queued_round_[f] = round;
        next_front_.push_back(f);
      }
    }

    // (d) each from its neighbours processed in earlier rounds only, so the result does not
    // depend on the order within the front
    std::size_t kept = 0;
    for (std::uint32_t f : next_front_) {
      const CollidingNode& c = collisions.nodes[f];
      const std::vector<Vec3>& x = bodies[c.body].positions();
      weight_sum_[f] = 0;
      depth_sum_[f] = 0;
      direction_sum_[f].setZero();
      for (std::uint32_t j : bodies[c.body].topology().neighbours(c.node)) {
        const std::uint32_t k = entry_for(node_offset_[c.body] + j, c.penetrated_body);
        if (k == kNone || round_[k] > round) continue;  // unprocessed is kNone, above any round
        const Real w = weight(x[j], x[c.node], weight_floor_sq);
        weight_sum_[f] += w;
        depth_sum_[f] += w * ((x[j] - x[c.node]).dot(direction_[k]) + depth_[k]);
        direction_sum_[f] += w * direction_[k];
      }
      if (finish_estimate(f, round + 1, min_depth)) next_front_[kept++] = f;
    }
    next_front_.resize(kept);
    counts_.propagated_nodes += kept;
    std::swap(front_, next_front_);
  }
}

const std::array<Vec3, 3>& PenetrationDepthEstimator::corner_normals_of(const SolidBody& body,
                                                                        std::uint32_t b,
                                                                        std::uint32_t triangle) {
  NormalCache& cache = normals_[b];
  if (cache.corner_stamp[triangle] != stamp_) {
    const TetTopology& topology = body.topology();
    cache.corners[triangle] = corner_normals(
        topology.surface, triangle, topology.surface_face_offset, topology.surface_face_index,
        cache.cos_crease, [&](std::uint32_t f) -> const FaceNormal& {
          if (cache.face_stamp[f] != stamp_) {
            cache.faces[f] = face_normal(body.positions(), topology.surface[f]);
            cache.face_stamp[f] = stamp_;
          }
          return cache.faces[f];
        });
    cache.corner_stamp[triangle] = stamp_;
  }
  return cache.corners[triangle];
}

void PenetrationDepthEstimator::compute(std::span<const SolidBody> bodies,
                                        const CollisionSet& collisions, Real min_depth,
                                        std::vector<PenetrationContact>& out) {
  FELT_CHECK(min_depth >= 0 && std::isfinite(min_depth));
  FELT_CHECK(collisions.triangles.size() == bodies.size());
  counts_ = PenetrationCounts{};

  node_offset_.resize(bodies.size() + 1);
  edge_offset_.resize(bodies.size() + 1);
  node_offset_[0] = edge_offset_[0] = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    node_offset_[b + 1] = node_offset_[b] + bodies[b].node_count();
    edge_offset_[b + 1] = edge_offset_[b] + bodies[b].topology().edges.size();
  }
  // the caches are hints, checked before use: only a change of size resets them
  if (crossing_cache_.size() != 2 * edge_offset_.back()) {
    crossing_cache_.assign(2 * edge_offset_.back(), CachedTriangle{});
  }
  if (contact_cache_.size() != node_offset_.back()) {
    contact_cache_.assign(node_offset_.back(), CachedTriangle{});
  }

  const std::size_t count = collisions.nodes.size();
  FELT_CHECK(count < kNone);
  first_entry_.assign(node_offset_.back(), kNone);
  next_entry_.assign(count, kNone);
  penetrated_.resize(count);
  for (std::size_t k = count; k-- > 0;) {
    const CollidingNode& c = collisions.nodes[k];
    FELT_CHECK(c.body < bodies.size() && c.penetrated_body < bodies.size());
    FELT_CHECK(c.node < bodies[c.body].node_count());
    const std::size_t flat = node_offset_[c.body] + c.node;
    next_entry_[k] = first_entry_[flat];
    first_entry_[flat] = static_cast<std::uint32_t>(k);
    penetrated_[k] = c.penetrated_body;
  }
  weight_sum_.assign(count, 0);
  depth_sum_.assign(count, 0);
  direction_sum_.assign(count, Vec3::Zero());
  depth_.assign(count, 0);
  direction_.assign(count, Vec3::Zero());
  round_.assign(count, kNone);
  queued_round_.assign(count, kNone);

  normals_.resize(bodies.size());
  if (++stamp_ == 0) {  // wrapped: no stamp may look current
    for (NormalCache& cache : normals_) {
      std::ranges::fill(cache.face_stamp, 0);
      std::ranges::fill(cache.corner_stamp, 0);
    }
    stamp_ = 1;
  }
  triangle_boxes_.resize(bodies.size());
  penetrated_bodies_.assign(bodies.size(), 0);
  for (const CollidingNode& c : collisions.nodes) penetrated_bodies_[c.penetrated_body] = 1;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!penetrated_bodies_[b]) continue;
    const std::size_t triangles = bodies[b].topology().surface.size();
    NormalCache& cache = normals_[b];
    cache.faces.resize(triangles);
    cache.corners.resize(triangles);
    cache.face_stamp.resize(triangles, 0);
    cache.corner_stamp.resize(triangles, 0);
    cache.cos_crease = std::cos(bodies[b].material().crease_angle);
    compute_triangle_boxes(bodies[b], collisions.triangles[b], triangle_boxes_[b]);
  }

  // border nodes from their intersection edges, then inward front by front
  const Real weight_floor_sq = std::max(min_depth * min_depth, kWeightDistanceFloorSq);
  add_crossing_estimates(bodies, collisions, weight_floor_sq);
  front_.clear();
  for (std::uint32_t k = 0; k < count; ++k) {
    if (weight_sum_[k] > 0 && finish_estimate(k, 0, min_depth)) front_.push_back(k);
  }
  counts_.border_nodes = front_.size();
  propagate(bodies, collisions, weight_floor_sq, min_depth);

  // (f) contact triangles: the nearest hit of x_i + t·d_i, t ∈ [0, 2]
  out.clear();
  for (std::uint32_t k = 0; k < count; ++k) {
    const CollidingNode& c = collisions.nodes[k];
    PenetrationContact contact;
    contact.body = c.body;
    contact.node = c.node;
    contact.penetrated_body = c.penetrated_body;
    contact.depth = depth_[k] * direction_[k];
    if (depth_[k] > 0) {
      const std::uint32_t self[] = {c.node};
      const std::span<const std::uint32_t> exclude = c.penetrated_body == c.body
                                                         ? std::span<const std::uint32_t>(self)
                                                         : std::span<const std::uint32_t>();
      const SurfaceHit hit =
          cast(bodies, collisions, c.penetrated_body, bodies[c.body].positions()[c.node],
               contact.depth, 2, exclude, contact_cache_[node_offset_[c.body] + c.node]);
      if (hit.triangle != kNone) {
        contact.triangle = hit.triangle;
        contact.barycentric = hit.barycentric;
        ++counts_.contact_triangles;
      }
    }
    out.push_back(contact);
  }
}

}  // namespace felt
